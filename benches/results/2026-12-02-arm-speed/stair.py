import subprocess, sys
B='/work/wt-arms3/target/release/viaroad'
path=[list(map(float,l.split())) for l in open('/work/wt-arms3/tests/data/arms/paths/cage_0003_rrtconnect.path') if l.strip()]
a, z = path[-2], path[-1]
def free(p, q):
    r=subprocess.run([B,'probe','/tmp/cage/cage3.toml','--from='+','.join(map(repr,p)),'--to='+','.join(map(repr,q))],capture_output=True,text=True)
    return r.stdout.startswith('free:'), r.stdout.strip().splitlines()[-1] if r.stdout else r.stderr
print('straight segment, several joints at once: (refused by the arm oracle; OMPL took it)')
for n in [1, 2, 4, 8, 16, 32, 64]:
    bad=0; calls=0
    cur=list(a)
    for k in range(1, n+1):
        tgt=[a[i]+(z[i]-a[i])*k/n for i in range(7)]
        for j in range(7):
            nxt=list(cur); nxt[j]=tgt[j]
            if nxt[j]!=cur[j]:
                ok,_=free(cur,nxt); calls+=1
                bad+= (not ok)
            cur=nxt
    print(f'{n} steps per joint, joint order 1..7: {bad} of {calls} single-joint moves collide')
