#!/usr/bin/env python3
"""Writes swap-corridor-K.toml for K = 2, 3, 4, 6: K squares in a corridor one square wide
with a niche, each square to take another's place. Run from this folder: python3 make_swaps.py"""

HALF = 0.4  # a square of side 0.8 in a corridor of width 1.0


def scene(k):
    length = 2 * k  # cells of width 1: the squares fill the first k, the rest is room to pass
    niche = k - 0.5  # the niche sits above the last square's cell
    lines = [
        f"# {k} squares (side {2 * HALF}) in a corridor one square wide (y in [0, 1], x in [0, {length}])",
        f"# with a niche above x in [{niche - 0.5}, {niche + 0.5}], y in [1, 2]. The squares start in the first {k}",
        "# cells; each takes another's place: the last one goes to the first cell, every other one a",
        "# cell to the right" + (" (for two squares: a swap)." if k == 2 else "."),
        "# The last square must wait in the niche while the others pass beneath it.",
        f"# Written by make_swaps.py.",
        f'name = "swap-corridor-{k}"',
        "",
        "[space]",
        'kind = "se2"',
        "lower = [0.0, 0.0]",
        f"upper = [{float(length)}, 2.0]",
        "",
    ]
    for i in range(k):
        lines += [
            "[[body]]",
            f'name = "s{i + 1}"',
            f"box = {{ half_extents = [{HALF}, {HALF}] }}",
            "",
        ]
    walls = [
        ("floor", [-0.5, -0.5], [length + 0.5, 0.0]),
        ("left end", [-0.5, 0.0], [0.0, 1.0]),
        ("right end", [length, 0.0], [length + 0.5, 1.0]),
        ("ceiling left of the niche", [-0.5, 1.0], [niche - 0.5, 2.5]),
        ("ceiling right of the niche", [niche + 0.5, 1.0], [length + 0.5, 2.5]),
        ("the niche's roof", [niche - 0.5, 2.0], [niche + 0.5, 2.5]),
    ]
    for name, lo, hi in walls:
        c = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]
        h = [(hi[0] - lo[0]) / 2, (hi[1] - lo[1]) / 2]
        if h[0] <= 0:
            continue
        lines += [
            f"[[obstacle]]   # {name}",
            f"box = {{ center = [{c[0]}, {c[1]}], half_extents = [{h[0]}, {h[1]}] }}",
        ]
    start, goal = [], []
    for i in range(k):
        start += [i + 0.5, 0.5, 0.0]
        cell = 0 if i == k - 1 else i + 1
        goal += [cell + 0.5, 0.5, 0.0]
    fmt = lambda v: "[" + ", ".join(f"{x}" for x in v) + "]"
    lines += ["", "[[query]]", f"start = {fmt(start)}", f"goal  = {fmt(goal)}", ""]
    return "\n".join(lines)


for k in (2, 3, 4, 6):
    with open(f"swap-corridor-{k}.toml", "w") as f:
        f.write(scene(k))
