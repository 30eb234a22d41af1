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
    found = "found_ms" in a[0]
    print("| family | valid | solved, answers / trees | certified | query p50 ms | p95 ms | sum of latencies s | nodes after |"
          + (" found p50 ms |" if found else ""))
    print("|---|---|---|---|---|---|---|---|" + ("---|" if found else ""))
    for x, y in zip(a, t):
        print(
            f"| {x['family'].replace('_panda', '')} | {x['valid']} | {x['solved']} / {y['solved']} "
            f"| {x['certified']} / {y['certified']} | {x['query_ms']['p50']:.2f} / {y['query_ms']['p50']:.2f} "
            f"| {x['query_ms']['p95']:.0f} / {y['query_ms']['p95']:.0f} "
            f"| {sum(x['latencies_ms']) / 1e3:.2f} / {sum(y['latencies_ms']) / 1e3:.2f} "
            f"| {x['nodes_after']} / {y['nodes_after']} |"
            + (f" {x['found_ms']['p50']:.2f} / {y['found_ms']['p50']:.2f} |" if found else "")
        )
    sa = sum(sum(x["latencies_ms"]) for x in a) / 1e3
    st = sum(sum(y["latencies_ms"]) for y in t) / 1e3
    print(f"| **all** | | | | | | **{sa:.2f} / {st:.2f}** | |")


table("race-answers-30", "race-trees-30", "`--race 50`, run 1")
table("rep-race-answers-30", "rep-race-trees-30", "`--race 50`, run 2")
table("found-race-answers-30", "found-race-trees-30", "`--race 50`, run 3 (with the time found, before shortening)")
table("turn-answers-30", "turn-trees-30", "in turn")
table("race-answers-30", "race2-trees-30", "answers kept with `--race 50` / trees kept with `--race 2`")
