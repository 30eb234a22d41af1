import csv,sys,statistics as s
R=list(csv.DictReader(open(sys.argv[1])))
fams=sorted(set(x['family'] for x in R))
allt=[]
for f in fams:
  r=[x for x in R if x['family']==f]
  t=sorted(float(x['time_s'])*1000 for x in r if x['solved']=='true'); allt+=t
  c=sorted(float(x['calls']) for x in r)
  L=sorted(float(x['length']) for x in r if x['solved']=='true')
  print('%-24s solved %3d p50 %7.1f mean %7.1f calls %6d len %.2f'%(f,len(t),t[len(t)//2],s.mean(t),c[len(c)//2],L[len(L)//2]))
allt.sort(); print('ALL solved %d p50 %.1f mean %.1f p95 %.1f'%(len(allt),allt[len(allt)//2],s.mean(allt),allt[int(len(allt)*.95)]))
