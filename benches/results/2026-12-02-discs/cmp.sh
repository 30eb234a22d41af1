#!/bin/sh
# compare two bench discs output dirs, ignoring time columns
a=$1; b=$2
python3 - "$a" "$b" <<'PY'
import csv,sys,json
a,b=sys.argv[1],sys.argv[2]
def load(d):
    return [ {k:v for k,v in r.items() if k!='seconds'} for r in csv.DictReader(open(d+'/tables.csv'))]
ra,rb=load(a),load(b)
print('csv rows', len(ra), len(rb), 'identical' if ra==rb else 'DIFFERENT')
def strip(d):
    j=json.load(open(d+'/tables.json'))
    def rec(x):
        if isinstance(x,dict): return {k:rec(v) for k,v in x.items() if k not in ('seconds','elapsed','wall_seconds','cpu_seconds')}
        if isinstance(x,list): return [rec(v) for v in x]
        return x
    return rec(j)
print('json', 'identical' if strip(a)==strip(b) else 'DIFFERENT')
PY
# markdown: drop the last column (CPU s)
sed -E 's/\| [0-9.]+ \|$/|/' $a/tables.md > /tmp/md.a; sed -E 's/\| [0-9.]+ \|$/|/' $b/tables.md > /tmp/md.b
diff /tmp/md.a /tmp/md.b > /dev/null && echo "md identical (CPU s column dropped)" || { echo "md DIFFERENT"; diff /tmp/md.a /tmp/md.b | head; }
