#!/usr/bin/env python3
"""Writes cubes-into-boxes-K.toml for K = 2, 3: K unit cubes, each to go into its own box open
at the top (the box of CHS A.2.1's "putting a cube into a box", 0.05 of clearance on every
side), the boxes in a row along x. The cubes start above and behind the row, in another order
than their boxes, so they pass each other on the way; some start turned and must turn back to
fit. Run from this folder: python3 make_boxes.py"""

import math

SPACING = 2.5  # box centres along x


def quat(axis, degrees):
    h = math.radians(degrees) / 2
    s = math.sin(h)
    return [round(axis[0] * s, 12), round(axis[1] * s, 12), round(axis[2] * s, 12), round(math.cos(h), 12)]


# per k: for each cube, (start x index, box index, start orientation)
PLANS = {
    2: [(0, 1, ([0, 0, 1], 0)), (1, 0, ([0, 0, 1], 30))],
    3: [(0, 2, ([0, 0, 1], 0)), (1, 0, ([0, 0, 1], 30)), (2, 1, ([1, 0, 0], 30))],
}
NAMES = ["red", "blue", "green"]


def box_walls(cx):
    # floor: x, y in [-0.65, 0.65], z in [-0.1, 0]; four walls 1.2 high, 0.1 thick
    return [
        ("floor", [cx, 0.0, -0.05], [0.65, 0.65, 0.05]),
        ("wall at +x", [cx + 0.6, 0.0, 0.6], [0.05, 0.65, 0.6]),
        ("wall at -x", [cx - 0.6, 0.0, 0.6], [0.05, 0.65, 0.6]),
        ("wall at +y", [cx, 0.6, 0.6], [0.55, 0.05, 0.6]),
        ("wall at -y", [cx, -0.6, 0.6], [0.55, 0.05, 0.6]),
    ]


def scene(k):
    xs = [SPACING * (i - (k - 1) / 2) for i in range(k)]
    half_x = SPACING * (k - 1) / 2 + 2.0
    lines = [
        f"# {k} unit cubes, each to go into its own box open at the top (CHS A.2.1's box: 0.05 of",
        "# clearance on every side, walls 1.2 high), the boxes in a row along x at "
        + ", ".join(f"x = {x}" for x in xs) + ".",
        "# The cubes start above and behind the row, in another order than their boxes, so they",
        "# pass each other on the way; a turned cube must turn back to fit. Goals 0.05 above the floor.",
        "# Written by make_boxes.py.",
        f'name = "cubes-into-boxes-{k}"',
        "",
        "[space]",
        'kind = "se3"',
        f"lower = [{-half_x}, -3.0, -1.0]",
        f"upper = [{half_x}, 3.0, 4.0]",
        "",
    ]
    start, goal = [], []
    for i, (s, b, (axis, deg)) in enumerate(PLANS[k]):
        lines += [
            "[[body]]",
            f'name = "{NAMES[i]}"',
            "box = { half_extents = [0.5, 0.5, 0.5] }",
            "",
        ]
        start += [xs[s], 2.0, 2.5] + quat(axis, deg)
        goal += [xs[b], 0.0, 0.55, 0.0, 0.0, 0.0, 1.0]
    for b, cx in enumerate(xs):
        for name, c, h in box_walls(cx):
            lines += [
                f"[[obstacle]]   # box {b + 1}: {name}",
                f"box = {{ center = [{c[0]}, {c[1]}, {c[2]}], half_extents = [{h[0]}, {h[1]}, {h[2]}] }}",
            ]
    fmt = lambda q: "[" + ", ".join(repr(float(v)) for v in q) + "]"
    lines += ["", "[[query]]", f"start = {fmt(start)}", f"goal  = {fmt(goal)}", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    for k in PLANS:
        with open(f"cubes-into-boxes-{k}.toml", "w") as f:
            f.write(scene(k))
