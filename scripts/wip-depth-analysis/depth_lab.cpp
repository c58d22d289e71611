// Scratch: depth mapping experiments on the dump (cross-validated by subject).
#include <legwork/wip/offline/learn.hpp>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#include <algorithm>
using namespace legwork;
struct Row { std::string trial, subject; int turning; double leg, t; int walking, lead; double since, stride, apex[2], c[2], h[2], v[2]; int ph[2]; double z[2]; double turn = 0; };
std::vector<Row> rows;
void load(const char* path) {
  std::ifstream in(path); std::string line; std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line); std::string tok; std::vector<std::string> v;
    while (std::getline(ss, tok, ',')) v.push_back(tok);
    Row r; int k = 0;
    r.trial = v[k++]; r.subject = v[k++]; r.turning = std::stoi(v[k++]); r.leg = std::stod(v[k++]); r.t = std::stod(v[k++]);
    r.walking = std::stoi(v[k++]); r.lead = std::stoi(v[k++]); r.since = std::stod(v[k++]); r.stride = std::stod(v[k++]);
    r.apex[0] = std::stod(v[k++]); r.apex[1] = std::stod(v[k++]); r.c[0] = std::stod(v[k++]); r.c[1] = std::stod(v[k++]);
    r.h[0] = std::stod(v[k++]); r.h[1] = std::stod(v[k++]); r.v[0] = std::stod(v[k++]); r.v[1] = std::stod(v[k++]);
    r.ph[0] = std::stoi(v[k++]); r.ph[1] = std::stoi(v[k++]); r.z[0] = std::stod(v[k++]); r.z[1] = std::stod(v[k++]);
    k += 3;  // px, pz, hd
    if (k < static_cast<int>(v.size())) r.turn = std::stod(v[k++]);
    rows.push_back(r);
  }
}
struct Agg { double n=0,sx=0,sy=0,sxx=0,syy=0,sxy=0,se=0; void add(double x,double y){ if(!std::isfinite(x)||!std::isfinite(y))return; n++;sx+=x;sy+=y;sxx+=x*x;syy+=y*y;sxy+=x*y;se+=(x-y)*(x-y);} 
  double r() const { double c=sxy/n-sx/n*sy/n, a=sxx/n-sx/n*sx/n, b=syy/n-sy/n*sy/n; return c/std::sqrt(a*b);} double rms() const { return std::sqrt(se/n);} };
