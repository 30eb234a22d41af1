import json, sys, os
def wc(d):
    out = {}
    for r in json.load(open(os.path.join(d, 'workcell.json'))):
        out[r['family'].replace('_panda','').replace('_ur5','')] = r
    return out
runs = sys.argv[1:]
data = [wc(d) for d in runs]
fams = list(data[0].keys())
print('| family | ' + ' | '.join(runs) + ' |')
for f in fams:
    cells = []
    for d in data:
        r = d.get(f)
        if r is None: cells.append('-'); continue
        cells.append('%.2f ms (found %.2f), len %.2f, %d/%d/%d' % (r['query_ms']['p50'], r['found_ms']['p50'], r['length']['p50'], r['solved'], r['certified'], r['valid']))
    print('| %s | %s |' % (f, ' | '.join(cells)))
for d, name in zip(data, runs):
    lat = [x for r in d.values() for x in r['latencies_ms']]
    lat.sort()
    import statistics
    n = len(lat)
    print(name, 'pooled p50 %.2f over %d requests' % (statistics.median(lat), n), 'load ms max %.2f' % max(r['load_ms'] for r in d.values()))
