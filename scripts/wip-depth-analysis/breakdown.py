import csv,collections,math
rows=list(csv.DictReader(open('/tmp/wipdepth-dump.csv')))
pred=[tuple(map(float,l.split(','))) for l in open('/tmp/wipdepth-pred.csv')]
by=collections.defaultdict(list)
for i,r in enumerate(rows): by[r['trial']].append(i)
cls={}
for t,ii in by.items():
    n=len(ii); P=[(float(rows[i]['px']),float(rows[i]['pz'])) for i in ii]
    w=8  # +-0.27 s
    dirs=[];spd=[]
    for k in range(n):
        a=max(0,k-w);b=min(n-1,k+w)
        dx=P[b][0]-P[a][0];dz=P[b][1]-P[a][1];dt=(b-a)/30
        spd.append(math.hypot(dx,dz)/dt if dt>0 else 0); dirs.append(math.atan2(dx,dz))
    for k in range(n):
        a=max(0,k-w);b=min(n-1,k+w)
        d=math.remainder(dirs[b]-dirs[a],2*math.pi); rate=abs(d)/((b-a)/30)*180/math.pi if b>a else 0
        r=rows[ii[k]]
        if t=='09_12' and float(r['t'])>7.5: c='09_12 backward/sideways part'
        elif r['walking']=='0': c='not walking (before the first detected step / after the stop rule)'
        elif spd[k]<0.25: c='walking, pelvis slower than 0.25 m/s (turns on the spot, shuffles, starts/stops)'
        elif rate>45: c='walking, travel direction turning > 45 deg/s'
        else: c='walking straight'
        cls[ii[k]]=c
agg=collections.defaultdict(lambda:[0,0.0]); tot=0;N=0
sub=collections.defaultdict(lambda:[0,0.0])
for i,r in enumerate(rows):
    if float(r['t'])<0.5: continue
    for f,(zk) in enumerate(('zL','zR')):
        e=(pred[i][f]-float(r[zk]))**2; agg[cls[i]][0]+=1; agg[cls[i]][1]+=e; tot+=e; N+=1
        sub[(r['subject']=='105', cls[i])][0]+=1; sub[(r['subject']=='105', cls[i])][1]+=e
print('total RMS %.2f cm, n %d'%(100*math.sqrt(tot/N),N))
for k,(n,e) in sorted(agg.items(), key=lambda x:-x[1][1]):
    print('%-85s samples %5d (%4.1f%%)  SSE share %4.1f%%  RMS %5.1f cm'%(k,n,100*n/N,100*e/tot,100*math.sqrt(e/n)))
print('RMS without each part:')
for k in agg: print('  without %-80s %.2f cm'%(k,100*math.sqrt((tot-agg[k][1])/(N-agg[k][0]))))
print('subject 105 vs others:')
for k,(n,e) in sorted(sub.items()): print('  105' if k[0] else '  other', '%-85s n %5d RMS %.1f'%(k[1],n,100*math.sqrt(e/n)))
print('straight walking only, per-trial oracles:')
import itertools
tg=collections.defaultdict(lambda:[0.0,0.0,0.0,0])  # sxy sxx syy n
for i,r in enumerate(rows):
    if float(r['t'])<0.5 or cls[i]!='walking straight': continue
    for f,zk in enumerate(('zL','zR')):
        x=pred[i][f]; y=float(r[zk]); a=tg[r['trial']]; a[0]+=x*y;a[1]+=x*x;a[2]+=y*y;a[3]+=1
se0=sum(a[2]-2*a[0]+a[1] for a in tg.values()); seg=sum(a[2]-a[0]**2/a[1] for a in tg.values()); n=sum(a[3] for a in tg.values())
print('  RMS %.2f cm; with each trial\'s best gain %.2f cm'%(100*math.sqrt(se0/n),100*math.sqrt(seg/n)))
gains=sorted((a[0]/a[1],t) for t,a in tg.items()); print('  best gains per trial: min %.2f %s, median %.2f, max %.2f %s'%(gains[0][0],gains[0][1],gains[len(gains)//2][0],gains[-1][0],gains[-1][1]))
# error by own phase in straight walking
ph=collections.defaultdict(lambda:[0,0.0])
for i,r in enumerate(rows):
    if float(r['t'])<0.5 or cls[i]!='walking straight': continue
    for f,(zk,pk) in enumerate((('zL','pL'),('zR','pR'))):
        e=(pred[i][f]-float(r[zk]))**2; k='stance' if r[pk]=='0' else 'swing'; ph[k][0]+=1; ph[k][1]+=e
for k,(m,e) in ph.items(): print('  straight, own %s: n %d RMS %.1f cm'%(k,m,100*math.sqrt(e/m)))
