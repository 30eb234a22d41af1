"""Several bodies from Python, each path re-checked here with numpy independently of the
library's oracle and checker, then by `Scene.certify`:

- in the plane, the two-square swap in a corridor learnt and answered through a roadmap
  (separating axes between every square and every wall and between the squares, at states along
  each motion at most a hundredth of a square apart);
- in space, two cubes put into their boxes (SE(3)^2) the same way (separating axes between each
  turned cube and every box wall and between the two cubes, at states along each motion at most
  STEP_3D apart for any point of a cube)."""

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


CUBES2 = ROOT / "scenes" / "bodies" / "cubes-into-boxes-2.toml"
STEP_3D = 0.01  # the farthest any point of a cube moves between two checked states (clearance 0.05)
CUBE_HALF = np.array([0.5, 0.5, 0.5])


def box_walls(text):
    """(centre, half extents) of every obstacle box of the scene."""
    found = re.findall(
        r"box\s*=\s*\{\s*center\s*=\s*\[([^\]]*)\]\s*,\s*half_extents\s*=\s*\[([^\]]*)\]",
        text.split("[[obstacle]]", 1)[1],
    )
    return [(np.array([float(v) for v in c.split(",")]), np.array([float(v) for v in h.split(",")])) for c, h in found]


def matrix(q):
    """The rotation matrix of the unit quaternion [x, y, z, w]."""
    x, y, z, w = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def boxes_apart(ca, ra, ha, cb, rb, hb):
    """Whether two boxes are strictly apart at each of T states (centres `(T, 3)`, rotations
    `(T, 3, 3)` whose columns are the axes, half extents): some axis of the fifteen of the
    separating-axis test separates them (touching counts as collision)."""
    a_axes, b_axes = np.swapaxes(ra, 1, 2), np.swapaxes(rb, 1, 2)
    crosses = np.cross(a_axes[:, :, None, :], b_axes[:, None, :, :]).reshape(len(ca), 9, 3)
    axes = np.concatenate([a_axes, b_axes, crosses], axis=1)
    reach = np.abs(np.einsum("tkc,tci->tki", axes, ra)) @ ha + np.abs(np.einsum("tkc,tci->tki", axes, rb)) @ hb
    gap = np.abs(np.einsum("tkc,tc->tk", axes, cb - ca))
    usable = np.einsum("tkc,tkc->tk", axes, axes) > 1e-12
    return np.any(usable & (gap > reach), axis=1)


def turn(qa, qb):
    """The axis and angle that take orientation qa to qb the shorter way."""
    ra, rb = matrix(qa), matrix(qb)
    rel = rb @ ra.T
    angle = math.acos(max(-1.0, min(1.0, (np.trace(rel) - 1) / 2)))
    if angle < 1e-12:
        return np.array([1.0, 0.0, 0.0]), 0.0, ra
    axis = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]])
    if np.linalg.norm(axis) < 1e-9:  # a half turn: the axis from the symmetric part
        m = (rel + np.eye(3)) / 2
        axis = m[:, np.argmax(np.diag(m))]
    return axis / np.linalg.norm(axis), angle, ra


def rodrigues(axis, angles):
    """The rotations by each of `angles` about `axis`, `(T, 3, 3)`."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * (k @ k)


def check_path_in_space(path, start, goal, obstacles, lower, upper):
    path = np.asarray(path)
    assert path.ndim == 2 and path.shape[1] == 14 and len(path) >= 2
    assert np.allclose(path[0], start, atol=1e-9) and np.allclose(path[-1], goal, atol=1e-9)
    radius = float(np.linalg.norm(CUBE_HALF))
    for a, b in zip(path[:-1], path[1:]):
        moves = []
        for i in range(2):
            pa, pb = a[7 * i : 7 * i + 3], b[7 * i : 7 * i + 3]
            axis, angle, ra = turn(a[7 * i + 3 : 7 * i + 7], b[7 * i + 3 : 7 * i + 7])
            moves.append((pa, pb - pa, axis, angle, ra))
        reach = max(np.linalg.norm(d) + radius * angle for _, d, _, angle, _ in moves)
        t = np.linspace(0.0, 1.0, int(math.ceil(reach / STEP_3D)) + 1)
        cubes = [(p + t[:, None] * d, rodrigues(axis, t * angle) @ ra) for p, d, axis, angle, ra in moves]
        fixed = np.broadcast_to(np.eye(3), (len(t), 3, 3))
        for c, r in cubes:
            assert np.all(c >= lower) and np.all(c <= upper), (a, b)
            for oc, oh in obstacles:
                free = boxes_apart(c, r, CUBE_HALF, np.broadcast_to(oc, c.shape), fixed, oh)
                assert free.all(), (a, b, t[~free][0], oc)
        free = boxes_apart(cubes[0][0], cubes[0][1], CUBE_HALF, cubes[1][0], cubes[1][1], CUBE_HALF)
        assert free.all(), (a, b, t[~free][0])


def test_two_cubes_go_into_their_boxes_and_are_rechecked_with_numpy():
    scene = viaroad.Scene.load(CUBES2)
    assert scene.dof == 14
    obstacles = box_walls(CUBES2.read_text())
    assert len(obstacles) == 10
    rm = viaroad.Roadmap.build(scene, nodes=300, seed=1)
    start, goal = scene.queries()[0]
    r = rm.query(start, goal, time=30.0)
    assert r.solved and r.error is None
    for path in (r.path, r.shortened):
        check_path_in_space(path, start, goal, obstacles, scene.lower[:3], scene.upper[:3])
    # the library's certificate agrees, and flags the cubes dropped straight through the walls
    assert scene.certify(r.shortened, motion="direct")["status"] == "free"
    assert scene.certify(np.array([start, goal]))["status"] == "collides"


def test_the_numpy_check_refuses_a_cube_through_a_wall():
    obstacles = box_walls(CUBES2.read_text())
    still = [0.0, 0.0, 0.0, 1.0]
    # the red cube slides sideways out of its box through the wall at -x
    a = np.array([-1.25, 0.0, 0.55, *still, 1.25, 0.0, 0.55, *still])
    b = np.array([-2.5, 0.0, 0.55, *still, 1.25, 0.0, 0.55, *still])
    try:
        check_path_in_space([a, b], a, b, obstacles, np.array([-3.25, -3.0, -1.0]), np.array([3.25, 3.0, 4.0]))
    except AssertionError:
        return
    raise AssertionError("a cube passing through a wall passed the check")
