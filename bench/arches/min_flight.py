"""The 20-voussoir arch (R = 5 m, t/R = 0.15) under the first 30 s of each far-field record
scaled to PGA 2.922 m/s² (2 λ g), and the bundled record as recorded: one `rocking simulate`
scene per record and variant, each variant `dt:min_flight` (docs/arch-performance.md, "The
closings ..."). Appends `record,dt,min_flight,collapsed,t_end,peak,events,closings,user_cpu` to
OUT/results.csv (user CPU of the child, niced; noisy on a shared machine).

python3 bench/arches/min_flight.py target/release/rocking OUT 1e-3:0,1e-3:1,5e-4:0 [RECORD.AT2 | bundled ...]
(no records: all of /work/shared/records/fema-p695/farfield/; run from the repository's root)
"""
import json,os,subprocess,sys,glob,time,resource
BIN=sys.argv[1]; OUT=sys.argv[2]; variants=sys.argv[3].split(',')
recs=sys.argv[4:] if len(sys.argv)>4 else sorted(glob.glob('/work/shared/records/fema-p695/farfield/*.AT2'))
os.makedirs(OUT,exist_ok=True)
res=open(os.path.join(OUT,'results.csv'),'a')
for r in recs:
    for v in variants:
        # variant: dt[:min_flight]  e.g. 1e-3:0, 5e-4:0, 1e-3:1
        dt,mf=v.split(':')
        name=os.path.basename(r)[:-4] if r.endswith('.AT2') else 'bundled'
        sc={"arch":{"radius":5.0,"thickness":0.75,"embrace_angle":180,"voussoirs":20,"density":2000,"depth":1.0},
            "duration":30.0,"dt":float(dt)}
        if r=='bundled':
            sc["excitation"]={"type":"record","path":os.path.abspath("examples/records/synthetic.AT2")}
        else:
            sc["excitation"]={"type":"record","path":r,"scale_to_pga":2.922}
        if float(mf)>0: sc["min_flight"]=float(mf)
        d=os.path.join(OUT,name+'_'+dt+'_'+mf); os.makedirs(d,exist_ok=True)
        json.dump(sc,open(d+'/scene.json','w'))
        t0=resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
        p=subprocess.run(['nice','-n','10',BIN,'simulate',d+'/scene.json','--out',d],capture_output=True,text=True)
        cpu=resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime-t0
        if p.returncode: print(name,v,'FAIL',p.stderr.strip()[:200]); res.write(f"{name},{dt},{mf},fail,,,,,{cpu:.3f}\n"); res.flush(); continue
        s=json.load(open(d+'/summary.json'))
        ev=s['events']; n=sum(ev.values())
        line=f"{name},{dt},{mf},{s['collapsed']},{s['t_end']:.6f},{s['peak_angle']:.6e},{n},{ev.get('closing',0)},{cpu:.3f}"
        print(line,flush=True); res.write(line+'\n'); res.flush()
        os.remove(d+'/history.csv')
