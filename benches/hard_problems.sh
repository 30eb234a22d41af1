#!/usr/bin/env bash
# Issue 9's judging protocol, back to back on one machine: viaroad (`build --time T` + `query`,
# and `solve --roadmap` when the binary has it) against the OMPL 1.5 + FCL peer
# (`ompl_peer solve --planner prm|rrtconnect --time T --runs 3`), every solved viaroad path
# re-checked with `ompl_peer check`. One JSON line per run, then a Markdown summary.
# See benches/hard_problems.md.
set -uo pipefail

usage() {
  cat <<'EOF'
usage: benches/hard_problems.sh [options]
  --viaroad PATH     viaroad binary (default: target/release/viaroad)
  --peer PATH        ompl_peer binary (default: /tmp/ompl-peer/build/ompl_peer)
  --out DIR          output directory (default: benches/results/$(date -u +%F))
  --work DIR         roadmaps and scratch files (default: /tmp/hard_problems_work)
  --problems "A B"   problems, each NAME or NAME:T (default: alpha-1.5:30 bugtrap:60 Apartment:60 Twistycool:20 cubicles:20 Abstract:60)
  --seeds "1 2 3"    viaroad seeds (default: 1 2 3)
  --side S           both | viaroad | peer (default: both)
  --threads N        RAYON_NUM_THREADS for viaroad (default: 1, as in the issue)
  --peer-runs N      runs per peer planner (default: 3)
  --planners "P Q"   peer planners (default: prm rrtconnect)
  --kinds "K …"      viaroad forms to run: build (build + query), roadmap (solve --roadmap),
                     tree (solve --tree) (default: build roadmap tree)
  --tree-args "A B"  extra options of `solve --tree` (default: none, the binary's defaults)
  --summarize        only (re)write DIR/summary.md from DIR/*.jsonl
EOF
}

VIAROAD=target/release/viaroad
PEER=/tmp/ompl-peer/build/ompl_peer
OUT=""
WORK=/tmp/hard_problems_work
PROBLEMS="alpha-1.5:30 bugtrap:60 Apartment:60 Twistycool:20 cubicles:20 Abstract:60"
SEEDS="1 2 3"
SIDE=both
THREADS=1
PEER_RUNS=3
PLANNERS="prm rrtconnect"
TREE_ARGS=""
KINDS="build roadmap tree"
SUMMARIZE_ONLY=0
SCENES=scenes/ompl/3D

while [ $# -gt 0 ]; do
  case "$1" in
    --viaroad) VIAROAD=$2; shift 2 ;;
    --peer) PEER=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    --problems) PROBLEMS=$2; shift 2 ;;
    --seeds) SEEDS=$2; shift 2 ;;
    --side) SIDE=$2; shift 2 ;;
    --threads) THREADS=$2; shift 2 ;;
    --peer-runs) PEER_RUNS=$2; shift 2 ;;
    --planners) PLANNERS=$2; shift 2 ;;
    --tree-args) TREE_ARGS=$2; shift 2 ;;
    --kinds) KINDS=$2; shift 2 ;;
    --summarize) SUMMARIZE_ONLY=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
done

cd "$(dirname "$0")/.." || exit 2
[ -n "$OUT" ] || OUT=benches/results/$(date -u +%F)
mkdir -p "$OUT" "$OUT/paths" "$WORK"
VJSON=$OUT/viaroad.jsonl
PJSON=$OUT/peer.jsonl

summarize() {
  python3 - "$OUT" <<'PY'
import json, os, sys, statistics
out = sys.argv[1]
def load(name):
    p = os.path.join(out, name)
    rows = []
    if os.path.exists(p):
        for line in open(p):
            line = line.strip()
            if line:
                try: rows.append(json.loads(line))
                except json.JSONDecodeError: pass
    return rows
V, P = load("viaroad.jsonl"), load("peer.jsonl")
order = []
for r in V + P:
    if r["problem"] not in order: order.append(r["problem"])
def f(x, d=1):
    return "–" if x is None else f"{x:.{d}f}"
def med(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None
L = []
meta = [r for r in V + P if "host" in r]
if meta:
    m = meta[0]
    L.append(f"Host `{m.get('host')}`, {m.get('cpus')} CPUs, {m.get('cpu_model','?')}; runs from "
             f"{min(r['date'] for r in meta)} to {max(r['date'] for r in meta)} (UTC). "
             f"Load average (1 min) at the start of the runs: "
             f"{min(r['load1'] for r in meta):.2f}–{max(r['load1'] for r in meta):.2f}.")
    vs = sorted({r.get('viaroad_commit','?') for r in V})
    if vs: L.append(f"viaroad `{', '.join(vs)}` ({V[0].get('threads')} thread(s)); query time limit: "
                    f"{', '.join(sorted({r.get('query_limit','?') for r in V}))}.")
    L.append("")
L.append("### viaroad: `build --time T --seed S`, then `query --from START --to GOAL`\n")
L.append("| problem | T s | seed | load | build wall s | ≤ 1.05 T + load? | nodes | edges | comps (largest) | query wall s | outcome | solved | time to solve s (build + query) | path states | `ompl_peer check` |")
L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for p in order:
    for r in [r for r in V if r["problem"] == p and r.get("kind") == "build+query"]:
        T = r["T"]
        held = r.get("build_budget_held")
        chk = r.get("check_valid")
        L.append("| {} | {} | {} | {:.2f} | {}{} | {} | {} | {} | {} | {}{} | {} | {} | {} | {} | {} |".format(
            p, T, r["seed"], r["load1"], f(r.get("build_wall_s")),
            " (killed)" if r.get("build_timed_out") else "",
            "yes" if held else ("no" if held is not None else "–"),
            r.get("nodes", "–"), r.get("edges", "–"),
            f"{r.get('components','–')} ({r.get('largest_component','–')})",
            f(r.get("query_wall_s")), " (killed)" if r.get("query_timed_out") else "",
            r.get("outcome") or r.get("query_error") or "–",
            "yes" if r.get("solved") else "no",
            f(r.get("time_to_solve_s")) if r.get("solved") else "–",
            r.get("path_states", "–"),
            "–" if chk is None else ("valid" if chk else "**INVALID**")))
SQ = [r for r in V if r.get("kind") == "solve-roadmap"]
ST = [r for r in V if r.get("kind") == "solve-tree"]
for rows, flag in ((SQ, "--roadmap"), (ST, "--tree")):
    if not rows: continue
    L.append(f"\n### viaroad: one command, `solve CFG {flag} --time T`\n")
    L.append("| problem | T s | seed | load | wall s | ≤ 1.05 T + load? | outcome | solved | `ompl_peer check` |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        chk = r.get("check_valid")
        held = r.get('wall_s') is not None and not r.get('timed_out') and r['wall_s'] <= 1.05 * r['T'] + (r.get('load_s') or 0)
        L.append(f"| {r['problem']} | {r['T']} | {r['seed']} | {r['load1']:.2f} | {f(r.get('wall_s'))}{' (killed)' if r.get('timed_out') else ''} | "
                 f"{'yes' if held else 'no'} | {r.get('outcome') or '–'} | "
                 f"{'yes' if r.get('solved') else 'no'} | {'–' if chk is None else ('valid' if chk else '**INVALID**')} |")
L.append("\n### OMPL 1.5 + FCL peer: `ompl_peer solve CFG --planner P --time T --runs 3 --seed 1`\n")
L.append("| problem | T s | planner | load | solved | time_s per run | vertices per run | simplified valid |")
L.append("|---|---|---|---|---|---|---|---|")
for p in order:
    for pl in sorted({r["planner"] for r in P if r["problem"] == p}):
        rs = [r for r in P if r["problem"] == p and r["planner"] == pl and "solved" in r]
        if not rs: continue
        L.append("| {} | {} | {} | {:.2f} | {}/{} | {} | {} | {} |".format(
            p, rs[0]["T"], pl, rs[0]["load1"], sum(1 for r in rs if r["solved"]), len(rs),
            ", ".join(f(r.get("time_s"), 2) for r in rs),
            ", ".join(str(r.get("vertices", "–")) for r in rs),
            ", ".join(("yes" if r.get("simplified_valid") else "no") if r["solved"] else "–" for r in rs)))
L.append("\n### Per problem\n")
L.append("| problem | T s | viaroad solved | viaroad median time to solve s | median nodes | build wall max / T | query wall max s | paths valid | `solve --roadmap` solved | `solve --tree` solved (median s) | PRM solved | PRM median time_s | RRTConnect solved | RRTConnect median time_s |")
L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for p in order:
    vr = [r for r in V if r["problem"] == p and r.get("kind") == "build+query"]
    T = (vr or [r for r in P + SQ + ST if r["problem"] == p])[0]["T"]
    sol = [r for r in vr if r.get("solved")]
    def peer(pl):
        rs = [r for r in P if r["problem"] == p and r["planner"] == pl and "solved" in r]
        if not rs: return "–", "–"
        s = [r["time_s"] for r in rs if r["solved"]]
        return f"{len(s)}/{len(rs)}", f(med(s), 2) if s else "–"
    pr, rr = peer("prm"), peer("rrtconnect")
    bw = [r.get("build_wall_s") for r in vr if r.get("build_wall_s") is not None]
    qw = [r.get("query_wall_s") for r in vr if r.get("query_wall_s") is not None]
    checked = [r for r in sol if r.get("check_valid") is not None]
    sq = [r for r in SQ if r["problem"] == p]
    sq_txt = "{}/{} ({} valid)".format(sum(1 for r in sq if r.get("solved")), len(sq),
        sum(1 for r in sq if r.get("check_valid"))) if sq else "–"
    st = [r for r in ST if r["problem"] == p]
    st_txt = "{}/{} ({} valid; {})".format(sum(1 for r in st if r.get("solved")), len(st),
        sum(1 for r in st if r.get("check_valid")),
        f(med([r.get("wall_s") for r in st if r.get("solved")]))) if st else "–"
    L.append("| {} | {} | {}/{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
        p, T, len(sol), len(vr), f(med([r.get("time_to_solve_s") for r in sol])) if sol else "–",
        f(med([r.get("nodes") for r in vr]), 0) if vr else "–",
        f(max(bw) / T, 2) if bw else "–", f(max(qw)) if qw else "–",
        f"{sum(1 for r in checked if r['check_valid'])}/{len(sol)}" if sol else "–", sq_txt, st_txt,
        pr[0], pr[1], rr[0], rr[1]))
text = "\n".join(L) + "\n"
open(os.path.join(out, "summary.md"), "w").write(text)
print(text)
PY
}

if [ "$SUMMARIZE_ONLY" = 1 ]; then summarize; exit 0; fi

export RAYON_NUM_THREADS=$THREADS
HOST=$(hostname)
CPUS=$(nproc)
CPU_MODEL=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
# the last commit that touched the sources of the binary's checkout (commits to benches/ do not count)
VTOP=$(git -C "$(dirname "$VIAROAD")" rev-parse --show-toplevel 2>/dev/null || true)
VCOMMIT=unknown
if [ -n "$VTOP" ]; then
  VCOMMIT=$(git -C "$VTOP" log -1 --format=%h -- src Cargo.toml Cargo.lock 2>/dev/null || echo unknown)
  [ -n "$(git -C "$VTOP" status --porcelain -- src Cargo.toml Cargo.lock 2>/dev/null)" ] && VCOMMIT="$VCOMMIT+dirty"
  [ "$VIAROAD" -ot "$VTOP/src" ] && VCOMMIT="$VCOMMIT (binary older than src/?)"
fi

load1() { cut -d' ' -f1 /proc/loadavg; }
now() { date +%s.%N; }
since() { python3 -c "import sys; print(round(float(sys.argv[2]) - float(sys.argv[1]), 3))" "$1" "$(now)"; }
meta() { # common JSON fields of a run
  jq -cn --arg host "$HOST" --argjson cpus "$CPUS" --arg cpu "$CPU_MODEL" --arg date "$(date -u +%FT%TZ)" \
    --argjson load1 "$(load1)" --arg loadavg "$(cut -d' ' -f1-3 /proc/loadavg)" \
    '{host:$host, cpus:$cpus, cpu_model:$cpu, date:$date, load1:$load1, loadavg:$loadavg}'
}

# The cfg's start and goal in OMPL's layout x y z qx qy qz qw, computed as viaroad's
# src/scene/ompl_cfg.rs and OMPL.app do: q = (sin(θ/2)·a/|a|, cos(θ/2)), θ and axis from
# `start.theta`, `start.axis.*` (missing θ = 0; no axis and θ = 0 = identity). Last key wins.
cfg_state() { # CFG start|goal
  python3 - "$1" "$2" <<'PY'
import math, sys
cfg, which = sys.argv[1], sys.argv[2]
kv, section = {}, None
for line in open(cfg):
    line = line.split('#', 1)[0].strip()
    if line.startswith('['): section = line.strip('[]').strip(); continue
    if section == 'problem' and '=' in line:
        k, v = line.split('=', 1); kv[k.strip()] = v.strip()
g = lambda k, d=None: float(kv[k]) if k in kv and kv[k] != '' else d
x, y, z = g(f'{which}.x'), g(f'{which}.y'), g(f'{which}.z', 0.0)
th = g(f'{which}.theta', 0.0)
a = [g(f'{which}.axis.{c}', 0.0) for c in 'xyz']
if not any(k.startswith(f'{which}.axis.') for k in kv) and th == 0.0: a = [1.0, 0.0, 0.0]
n = math.sqrt(sum(c * c for c in a))
q = [0.0, 0.0, 0.0, 1.0] if n < 2.2e-16 else [math.sin(th / 2) / n * a[0], math.sin(th / 2) / n * a[1], math.sin(th / 2) / n * a[2], math.cos(th / 2)]
print(" ".join(repr(v) for v in [x, y, z] + q))
PY
}

# does `viaroad SUBCOMMAND --help` list FLAG? (help captured first: `| grep -q` under pipefail
# fails at random when grep exits before the writer is done, SIGPIPE)
has_flag() { # SUBCOMMAND FLAG
  local help; help=$("$VIAROAD" "$1" --help 2>/dev/null) || true
  grep -Eq -- "$2([^-a-zA-Z0-9_]|\$)" <<<"$help"
}

run_viaroad() { # NAME T SEED
  local name=$1 T=$2 seed=$3 cfg=$SCENES/$1.cfg
  local tag="${name}_s${seed}" bin="$WORK/${1}_s${3}.bin" path="$OUT/paths/${1}_s${3}.path"
  local start goal; start=$(cfg_state "$cfg" start); goal=$(cfg_state "$cfg" goal)
  local m; m=$(meta)
  rm -f "$bin" "$path"
  # scene load time (meshes + BVHs), the "+ load time" of the budget: a zero-length probe
  local load_s t0; t0=$(now)
  "$VIAROAD" probe "$cfg" --from "$start" --to "$start" >/dev/null 2>&1
  load_s=$(since "$t0")
  echo "[$(date -u +%T)] viaroad build $tag (T=$T, load $(load1))" >&2
  local brc bwall bout
  t0=$(now)
  bout=$(timeout -k 5 $((T + 60)) "$VIAROAD" build "$cfg" -o "$bin" --time "$T" --seed "$seed" 2>"$WORK/$tag.build.err")
  brc=$?; bwall=$(since "$t0")
  local info='{}'
  [ $brc -eq 0 ] && [ -s "$bin" ] && info=$("$VIAROAD" info "$bin" --json 2>/dev/null | jq -c '{nodes, edges, components, largest_component, rounds, counts}' 2>/dev/null || echo '{}')
  # query: its own --time when the binary has it (killed at T + 30 s), else killed at T by timeout
  local qlimit qcmd=("$VIAROAD" query "$bin" --scene "$cfg" --from "$start" --to "$goal" --json --path-out "$path")
  local qkill
  if has_flag query --time; then qcmd+=(--time "$T"); qlimit="query --time T"; qkill=$((T + 30))
  else qlimit="timeout T (no query --time)"; qkill=$T; fi
  local qrc=-1 qwall=null qout=""
  if [ $brc -eq 0 ]; then
    echo "[$(date -u +%T)] viaroad query $tag (load $(load1))" >&2
    t0=$(now)
    qout=$(timeout -k 5 "$qkill" "${qcmd[@]}" 2>"$WORK/$tag.query.err" | tail -n 1)
    qrc=${PIPESTATUS[0]}; qwall=$(since "$t0")
  fi
  local qjson='{}'
  [ -n "$qout" ] && qjson=$(echo "$qout" | jq -c 'del(.path, .shortened)' 2>/dev/null || echo '{}')
  local chk='{}'
  if [ "$(echo "$qjson" | jq -r '.solved // false')" = true ] && [ -s "$path" ]; then
    echo "[$(date -u +%T)] ompl_peer check $tag" >&2
    chk=$(timeout 600 "$PEER" check "$cfg" "$path" 2>/dev/null | tail -n 1 | jq -c '{check_valid: .valid, check_invalid_states: .invalid_states, check_invalid_segments: .invalid_segments, check_path_length: .path_length, path_states: .states}' 2>/dev/null || echo '{"check_valid": null}')
  fi
  jq -cn --argjson m "$m" --arg problem "$name" --argjson T "$T" --argjson seed "$seed" \
    --arg viaroad "$VIAROAD" --arg commit "$VCOMMIT" --argjson threads "$THREADS" --arg qlimit "$qlimit" \
    --argjson load_s "$load_s" --argjson brc "$brc" --argjson bwall "$bwall" --arg bout "$bout" \
    --arg berr "$(tail -c 300 "$WORK/$tag.build.err" 2>/dev/null)" --arg qerr "$(tail -c 300 "$WORK/$tag.query.err" 2>/dev/null)" \
    --argjson info "$info" --argjson qrc "$qrc" --argjson qwall "$qwall" --argjson q "$qjson" --argjson chk "$chk" \
    --arg start "$start" --arg goal "$goal" '
    $m + {side: "viaroad", kind: "build+query", problem: $problem, T: $T, seed: $seed, viaroad: $viaroad,
      viaroad_commit: $commit, threads: $threads, query_limit: $qlimit, start: $start, goal: $goal,
      load_s: $load_s, build_rc: $brc, build_timed_out: ($brc == 124 or $brc == 137), build_wall_s: $bwall,
      build_budget_held: ($brc == 0 and $bwall <= 1.05 * $T + $load_s),
      build_stdout: $bout, build_stderr: $berr,
      build_reported_s: (($bout | capture("in (?<s>[0-9.]+) s") | .s | tonumber) // null),
      build_stopped: (($bout | capture("stopped: (?<r>[A-Za-z]+)") | .r) // null)} + $info +
     {query_rc: $qrc, query_timed_out: ($qrc == 124 or $qrc == 137), query_wall_s: $qwall,
      query_error: (if $qrc != 0 and $qrc != -1 and ($qerr | length) > 0 then $qerr else null end)} + $q +
     {solved: ($q.solved // false)} + $chk +
     {time_to_solve_s: (if ($q.solved // false) then ($bwall + $qwall) else null end)}' >"$WORK/line.json"
  # never lose a run: if the record could not be assembled, keep the bare facts
  [ -s "$WORK/line.json" ] || jq -cn --arg problem "$name" --argjson T "$T" --argjson seed "$seed" --arg brc "$brc" \
    --arg bwall "$bwall" --arg qrc "$qrc" --arg qwall "$qwall" --arg qout "$qout" \
    '{side: "viaroad", kind: "build+query", problem: $problem, T: $T, seed: $seed, record_error: true,
      build_rc: $brc, build_wall_s: $bwall, query_rc: $qrc, query_wall_s: $qwall, query_stdout: $qout}' >"$WORK/line.json"
  cat "$WORK/line.json" >>"$VJSON"
  tail -n 1 "$VJSON" | jq -c '{problem, seed, build_wall_s, nodes, components, query_wall_s, outcome, solved, check_valid}' >&2
}

run_solve_roadmap() { # NAME T SEED [MODE]: the one-command form, only when the binary has `solve --roadmap`
  # (MODE roadmap, the default) or `solve --tree` (MODE tree: RRT-Connect with exact extends)
  local name=$1 T=$2 seed=$3 mode=${4:-roadmap} cfg=$SCENES/$1.cfg
  local sfx=solve; [ "$mode" = tree ] && sfx=tree
  local tag="${name}_s${seed}_$sfx" path="$OUT/paths/${1}_s${3}_$sfx.path"
  local cmd=("$VIAROAD" solve "$cfg" "--$mode" --time "$T" --json --path-out "$path")
  [ "$mode" = tree ] && [ -n "$TREE_ARGS" ] && read -ra extra <<<"$TREE_ARGS" && cmd+=("${extra[@]}")
  has_flag solve --seed && cmd+=(--seed "$seed")
  local m; m=$(meta); rm -f "$path"
  local start load_s t0; start=$(cfg_state "$cfg" start); t0=$(now)
  "$VIAROAD" probe "$cfg" --from "$start" --to "$start" >/dev/null 2>&1
  load_s=$(since "$t0")
  echo "[$(date -u +%T)] viaroad solve --$mode $tag (load $(load1))" >&2
  local rc wall out
  t0=$(now)
  out=$(timeout -k 5 $((2 * T + 30)) "${cmd[@]}" 2>"$WORK/$tag.err" | tail -n 1)
  rc=${PIPESTATUS[0]}; wall=$(since "$t0")
  local q='{}'; [ -n "$out" ] && q=$(echo "$out" | jq -c 'del(.path, .shortened)' 2>/dev/null || echo '{}')
  local chk='{}'
  if [ "$(echo "$q" | jq -r '.solved // false')" = true ] && [ -s "$path" ]; then
    chk=$(timeout 600 "$PEER" check "$cfg" "$path" 2>/dev/null | tail -n 1 | jq -c '{check_valid: .valid, path_states: .states}' 2>/dev/null || echo '{"check_valid": null}')
  fi
  jq -cn --argjson m "$m" --arg problem "$name" --argjson T "$T" --argjson seed "$seed" --arg commit "$VCOMMIT" \
    --arg mode "$mode" --argjson threads "$THREADS" --argjson load_s "$load_s" --argjson rc "$rc" --argjson wall "$wall" --argjson q "$q" --argjson chk "$chk" '
    $m + {side: "viaroad", kind: ("solve-" + $mode), problem: $problem, T: $T, seed: $seed, viaroad_commit: $commit,
      threads: $threads, load_s: $load_s, rc: $rc, timed_out: ($rc == 124 or $rc == 137), wall_s: $wall} + $q +
     {solved: ($q.solved // false)} + $chk' >>"$VJSON"
}

run_peer() { # NAME T PLANNER
  local name=$1 T=$2 planner=$3 cfg=$SCENES/$1.cfg
  local m; m=$(meta)
  echo "[$(date -u +%T)] ompl_peer $planner $name (T=$T, load $(load1))" >&2
  local lines rc
  lines=$(timeout -k 5 $((PEER_RUNS * (T + 30) + 60)) "$PEER" solve "$cfg" --planner "$planner" --time "$T" \
    --runs "$PEER_RUNS" --seed 1 --save-path "$OUT/paths/${name}_${planner}" 2>"$WORK/${name}_$planner.peer.err")
  rc=$?
  [ -n "$lines" ] || lines='{"solved": null}'
  echo "$lines" | while IFS= read -r l; do
    jq -cn --argjson m "$m" --argjson r "$l" --arg problem "$name" --argjson T "$T" --argjson rc "$rc" \
      '$m + {side: "peer"} + $r + {problem: $problem, ompl_problem: $r.problem, T: $T, peer_rc: $rc}' >>"$PJSON"
  done
}

[ -x "$VIAROAD" ] || [ "$SIDE" = peer ] || { echo "no viaroad binary at $VIAROAD" >&2; exit 2; }
[ -x "$PEER" ] || { echo "no ompl_peer at $PEER (build it: cp -r ../shared/ompl-peer /tmp/ompl-peer && /tmp/ompl-peer/build.sh)" >&2; exit 2; }
echo "out=$OUT viaroad=$VIAROAD ($VCOMMIT) peer=$PEER threads=$THREADS problems=[$PROBLEMS] seeds=[$SEEDS] side=$SIDE" >&2

for spec in $PROBLEMS; do
  name=${spec%%:*}; T=${spec#*:}
  if [ "$T" = "$spec" ]; then
    case $name in alpha-1.5) T=30 ;; bugtrap|Apartment) T=60 ;; *) T=20 ;; esac
  fi
  [ -f "$SCENES/$name.cfg" ] || { echo "no $SCENES/$name.cfg" >&2; continue; }
  if [ "$SIDE" != peer ]; then
    for s in $SEEDS; do
      [[ " $KINDS " == *" build "* ]] && run_viaroad "$name" "$T" "$s"
      if [[ " $KINDS " == *" roadmap "* ]] && has_flag solve --roadmap; then run_solve_roadmap "$name" "$T" "$s"; fi
      if [[ " $KINDS " == *" tree "* ]] && has_flag solve --tree; then run_solve_roadmap "$name" "$T" "$s" tree; fi
    done
  fi
  if [ "$SIDE" != viaroad ]; then
    for pl in $PLANNERS; do run_peer "$name" "$T" "$pl"; done
  fi
done
summarize
