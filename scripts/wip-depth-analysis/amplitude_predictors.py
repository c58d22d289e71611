import csv,collections,math
rows=list(csv.DictReader(open('/tmp/wipdepth-dump.csv')))
by=collections.defaultdict(list)
for r in rows: by[r['trial']].append(r)
data=[]
for t,v in by.items():
    zs=sorted([float(r['zL'])/float(r['leg']) for r in v if r['walking']=='1' and float(r['t'])>=.5]+[float(r['zR'])/float(r['leg']) for r in v if r['walking']=='1' and float(r['t'])>=.5])
    if len(zs)<20: continue
    amp=0.5*(zs[int(.95*(len(zs)-1))]-zs[int(.05*(len(zs)-1))])
    W=[r for r in v if r['walking']=='1' and float(r['t'])>=.5]
    apex=sum(float(r['apexL'])+float(r['apexR']) for r in W)/2/len(W)
    cad=sum(1/float(r['stride']) for r in W)/len(W)
    swing=sum((r['pL']!='0')+(r['pR']!='0') for r in W)/2/len(W)
    # swing durations
    durs=[]
    for f in 'LR':
        run=0
        for r in v:
            if r['p'+f]!='0': run+=1
            elif run: durs.append(run/30); run=0
    sd=sum(durs)/len(durs) if durs else float('nan')
    leg=float(v[0]['leg'])
    vpk=max(float(r['vL']) for r in W)
    data.append((t,amp,apex/leg,cad,swing,sd,leg,apex))
def corr(a,b):
    n=len(a);ma=sum(a)/n;mb=sum(b)/n
    return sum((x-ma)*(y-mb) for x,y in zip(a,b))/math.sqrt(sum((x-ma)**2 for x in a)*sum((y-mb)**2 for y in b))
amp=[d[1] for d in data]
for k,name in [(2,'apex/leg'),(3,'cadence'),(4,'swing fraction'),(5,'swing duration'),(6,'leg'),(7,'apex m')]:
    print('%-16s r with amplitude/leg: %.2f'%(name,corr(amp,[d[k] for d in data])))
for d in sorted(data,key=lambda d:d[1])[::6]: print(d[0],'amp %.3f apex/leg %.3f cad %.2f swingfrac %.2f swingdur %.2f'%d[1:6])
