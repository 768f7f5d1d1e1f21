"""Summary of bench/arches/min_flight.csv over the far-field records: per variant (dt,
min_flight) the median events and CPU, runs under 0.1 s, collapses (and the records whose verdict
differs from the dt = 0.25 ms default), and |peak / peak(dt = 0.25 ms default) − 1| over the
records that rock without collapse (median, 75th and 90th percentiles) with the mean log ratio.

python3 bench/arches/min_flight_summary.py bench/arches/min_flight.csv
"""
import sys,collections,statistics as st
rows=[l.strip().split(',') for l in open(sys.argv[1]) if l.count(',')==8 and not l.startswith('record,')]
rows=[r for r in rows if r[0]!='bundled']
D=collections.defaultdict(dict)
for r in rows:
    D[r[0]][(r[1],r[2])]=dict(col=r[3]=='True',t=float(r[4]),peak=float(r[5]),ev=int(r[6]),cl=int(r[7]),cpu=float(r[8]))
ref=('2.5e-4','0')
vs=[('9.99e-4','0'),('1.001e-3','0'),('1e-3','0'),('1e-3','1'),('1e-3','1.5'),('1e-3','2'),('1e-3','3'),('1e-3','4'),('5e-4','0'),('5e-4','1'),('5e-4','2'),('5e-4','4'),ref]
def q(xs,p): xs=sorted(xs); return xs[min(len(xs)-1,int(p*len(xs)))]
print('variant(dt,min_flight) | events median | CPU median (s) | CPU sum | under 0.1 s | collapses (verdicts differing from dt/4) | |peak/peak_ref-1| median, 75%, 90% over rocking records | log-mean ratio')
import math
for v in vs:
    R=[(k,d[v],d[ref]) for k,d in D.items()]
    col=sum(x['col'] for _,x,_ in R); diffv=[k for k,x,r in R if x['col']!=r['col']]
    e=[abs(x['peak']/r['peak']-1) for k,x,r in R if not x['col'] and not r['col'] and r['peak']>0]
    lm=st.mean([math.log(x['peak']/r['peak']) for k,x,r in R if not x['col'] and not r['col'] and r['peak']>0])
    print(v, st.median([x['ev'] for _,x,_ in R]), '%.3f'%st.median([x['cpu'] for _,x,_ in R]), '%.1f'%sum(x['cpu'] for _,x,_ in R), sum(x['cpu']<0.1 for _,x,_ in R), col, diffv, 'n=%d %.3f %.3f %.3f'%(len(e),st.median(e),q(e,0.75),q(e,0.9)), '%+.3f'%lm)
