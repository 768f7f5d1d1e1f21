"""Per-record change of the peak against the default at dt = 1 ms (bench/arches/min_flight.csv):
the options, halving dt, and a 0.1 % change of dt (the sensitivity of the response).

python3 bench/arches/min_flight_pairs.py  (from the repository root)
"""
import collections,statistics as st,math
rows=[l.strip().split(',') for l in open('bench/arches/min_flight.csv')][1:]
D=collections.defaultdict(dict)
for r in rows:
    if r[0]!='bundled': D[r[0]][(r[1],r[2])]=r
base=('1e-3','0')
def q(xs,p): xs=sorted(xs); return xs[min(len(xs)-1,int(p*len(xs)))]
for v in [('9.99e-4','0'),('1.001e-3','0'),('5e-4','0'),('1e-3','1'),('1e-3','1.5'),('1e-3','2'),('1e-3','3'),('1e-3','4')]:
    e=[abs(float(d[v][5])/float(d[base][5])-1) for d in D.values() if d[v][3]=='False' and d[base][3]=='False' and float(d[base][5])>0]
    print(v,'n',len(e),'|peak/peak(default 1 ms)-1| median %.3f 75%% %.3f 90%% %.3f'%(st.median(e),q(e,.75),q(e,.9)))
