import subprocess, re, sys, yaml
LO=[-2.8973,-1.7628,-2.8973,-3.0718,-2.8973,-0.0175,-2.8973]; HI=[2.8973,1.7628,2.8973,-0.0698,2.8973,3.7525,2.8973]
B='/work/wt-arms3/target/release/viaroad'
FAM=sys.argv[1]; P=f'/tmp/vamp/mbm/problems/{FAM}_panda'
for i in range(1, int(sys.argv[2])+1):
    toml=f'''name = "cage-{i}"
[space]
kind = "arm"
[robot]
urdf = "/work/wt-arms3/scenes/arms/panda/panda.urdf"
srdf = "/work/wt-arms3/scenes/arms/panda/panda.srdf"
group = "panda_arm"
[environment]
moveit_scene = "{P}/scene{i:04d}.yaml"
[[query]]
moveit_request = "{P}/request{i:04d}.yaml"
'''
    open(f'c{i}.toml','w').write(toml)
    req=yaml.safe_load(open(f'{P}/request{i:04d}.yaml'))
    jc=req['goal_constraints'][0]['joint_constraints']
    g={c['joint_name']:c['position'] for c in jc}
    G=[g[f'panda_joint{k}'] for k in range(1,8)]
    out=[]
    for j in range(7):
        a=list(G); b=list(G); a[j]=LO[j]; b[j]=HI[j]
        r=subprocess.run([B,'probe',f'c{i}.toml','--from='+','.join(map(repr,a)),'--to='+','.join(map(repr,b))],capture_output=True,text=True).stdout
        ivs=[(float(x),float(y)) for x,y in re.findall(r'\[([0-9.]+), ([0-9.]+)\]', r)]
        span=HI[j]-LO[j]; t=(G[j]-LO[j])/span
        lo=max([y for x,y in ivs if y<=t+1e-12]+[0.0]); hi=min([x for x,y in ivs if x>=t-1e-12]+[1.0])
        out.append((hi-lo)*span)
    print(i, ' '.join(f'{w:.2f}' for w in out), ' min', f'{min(out):.2f}')
