"""Several bodies in the plane from Python: the two-square swap in a corridor learnt and
answered through a roadmap, and both paths re-checked here with numpy (separating axes between
every square and every wall and between the squares, at states along each motion at most a
hundredth of a square apart), independently of the library's oracle and checker; then
`Scene.certify` on the same scene."""

import math
import re
from pathlib import Path

import numpy as np

import viaroad

ROOT = Path(__file__).resolve().parents[2]
SWAP2 = ROOT / "scenes" / "bodies" / "swap-corridor-2.toml"
STEP = 0.008  # the farthest any point of a square moves between two checked states


def boxes(text, key):
    """(centre, half extents) of every `box = { center = …, half_extents = … }` after `key`."""
    found = re.findall(
        r"box\s*=\s*\{\s*center\s*=\s*\[([^\]]*)\]\s*,\s*half_extents\s*=\s*\[([^\]]*)\]",
        text.split(key, 1)[1],
    )
    return [(np.array([float(v) for v in c.split(",")]), np.array([float(v) for v in h.split(",")])) for c, h in found]


def corners(centre, half, theta=0.0):
    local = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * half
    c, s = math.cos(theta), math.sin(theta)
    return centre + local @ np.array([[c, s], [-s, c]])


def apart(p, q):
    """Whether two convex polygons are strictly apart (touching counts as collision)."""
    for poly in (p, q):
        edges = np.roll(poly, -1, axis=0) - poly
        for n in np.stack([edges[:, 1], -edges[:, 0]], axis=1):
            a, b = p @ n, q @ n
            if a.max() < b.min() or b.max() < a.min():
                return True
    return False


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def check_path(path, start, goal, walls, half, lower, upper):
    path = np.asarray(path)
    assert path.ndim == 2 and path.shape[1] == 6 and len(path) >= 2
    assert np.allclose(path[0], start, atol=1e-12) and np.allclose(path[-1], goal, atol=1e-12)
    radius = float(np.linalg.norm(half))
    for a, b in zip(path[:-1], path[1:]):
        d = b - a
        d[2::3] = wrap(d[2::3])
        reach = max(np.hypot(d[3 * i], d[3 * i + 1]) + radius * abs(d[3 * i + 2]) for i in range(2))
        for t in np.linspace(0.0, 1.0, int(math.ceil(reach / STEP)) + 1):
            q = a + t * d
            squares = [corners(q[3 * i : 3 * i + 2], half, q[3 * i + 2]) for i in range(2)]
            for i in range(2):
                assert np.all(q[3 * i : 3 * i + 2] >= lower) and np.all(q[3 * i : 3 * i + 2] <= upper), q
                for c, h in walls:
                    assert apart(squares[i], corners(c, h)), (q, c)
            assert apart(squares[0], squares[1]), q


def test_the_swap_in_a_corridor_is_solved_and_rechecked_with_numpy():
    scene = viaroad.Scene.load(SWAP2)
    assert scene.dof == 6
    text = SWAP2.read_text()
    body = re.search(r"\[\[body\]\][^\[]*?half_extents\s*=\s*\[([^\]]*)\]", text)
    half = np.array([float(v) for v in body.group(1).split(",")])
    walls = boxes(text, "[[obstacle]]")
    assert len(walls) == 6
    rm = viaroad.Roadmap.build(scene, nodes=3000, seed=1)
    start, goal = scene.queries()[0]
    r = rm.query(start, goal, time=30.0)
    assert r.solved and r.error is None
    for path in (r.path, r.shortened):
        check_path(path, start, goal, walls, half, scene.lower[:2], scene.upper[:2])
    # the library's certificate agrees, and flags the two squares passing through each other
    assert scene.certify(r.shortened)["status"] == "free"
    through = scene.certify(np.array([start, goal]))
    assert through["status"] == "collides"
    assert through["segments"][0]["pairs"] == [["s1", "s2"]]


def test_the_numpy_check_refuses_squares_that_pass_through_each_other():
    text = SWAP2.read_text()
    walls = boxes(text, "[[obstacle]]")
    half = np.array([0.4, 0.4])
    start = np.array([0.5, 0.5, 0.0, 1.5, 0.5, 0.0])
    goal = np.array([1.5, 0.5, 0.0, 0.5, 0.5, 0.0])
    try:
        check_path([start, goal], start, goal, walls, half, np.array([0.0, 0.0]), np.array([4.0, 2.0]))
    except AssertionError:
        return
    raise AssertionError("two squares swapping straight through each other passed the check")
