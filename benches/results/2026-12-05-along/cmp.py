import json, csv, glob, statistics as st, sys
O=[json.loads(l) for f in sorted(glob.glob('/tmp/r/ompl/*.jsonl')) for l in open(f) if l.strip()]
V=list(csv.DictReader(open(sys.argv[1] if len(sys.argv)>1 else '/tmp/r/p700-final/problems.csv')))
def pct(xs,p):
    xs=sorted(xs); return xs[min(len(xs)-1,int(round(p*(len(xs)-1))))]
fams=sorted(set(o['family'] for o in O))
print('| family | OMPL solved | OMPL p50 ms (grow / +simplify) | viaroad solved | viaroad p50 ms | ratio (+simplify) | OMPL length p50 (simplified) | viaroad length p50 |')
print('|---|---|---|---|---|---|---|---|')
def row(name, os_, vs):
    og=[o['time_s']*1e3 for o in os_ if o['solved']]
    ot=[(o['time_s']+o.get('simplify_time_s',0))*1e3 for o in os_ if o['solved']]
    vt=[float(v['time_s'])*1e3 for v in vs if v['solved']=='true']
    ol=[o['simplified_length'] for o in os_ if o['solved']]
    vl=[float(v['length']) for v in vs if v['solved']=='true']
    print('| %s | %d/%d | %.1f / %.1f | %d/%d | %.1f | %.2f× (%.2f×) | %.2f | %.2f |' % (name, len(og), len(os_), st.median(og), st.median(ot), len(vt), len(vs), st.median(vt), st.median(vt)/st.median(og), st.median(vt)/st.median(ot), st.median(ol), st.median(vl)))
    return og, ot, vt
for f in fams:
    row(f, [o for o in O if o['family']==f], [v for v in V if v['family']==f])
og, ot, vt = row('**all**', O, V)
print()
print('OMPL grow: mean %.1f p95 %.1f ms; grow+simplify: mean %.1f p95 %.1f; viaroad: mean %.1f p95 %.1f' % (st.mean(og), pct(og,.95), st.mean(ot), pct(ot,.95), st.mean(vt), pct(vt,.95)))
print('OMPL simplified paths passing its own check:', sum(1 for o in O if o['solved'] and o.get('simplified_valid')), '/', sum(1 for o in O if o['solved']))
