"""Side-by-side table of the workcell runs here: answers kept, with and without their trees."""
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))


def load(name):
    for path in (os.path.join(here, name + ".json"), os.path.join(here, "out", name, "workcell.json")):
        if os.path.exists(path):
            return json.load(open(path))
    return None


def table(before, after, title):
    a, t = load(before), load(after)
    if a is None or t is None:
        return
    print(f"\n### {title}\n")
    print("| family | valid | solved, answers / trees | certified | query p50 ms | p95 ms | sum of latencies s | nodes after |")
    print("|---|---|---|---|---|---|---|---|")
    for x, y in zip(a, t):
        print(
            f"| {x['family'].replace('_panda', '')} | {x['valid']} | {x['solved']} / {y['solved']} "
            f"| {x['certified']} / {y['certified']} | {x['query_ms']['p50']:.2f} / {y['query_ms']['p50']:.2f} "
            f"| {x['query_ms']['p95']:.0f} / {y['query_ms']['p95']:.0f} "
            f"| {sum(x['latencies_ms']) / 1e3:.2f} / {sum(y['latencies_ms']) / 1e3:.2f} "
            f"| {x['nodes_after']} / {y['nodes_after']} |"
        )
    sa = sum(sum(x["latencies_ms"]) for x in a) / 1e3
    st = sum(sum(y["latencies_ms"]) for y in t) / 1e3
    print(f"| **all** | | | | | | **{sa:.2f} / {st:.2f}** | |")


table("race-answers-30", "race-trees-30", "`--race 50`, run 1")
table("rep-race-answers-30", "rep-race-trees-30", "`--race 50`, run 2")
table("turn-answers-30", "turn-trees-30", "in turn")
table("race-answers-30", "race2-trees-30", "answers kept with `--race 50` / trees kept with `--race 2`")