// pred[i][f]
using Pred = std::vector<std::array<double,2>>;
void report(const char* name, const Pred& p) {
  Agg all, cls[2];
  for (size_t i = 0; i < rows.size(); ++i) { auto& r = rows[i]; if (r.t < 0.5) continue; for (int f=0;f<2;++f){ all.add(p[i][f], r.z[f]); cls[r.turning].add(p[i][f], r.z[f]); } }
  std::printf("%-40s pooled r %.3f rms %.2f | normal %.3f/%.2f | turning %.3f/%.2f  (n %.0f)\n", name, all.r(), 100*all.rms(), cls[0].r(), 100*cls[0].rms(), cls[1].r(), 100*cls[1].rms(), all.n);
}
// Per-trial amplitude as learning_samples does; returns per-row amplitude (0 if none)
std::map<std::string,double> trial_amp;
void amplitudes() {
  std::map<std::string,std::vector<double>> d;
  for (auto& r : rows) if (r.walking && r.lead >= 0 && r.t >= 0.5) for (int f=0;f<2;++f) d[r.trial].push_back(r.z[f]/r.leg);
  for (auto& [t,v] : d) { std::sort(v.begin(), v.end()); auto at=[&](double p){return v[(size_t)(p*(v.size()-1))];}; trial_amp[t] = 0.5*(at(0.95)-at(0.05)); }
}
std::vector<std::string> subjects() { std::set<std::string> s; for (auto& r: rows) s.insert(r.subject); return {s.begin(), s.end()}; }
std::vector<wip::LearnSample> samples_of(const std::string& excl) {
  std::vector<wip::LearnSample> out;
  for (auto& r : rows) { if (r.subject == excl || !r.walking || r.lead < 0 || r.t < 0.5) continue; double a = trial_amp[r.trial]; if (!(a > 1e-3)) continue;
    for (int f=0;f<2;++f) out.push_back({r.c[f], r.c[1-f], r.lead==f?1:0, r.since, 0.5*(r.apex[0]+r.apex[1]), 1/r.stride, r.z[f]/r.leg, a, r.turn}); }
  return out;
}
Pred baseline_table() {
  Pred p(rows.size(), {0,0});
  for (auto& s : subjects()) {
    auto tab = wip::build_learned_mapping(samples_of(s));
    for (size_t i=0;i<rows.size();++i) { auto& r=rows[i]; if (r.subject!=s || !r.walking) continue;
      for (int f=0;f<2;++f) { int lead = r.lead<0?-1:r.lead==f?1:0; p[i][f] = r.leg*tab.depth(r.c[f], r.c[1-f], lead, r.since, 0.5*(r.apex[0]+r.apex[1]), 1/r.stride, r.turn); } }
  }
  return p;
}
void breakdown(const Pred& p) {
  // SSE shares
  double tot=0; std::map<std::string,double> part; std::map<std::string,double> cnt;
  auto add=[&](const std::string& k,double e){part[k]+=e;cnt[k]++;};
  for (size_t i=0;i<rows.size();++i){auto& r=rows[i]; if(r.t<0.5)continue; for(int f=0;f<2;++f){ double e=(p[i][f]-r.z[f]); e*=e; tot+=e;
    add(std::string(r.turning?"turning":"normal"),e); add(std::string(r.walking?"walking":"not walking"),e);
    add(std::string(r.ph[f]==0?"own stance (detected)":"own swing (detected)"),e);
    add("subject "+r.subject,e); } }
  std::printf("SSE share / RMS by part (total RMS %.2f cm):\n", 100*std::sqrt(tot/cnt["normal"]/1 /1 ) );
  double n=0; for(auto&[k,v]:cnt) if(k=="normal"||k=="turning") n+=v;
  std::printf("  total RMS %.2f cm over %.0f\n", 100*std::sqrt(tot/n), n);
  for (auto& [k,v] : part) std::printf("  %-28s share %5.1f %%  RMS %.2f cm  n %.0f\n", k.c_str(), 100*v/tot, 100*std::sqrt(v/cnt[k]), cnt[k]);
}
// oracles per trial: best gain (through origin of the mean-removed?) / best offset / best gain+offset / best shift
void oracles(const Pred& p) {
  std::map<std::string,std::vector<size_t>> idx; for(size_t i=0;i<rows.size();++i) if(rows[i].t>=0.5) idx[rows[i].trial].push_back(i);
  Agg g, o, go, sh, gsh;
  for (auto& [t, ii] : idx) {
    double sxx=0,sxy=0,sx=0,sy=0,n=0;
    for (auto i: ii) for(int f=0;f<2;++f){double x=p[i][f],y=rows[i].z[f]; sxx+=x*x;sxy+=x*y;sx+=x;sy+=y;n++;}
    double gain = sxy/sxx, off=(sy-sx)/n;
    double b = (sxy/n - sx/n*sy/n)/(sxx/n-sx/n*sx/n), a = sy/n - b*sx/n;
    for (auto i: ii) for(int f=0;f<2;++f){double x=p[i][f],y=rows[i].z[f]; g.add(gain*x,y); o.add(x+off,y); go.add(a+b*x,y);}
    // best shift -10..10 frames (pred shifted in time), within trial
    double best=1e18; int bs=0;
    for (int s=-10;s<=10;++s){ double e=0; int m=0; for(size_t k=0;k<ii.size();++k){ long j=(long)k+s; if(j<0||j>=(long)ii.size())continue; for(int f=0;f<2;++f){double d=p[ii[j]][f]-rows[ii[k]].z[f]; e+=d*d;m++;}} if(e/m<best){best=e/m;bs=s;} }
    for(size_t k=0;k<ii.size();++k){ long j=std::clamp((long)k+bs,0L,(long)ii.size()-1); for(int f=0;f<2;++f) sh.add(p[ii[j]][f], rows[ii[k]].z[f]); }
  }
  std::printf("oracle per-trial gain: r %.3f rms %.2f | offset: %.3f/%.2f | gain+offset: %.3f/%.2f | time shift: %.3f/%.2f\n", g.r(),100*g.rms(),o.r(),100*o.rms(),go.r(),100*go.rms(),sh.r(),100*sh.rms());
}
// derived causal timing features per row
std::vector<std::array<double,2>> since_own_strike, since_own_off;
void timing() {
  since_own_strike.assign(rows.size(), {9,9}); since_own_off.assign(rows.size(), {9,9});
  for (size_t i=0;i<rows.size();++i) for(int f=0;f<2;++f){
    bool first = i==0 || rows[i-1].trial!=rows[i].trial;
    double dt = first?0:rows[i].t-rows[i-1].t;
    double ss = first?9:since_own_strike[i-1][f]+dt, so = first?9:since_own_off[i-1][f]+dt;
    if(!first && rows[i-1].ph[f]!=0 && rows[i].ph[f]==0) ss=0;
    if(!first && rows[i-1].ph[f]==0 && rows[i].ph[f]!=0) so=0;
    since_own_strike[i][f]=std::min(ss,9.0); since_own_off[i][f]=std::min(so,9.0);
  }
}
void report_excl(const char* name, const Pred& p, const std::string& excl) {
  Agg all, cls[2];
  for (size_t i = 0; i < rows.size(); ++i) { auto& r = rows[i]; if (r.t < 0.5 || r.trial==excl) continue; for (int f=0;f<2;++f){ all.add(p[i][f], r.z[f]); cls[r.turning].add(p[i][f], r.z[f]); } }
  std::printf("%-40s pooled r %.3f rms %.2f | normal %.3f/%.2f | turning %.3f/%.2f  (n %.0f) without %s\n", name, all.r(), 100*all.rms(), cls[0].r(), 100*cls[0].rms(), cls[1].r(), 100*cls[1].rms(), all.n, excl.c_str());
}
using Feat = std::function<std::vector<double>(size_t i, int f)>;
// kNN regression of z/leg (or z/amp) cross-validated by subject; predicts for walking rows only
Pred knn(const Feat& feat, int k, bool walking_only=true) {
  Pred p(rows.size(), {0,0});
  std::vector<std::vector<double>> X; std::vector<double> Y; std::vector<std::string> S; 
  for (size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(!r.walking||r.t<0.5) continue; for(int f=0;f<2;++f){ X.push_back(feat(i,f)); Y.push_back(r.z[f]/r.leg); S.push_back(r.subject);} }
  for (size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(walking_only && !r.walking) continue; for(int f=0;f<2;++f){
    auto x=feat(i,f); std::vector<std::pair<double,int>> best; best.reserve(k+1);
    for(size_t j=0;j<X.size();++j){ if(S[j]==r.subject) continue; double d=0; for(size_t q=0;q<x.size();++q){double e=x[q]-X[j][q]; d+=e*e;}
      if((int)best.size()<k||d<best.back().first){ best.push_back({d,(int)j}); std::sort(best.begin(),best.end()); if((int)best.size()>k) best.pop_back(); } }
    double s=0; for(auto&b:best) s+=Y[b.second]; p[i][f]=r.leg*s/best.size(); } }
  return p;
}
int main(int argc, char** argv) {
  load(argc>1?argv[1]:"/tmp/wipdepth-dump.csv"); amplitudes();
  std::string mode = argc>2?argv[2]:"base";
  Pred zero(rows.size(), {0,0}); report("zero", zero);
  Pred base = baseline_table(); report("table (cv by subject)", base);
  breakdown(base); oracles(base);
  { std::map<std::string,Agg> pt; for(size_t i=0;i<rows.size();++i){ if(rows[i].t<0.5)continue; for(int f=0;f<2;++f) pt[rows[i].trial].add(base[i][f],rows[i].z[f]); }
    for(auto&[t,a]:pt) std::printf("  trial %s r %.2f rms %.1f\n", t.c_str(), a.r(), 100*a.rms()); }
  { FILE* o=std::fopen("/tmp/wipdepth-trial.csv","w"); for(size_t i=0;i<rows.size();++i) if(rows[i].trial==(getenv("TR")?getenv("TR"):"09_12")) std::fprintf(o,"%.3f,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n",rows[i].t,rows[i].walking,rows[i].ph[0],rows[i].ph[1],rows[i].h[0],rows[i].h[1],base[i][0],rows[i].z[0],base[i][1],rows[i].z[1]); std::fclose(o);}
  { FILE* o=std::fopen("/tmp/wipdepth-pred.csv","w"); for(size_t i=0;i<rows.size();++i) std::fprintf(o,"%.5f,%.5f\n",base[i][0],base[i][1]); std::fclose(o); }
  timing();
  report_excl("table", base, "09_12");
  std::string m2 = argc>2?argv[2]:"";
  // last swing apex per foot (causal): max h over the current/last swing
  std::vector<std::array<double,2>> last_apex(rows.size(), {0,0});
  for (size_t i=0;i<rows.size();++i) for(int f=0;f<2;++f){ bool first = i==0 || rows[i-1].trial!=rows[i].trial; double a = first?rows[i].apex[f]:last_apex[i-1][f];
    if(rows[i].ph[f]!=0){ bool start = first || rows[i-1].ph[f]==0; a = start? rows[i].h[f] : std::max(a, rows[i].h[f]); } last_apex[i][f]=a; }
  std::vector<double> nsteps(rows.size(),0);
  for (size_t i=0;i<rows.size();++i){ bool first = i==0 || rows[i-1].trial!=rows[i].trial; double c = first?0:nsteps[i-1]; if(!rows[i].walking) c=0; else for(int f=0;f<2;++f) if(!first && rows[i-1].ph[f]==0 && rows[i].ph[f]!=0) c+=1; nsteps[i]=c; }
  const char* qn[] = {"mean of both feet's last apex / estimate", "min", "own foot", "lead foot (landed last)", "max", "steps since walking started"};
  for (int qv=0; qv<6; ++qv) {
    auto q=[&](size_t i,int f){ auto& r=rows[i]; double a0=last_apex[i][0]/std::max(r.apex[0],0.03), a1=last_apex[i][1]/std::max(r.apex[1],0.03);
      if (qv==5) return std::min(nsteps[i],6.0)/4.0;
      double v = qv==0?0.5*(a0+a1): qv==1?std::min(a0,a1): qv==2?(f?a1:a0): qv==3?(r.lead<0?0.5*(a0+a1):(r.lead?a1:a0)) : std::max(a0,a1); return std::clamp(v,0.0,1.5); };
    const int B=6; Pred pg(rows.size(), {0,0});
    for (auto& s : subjects()) {
      double sxy[B+1]={0}, sxx[B+1]={0};
      auto bin=[&](double v,int& b,double& w){ double x=v/1.5*B; b=std::min((int)x,B-1); w=x-b; };
      for(size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject==s||!r.walking||r.t<0.5) continue; for(int f=0;f<2;++f){ int b; double w; bin(q(i,f),b,w); double x=base[i][f], y=r.z[f];
        sxy[b]+=(1-w)*x*y; sxx[b]+=(1-w)*x*x; sxy[b+1]+=w*x*y; sxx[b+1]+=w*x*x; } }
      double g[B+1]; for(int b=0;b<=B;++b) g[b]= sxx[b]>1e-9? sxy[b]/sxx[b] : 1;
      if (s=="16") { std::printf("  gains (fold 16) by q/%d:", B); for(int b=0;b<=B;++b) std::printf(" %.2f", g[b]); std::printf("\n"); }
      for(size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject!=s) continue; for(int f=0;f<2;++f){ int b; double w; bin(q(i,f),b,w); pg[i][f]=base[i][f]*((1-w)*g[b]+w*g[b+1]); } }
    }
    report(qn[qv], pg); report_excl(qn[qv], pg, "09_12");
  }
  if (m2=="knn") {
    Feat f1=[&](size_t i,int f){ auto& r=rows[i]; return std::vector<double>{r.c[f], r.c[1-f], r.lead<0?0.5:(r.lead==f?1.0:0.0), std::min(r.since,1.2)}; };
    auto p1=knn(f1, 20); report("knn table features", p1); report_excl("knn table features", p1, "09_12");
    Feat f2=[&](size_t i,int f){ auto& r=rows[i]; return std::vector<double>{r.c[f], r.c[1-f], r.lead<0?0.5:(r.lead==f?1.0:0.0), std::min(r.since,1.2), std::min(since_own_strike[i][f],1.5), std::min(since_own_off[i][f],1.5), std::min(since_own_strike[i][1-f],1.5), std::min(since_own_off[i][1-f],1.5)}; };
    auto p2=knn(f2, 20); report("knn + own/other timing", p2); report_excl("knn + own/other timing", p2, "09_12"); breakdown(p2);
  }
  {  // standing (not walking) frames: the table's pause entries, or a constant learned standing depth
    Pred ps = base, pc = base;
    for (auto& s : subjects()) {
      auto tab = wip::build_learned_mapping(samples_of(s));
      double sum=0; int n=0; for(auto& r:rows) if(r.subject!=s && !r.walking && r.t>=0.5) for(int f=0;f<2;++f){ sum+=r.z[f]/r.leg; n++; }
      for (size_t i=0;i<rows.size();++i) { auto& r=rows[i]; if (r.subject!=s || r.walking) continue;
        for (int f=0;f<2;++f) { int lead = r.lead<0?-1:r.lead==f?1:0; ps[i][f] = r.leg*tab.depth(r.c[f], r.c[1-f], lead, r.since, 0.5*(r.apex[0]+r.apex[1]), 1/r.stride, r.turn); pc[i][f] = r.leg*sum/n; } }
    }
    report("standing: table", ps); report("standing: constant", pc);
  }
  // Amplitude with the running swing fraction (duty factor) as a third predictor.
  for (double tau : {1.0, 2.0, 4.0}) {
    std::vector<double> sf(rows.size(), 0.3);
    for (size_t i=0;i<rows.size();++i){ bool first = i==0 || rows[i-1].trial!=rows[i].trial; double v = first?0.3:sf[i-1];
      double dt = first?0:rows[i].t-rows[i-1].t; if (rows[i].walking) { double x = 0.5*((rows[i].ph[0]!=0)+(rows[i].ph[1]!=0)); v += (x-v)*(1-std::exp(-dt/tau)); } sf[i]=v; }
    Pred pa(rows.size(), {0,0});
    std::map<std::string,double> tcount; for (auto& r : rows) if (r.walking && r.lead>=0 && r.t>=0.5) tcount[r.trial]+=1;
    for (auto& s : subjects()) {
      auto tab = wip::build_learned_mapping(samples_of(s));
      // LS: amp ~ 1, apex, cadence, sf over training samples (walking, lead known)
      double A[4][4]={{0}}, B[4]={0}, lo=1e9, hi=-1e9;
      for (size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject==s||!r.walking||r.lead<0||r.t<0.5) continue; double a=trial_amp[r.trial]; if(!(a>1e-3)) continue;
        double x[4]={1, 0.5*(r.apex[0]+r.apex[1]), 1/r.stride, sf[i]}; double wt = tcount[r.trial] > 0 ? 1.0/tcount[r.trial] : 0; for(int u=0;u<4;++u){ B[u]+=wt*x[u]*a; for(int w=0;w<4;++w) A[u][w]+=wt*x[u]*x[w]; } lo=std::min(lo,a); hi=std::max(hi,a); }
      // solve 4x4 (Gauss)
      double M[4][5]; for(int u=0;u<4;++u){ for(int w=0;w<4;++w) M[u][w]=A[u][w]; M[u][4]=B[u]; }
      for(int c=0;c<4;++c){ int piv=c; for(int u=c+1;u<4;++u) if(std::abs(M[u][c])>std::abs(M[piv][c])) piv=u; for(int w=0;w<5;++w) std::swap(M[c][w],M[piv][w]);
        for(int u=0;u<4;++u) if(u!=c){ double f=M[u][c]/M[c][c]; for(int w=0;w<5;++w) M[u][w]-=f*M[c][w]; } }
      double co[4]; for(int u=0;u<4;++u) co[u]=M[u][4]/M[u][u];
      if (s=="105") std::printf("  tau %.0f fold 105 amp = %.3f + %.3f apex + %.3f cadence + %.3f swing fraction\n", tau, co[0],co[1],co[2],co[3]);
      for (size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject!=s||!r.walking) continue;
        double amp = std::clamp(co[0]+co[1]*0.5*(r.apex[0]+r.apex[1])+co[2]/r.stride+co[3]*sf[i], lo, hi);
        for(int f=0;f<2;++f){ int lead = r.lead<0?-1:r.lead==f?1:0; pa[i][f] = r.leg*amp*tab.lookup(r.c[f], r.c[1-f], lead, r.since); }
        if (tau==2.0 && (r.trial=="07_10"||r.trial=="105_24"||r.trial=="16_13") && std::fmod(r.t,1.0)<0.034) std::printf("   %s t %.1f amp new %.3f old %.3f true %.3f sf %.2f [%g %g]\n", r.trial.c_str(), r.t, amp, tab.amplitude(0.5*(r.apex[0]+r.apex[1]),1/r.stride), trial_amp[r.trial], sf[i], lo, hi); }
    }
    char nm[64]; std::snprintf(nm, sizeof nm, "amp + swing fraction tau %.0f", tau); report(nm, pa); report_excl(nm, pa, "09_12");
    if (tau == 1.0) {
      // then a gain over the steps since walking started (fitted on these predictions), then a constant standing depth
      const int B=6; Pred pg = pa;
      for (auto& s : subjects()) {
        double sxy[B+1]={0}, sxx[B+1]={0};
        auto bin=[&](double v,int& b,double& w){ double x=std::min(v,6.0)/4.0/1.5*B; b=std::min((int)x,B-1); w=x-b; };
        for(size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject==s||!r.walking||r.t<0.5) continue; for(int f=0;f<2;++f){ int b; double w; bin(nsteps[i],b,w); double x=pa[i][f], y=r.z[f];
          sxy[b]+=(1-w)*x*y; sxx[b]+=(1-w)*x*x; sxy[b+1]+=w*x*y; sxx[b+1]+=w*x*x; } }
        double g[B+1]; for(int b=0;b<=B;++b) g[b]= sxx[b]>1e-9? sxy[b]/sxx[b] : 1;
        double sum=0; int n=0; for(auto& r:rows) if(r.subject!=s && !r.walking && r.t>=0.5) for(int f=0;f<2;++f){ sum+=r.z[f]/r.leg; n++; }
        for(size_t i=0;i<rows.size();++i){ auto& r=rows[i]; if(r.subject!=s) continue; for(int f=0;f<2;++f){ int b; double w; bin(nsteps[i],b,w); pg[i][f]= r.walking ? pa[i][f]*((1-w)*g[b]+w*g[b+1]) : r.leg*sum/n; } }
      }
      report("amp+sf, steps gain, standing const", pg); report_excl("amp+sf, steps gain, standing const", pg, "09_12"); breakdown(pg); oracles(pg);
    }
  }
  // oracle: truth-amplitude per trial with table shape
  return 0;
}
