"""Several bodies in space from Python: two cubes put into their boxes (SE(3)^2), learnt and
answered through a roadmap, and both paths re-checked here with numpy (separating axes between
each turned cube and every box wall and between the two cubes, at states along each motion at
most STEP apart for any point of a cube), independently of the library's oracle and checker;
then `Scene.certify` on the same path."""

import math
import re
from pathlib import Path

import numpy as np

import viaroad

ROOT = Path(__file__).resolve().parents[2]
CUBES2 = ROOT / "scenes" / "bodies" / "cubes-into-boxes-2.toml"
STEP = 0.01  # the farthest any point of a cube moves between two checked states (clearance 0.05)
HALF = np.array([0.5, 0.5, 0.5])


def walls(text):
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


def apart(ca, ra, ha, cb, rb, hb):
    """Whether two boxes (centre, rotation whose columns are the axes, half extents) are
    strictly apart: some axis of the fifteen of the separating-axis test separates them
    (touching counts as collision)."""
    axes = [ra[:, i] for i in range(3)] + [rb[:, i] for i in range(3)]
    axes += [np.cross(ra[:, i], rb[:, j]) for i in range(3) for j in range(3)]
    d = cb - ca
    for n in axes:
        if np.dot(n, n) < 1e-12:
            continue
        reach = np.sum(np.abs(ra.T @ n) * ha) + np.sum(np.abs(rb.T @ n) * hb)
        if abs(np.dot(n, d)) > reach:
            return True
    return False


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


def rodrigues(axis, angle):
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def check_path(path, start, goal, obstacles, lower, upper):
    path = np.asarray(path)
    assert path.ndim == 2 and path.shape[1] == 14 and len(path) >= 2
    assert np.allclose(path[0], start, atol=1e-9) and np.allclose(path[-1], goal, atol=1e-9)
    radius = float(np.linalg.norm(HALF))
    fixed = np.eye(3)
    for a, b in zip(path[:-1], path[1:]):
        moves = []
        for i in range(2):
            pa, pb = a[7 * i : 7 * i + 3], b[7 * i : 7 * i + 3]
            axis, angle, ra = turn(a[7 * i + 3 : 7 * i + 7], b[7 * i + 3 : 7 * i + 7])
            moves.append((pa, pb - pa, axis, angle, ra))
        reach = max(np.linalg.norm(d) + radius * angle for _, d, _, angle, _ in moves)
        for t in np.linspace(0.0, 1.0, int(math.ceil(reach / STEP)) + 1):
            cubes = [(p + t * d, rodrigues(axis, t * angle) @ ra) for p, d, axis, angle, ra in moves]
            for c, r in cubes:
                assert np.all(c >= lower) and np.all(c <= upper), (t, c)
                for oc, oh in obstacles:
                    assert apart(c, r, HALF, oc, fixed, oh), (a, b, t, oc)
            assert apart(cubes[0][0], cubes[0][1], HALF, cubes[1][0], cubes[1][1], HALF), (a, b, t)


def test_two_cubes_go_into_their_boxes_and_are_rechecked_with_numpy():
    scene = viaroad.Scene.load(CUBES2)
    assert scene.dof == 14
    obstacles = walls(CUBES2.read_text())
    assert len(obstacles) == 10
    rm = viaroad.Roadmap.build(scene, nodes=300, seed=1)
    start, goal = scene.queries()[0]
    r = rm.query(start, goal, time=30.0)
    assert r.solved and r.error is None
    for path in (r.path, r.shortened):
        check_path(path, start, goal, obstacles, scene.lower[:3], scene.upper[:3])
    # the library's certificate agrees, and flags the cubes dropped straight through the walls
    assert scene.certify(r.shortened, motion="direct")["status"] == "free"
    assert scene.certify(np.array([start, goal]))["status"] == "collides"


def test_the_numpy_check_refuses_a_cube_through_a_wall():
    obstacles = walls(CUBES2.read_text())
    still = [0.0, 0.0, 0.0, 1.0]
    # the red cube slides sideways out of its box through the wall at -x
    a = np.array([-1.25, 0.0, 0.55, *still, 1.25, 0.0, 0.55, *still])
    b = np.array([-2.5, 0.0, 0.55, *still, 1.25, 0.0, 0.55, *still])
    try:
        check_path([a, b], a, b, obstacles, np.array([-3.25, -3.0, -1.0]), np.array([3.25, 3.0, 4.0]))
    except AssertionError:
        return
    raise AssertionError("a cube passing through a wall passed the check")
