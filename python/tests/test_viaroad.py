"""The `viaroad` Python package: a disc scene and an OMPL.app scene solved from
Python, every returned path re-checked by a check written here (segment-disc distance in numpy
for discs; straight single-group motions sampled densely for the planar OMPL.app scene), a
roadmap file round-tripped, parallel and threaded queries equal to single ones, and every kind
of error raised as a `ViaroadError` with the command line's one-line message."""

import math
import re
import subprocess
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import viaroad

ROOT = Path(__file__).resolve().parents[2]
DISCS = ROOT / "scenes" / "discs-cluttered.toml"
DISCS_MAP = ROOT / "roadmaps" / "discs-cluttered.bin"
PLANAR = ROOT / "scenes" / "ompl" / "2D" / "BugTrap_planar.cfg"
ARM = ROOT / "scenes" / "arms" / "panda-box-1.toml"
CLI = ROOT / "target" / "release" / "viaroad"


def discs_of(path):
    """The discs of a TOML disc scene, read with a regular expression (not the loader)."""
    text = path.read_text()
    found = re.findall(
        r"disc\s*=\s*\{\s*center\s*=\s*\[([^\]]*)\]\s*,\s*radius\s*=\s*([0-9.eE+-]+)", text
    )
    centres = np.array([[float(x) for x in c.split(",")] for c, _ in found])
    radii = np.array([float(r) for _, r in found])
    assert len(radii) == 80
    return centres, radii


def segment_disc_clearance(a, b, centres, radii):
    """The least distance from segment a-b to a disc's boundary (negative: it enters)."""
    ab = b - a
    den = float(ab @ ab)
    t = np.zeros(len(centres)) if den == 0 else np.clip((centres - a) @ ab / den, 0.0, 1.0)
    nearest = a + t[:, None] * ab
    return float(np.min(np.linalg.norm(centres - nearest, axis=1) - radii))


def check_disc_path(path, start, goal, centres, radii):
    path = np.asarray(path)
    assert path.ndim == 2 and path.shape[1] == 2 and len(path) >= 2
    assert np.allclose(path[0], start, atol=1e-12) and np.allclose(path[-1], goal, atol=1e-12)
    assert np.all(path >= 0.0) and np.all(path <= 1.0)
    for a, b in zip(path[:-1], path[1:]):
        # touching counts as collision
        assert segment_disc_clearance(a, b, centres, radii) > 0.0, (a, b)


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def check_planar_path(scene, path, start, goal, samples_per_unit=400):
    """SE(2) paths: corners free, each step a translation or a turn (never both), and the
    motion free at dense samples (translation linear, turn the shortest way)."""
    path = np.asarray(path)
    assert path.ndim == 2 and path.shape[1] == 3 and len(path) >= 2
    assert np.allclose(path[0], start, atol=1e-9) and np.allclose(path[-1], goal, atol=1e-9)
    for a, b in zip(path[:-1], path[1:]):
        moved = np.linalg.norm(b[:2] - a[:2]) > 1e-12
        turned = abs(wrap(b[2] - a[2])) > 1e-12
        assert not (moved and turned), (a, b)
        span = np.linalg.norm(b[:2] - a[:2]) + abs(wrap(b[2] - a[2]))
        n = max(8, int(span * samples_per_unit))
        for t in np.linspace(0.0, 1.0, n + 1):
            q = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), wrap(a[2] + t * wrap(b[2] - a[2]))]
            assert scene.is_free(q), (a, b, t)


@pytest.fixture(scope="module")
def discs():
    return viaroad.Scene.load(DISCS)


@pytest.fixture(scope="module")
def discs_map(discs):
    return viaroad.Roadmap.load(DISCS_MAP, discs)


def test_disc_scene_learnt_in_python_answers_valid_paths(discs):
    centres, radii = discs_of(DISCS)
    seen = []
    rm = viaroad.Roadmap.build(discs, nodes=400, seed=3, progress=seen.append)
    info = rm.info()
    assert info["nodes"] >= 400 and info["edges"] > 0 and info["seed"] == 3
    assert seen and seen[-1]["nodes"] == info["nodes"]
    assert all(seen[i]["rounds"] < seen[i + 1]["rounds"] for i in range(len(seen) - 1))
    free = discs.sample_free(120, seed=1)
    starts, goals = free[:60], free[60:]
    answers = rm.query_many(starts, goals)
    assert len(answers) == 60
    solved = 0
    for s, g, r in zip(starts, goals, answers):
        assert r.error is None
        if r.solved:
            solved += 1
            check_disc_path(r.path, s, g, centres, radii)
            check_disc_path(r.shortened, s, g, centres, radii)
            assert r.length <= r.raw_length + 1e-9
            assert r.calls > 0 and r.ms >= 0.0
        else:
            assert r.path.shape == (0, 2)
    assert solved >= 54, solved
    # the scene's own query, from lists
    s, g = discs.queries()[0]
    r = rm.query(list(s), tuple(g))
    assert r.solved
    check_disc_path(r.shortened, s, g, centres, radii)


def test_parallel_and_threaded_queries_equal_single_ones(discs, discs_map):
    free = discs.sample_free(40, seed=2)
    starts, goals = free[:20], free[20:]
    many = discs_map.query_many(starts, goals)
    single = [discs_map.query(s, g) for s, g in zip(starts, goals)]
    with ThreadPoolExecutor(4) as pool:
        threaded = list(pool.map(lambda p: discs_map.query(*p), zip(starts, goals)))
    for m, s, t in zip(many, single, threaded):
        assert m.solved == s.solved == t.solved
        assert m.outcome == s.outcome == t.outcome
        # landmarks guide the batch's A*, not a single query's: the same shortest-path
        # problem, so the same length
        assert m.raw_length == pytest.approx(s.raw_length, rel=1e-9)
        np.testing.assert_array_equal(s.shortened, t.shortened)
        np.testing.assert_array_equal(s.path, t.path)


def test_roadmap_file_round_trip(discs, tmp_path):
    rm = viaroad.Roadmap.build(discs, nodes=200, seed=5)
    f = tmp_path / "discs.bin"
    rm.save(f)
    back = viaroad.Roadmap.load(str(f), discs)
    assert back.info() == rm.info()
    free = discs.sample_free(20, seed=4)
    for a, b in zip(rm.query_many(free[:10], free[10:]), back.query_many(free[:10], free[10:])):
        assert a.solved == b.solved
        np.testing.assert_array_equal(a.path, b.path)
        np.testing.assert_array_equal(a.shortened, b.shortened)
    # the same seed and node budget learn the same roadmap
    again = viaroad.Roadmap.build(discs, nodes=200, seed=5)
    g = tmp_path / "again.bin"
    again.save(g)
    assert g.read_bytes() == f.read_bytes()


def test_ompl_app_planar_scene(tmp_path):
    scene = viaroad.Scene.load(PLANAR)
    assert scene.dof == 3 and scene.space == "se2"
    rm = viaroad.Roadmap.build(scene, nodes=200, seed=5)
    free = scene.sample_free(16, seed=5)
    answers = rm.query_many(free[:8], free[8:], time=20.0)
    solved = 0
    for s, g, r in zip(free[:8], free[8:], answers):
        assert r.error is None
        if r.solved:
            solved += 1
            check_planar_path(scene, r.path, s, g)
            check_planar_path(scene, r.shortened, s, g)
    assert solved >= 4, solved
    # the scene's own query
    s, g = scene.queries()[0]
    r = rm.query(s, g, time=30.0)
    if r.solved:
        check_planar_path(scene, r.shortened, s, g)


def test_intervals_agree_with_disc_geometry(discs):
    centres, radii = discs_of(DISCS)
    rng = np.random.default_rng(7)
    for _ in range(50):
        a, b = rng.uniform(0, 1, 2), rng.uniform(0, 1, 2)
        ivs = discs.intervals(a, b)
        assert ivs.ndim == 2 and ivs.shape[1] == 2
        assert np.all(ivs[:, 0] <= ivs[:, 1])
        assert np.all(ivs[1:, 0] > ivs[:-1, 1])  # sorted and disjoint
        # brute force: a sample collides exactly where an interval says so
        for t in np.linspace(0, 1, 201):
            p = a + t * (b - a)
            inside = np.any(np.linalg.norm(centres - p, axis=1) < radii - 1e-9)
            clear = np.all(np.linalg.norm(centres - p, axis=1) > radii + 1e-9)
            covered = np.any((ivs[:, 0] <= t) & (t <= ivs[:, 1]))
            if inside:
                assert covered, (a, b, t)
            if clear and covered:
                # only the bounds' own intervals remain (the box is [0, 1]^2 here)
                assert np.any((p < 0) | (p > 1)), (a, b, t)
        assert discs.is_free(a) == (not np.any(np.linalg.norm(centres - a, axis=1) <= radii))


def cli_error(*args):
    """The one-line message the command line prints for `args`, without `error: `."""
    if not CLI.exists():
        pytest.skip("the release binary is not built")
    o = subprocess.run([str(CLI), *args], cwd=ROOT, capture_output=True, text=True)
    assert o.returncode == 1, o
    (line,) = [l for l in o.stderr.splitlines() if l.startswith("error: ")]
    return line[len("error: "):]


def test_errors_are_exceptions_with_the_cli_messages(discs, discs_map, tmp_path):
    for exc in (viaroad.SceneError, viaroad.RoadmapError, viaroad.QueryError, viaroad.LearnError, viaroad.MotionError):
        assert issubclass(exc, viaroad.ViaroadError)
    q = ["query", str(DISCS_MAP), "--scene", str(DISCS)]
    with pytest.raises(viaroad.QueryError) as e:
        discs_map.query([0.5, 0.5], [0.02, 0.98])
    assert str(e.value) == cli_error(*q, "--from", "0.5,0.5", "--to", "0.02,0.98")
    with pytest.raises(viaroad.QueryError) as e:
        discs_map.query([0.02, 0.98], [0.5])
    assert str(e.value) == cli_error(*q, "--from", "0.02,0.98", "--to", "0.5")
    with pytest.raises(viaroad.QueryError) as e:
        discs_map.query([0.02, 0.98], [1.5, 0.5])
    assert str(e.value) == cli_error(*q, "--from", "0.02,0.98", "--to", "1.5,0.5")
    missing = tmp_path / "missing.toml"
    with pytest.raises(viaroad.SceneError) as e:
        viaroad.Scene.load(missing)
    assert str(e.value) == cli_error("probe", str(missing), "--from", "0,0", "--to", "1,1")
    bad = tmp_path / "bad.toml"
    bad.write_text("name = 3\n[space\n")
    with pytest.raises(viaroad.SceneError) as e:
        viaroad.Scene.load(bad)
    assert str(e.value) == cli_error("probe", str(bad), "--from", "0,0", "--to", "1,1")
    other = viaroad.Scene.load(ROOT / "scenes" / "discs-example.toml")
    with pytest.raises(viaroad.RoadmapError) as e:
        viaroad.Roadmap.load(DISCS_MAP, other)
    assert str(e.value) == cli_error("query", str(DISCS_MAP), "--scene", "scenes/discs-example.toml", "--from", "0.1,0.1", "--to", "0.2,0.2")
    with pytest.raises(viaroad.RoadmapError):
        viaroad.Roadmap.load(DISCS, discs)  # not a roadmap file
    with pytest.raises(viaroad.RoadmapError):
        discs_map.save(tmp_path / "no" / "such" / "dir" / "x.bin")
    # inputs Python users get wrong: a clear QueryError, never a crash
    for s, g in [("ab", [0.1, 0.1]), ([[0.1, 0.1]], [0.2, 0.2]), ([float("nan"), 0.1], [0.2, 0.2]), (None, [0.1, 0.1])]:
        with pytest.raises(viaroad.QueryError):
            discs_map.query(s, g)
    with pytest.raises(viaroad.QueryError, match="shorten"):
        discs_map.query([0.02, 0.98], [0.98, 0.02], shorten="best")
    with pytest.raises(viaroad.QueryError, match="time"):
        discs_map.query([0.02, 0.98], [0.98, 0.02], time=-1.0)
    with pytest.raises(viaroad.QueryError, match="3 starts but 2 goals"):
        discs_map.query_many(np.zeros((3, 2)), np.zeros((2, 2)))
    # in a batch, a bad row is an answer with its error; the others are answered
    out = discs_map.query_many([[0.5, 0.5], [0.02, 0.98]], [[0.98, 0.02], [0.98, 0.02]])
    assert out[0].error == "start [0.5, 0.5] is in collision" and not out[0].solved
    assert out[1].solved and out[1].error is None
    with pytest.raises(viaroad.QueryError):
        discs.is_free([0.1])
    with pytest.raises(viaroad.LearnError):
        viaroad.Roadmap.build(discs, nodes=0)
    with pytest.raises(viaroad.LearnError):
        viaroad.Roadmap.build(discs, nodes=10, local="teleport")
    planar = viaroad.Scene.load(PLANAR)
    with pytest.raises(viaroad.MotionError):
        planar.intervals([0, 0, 0], [1, 1, 1])
    # an exception in the progress callback stops learning and reaches the caller
    def stop(_):
        raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        viaroad.Roadmap.build(discs, nodes=100_000, progress=stop)


def test_queries_release_the_interpreter(discs, discs_map):
    """Another Python thread runs while a batch is answered."""
    free = discs.sample_free(400, seed=9)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        for _ in range(5):
            discs_map.query_many(free[:200], free[200:])
    finally:
        done.set()
        t.join()
    assert len(ticks) > 1


def test_the_checks_here_refuse_colliding_paths(discs):
    """A check that accepts everything would make the tests above meaningless."""
    centres, radii = discs_of(DISCS)
    s, g = discs.queries()[0]
    assert len(discs.intervals(s, g)) > 0  # the straight line crosses discs
    with pytest.raises(AssertionError):
        check_disc_path([s, g], s, g, centres, radii)
    # grazing a disc counts as collision
    c, r = centres[0], radii[0]
    a = c + np.array([-1.0, r]) * np.array([0.05, 1.0])
    b = c + np.array([1.0, r]) * np.array([0.05, 1.0])
    assert segment_disc_clearance(a, b, centres[:1], radii[:1]) == pytest.approx(0.0, abs=1e-12)
    planar = viaroad.Scene.load(PLANAR)
    ps, pg = planar.queries()[0]
    with pytest.raises(AssertionError):
        check_planar_path(planar, [ps, pg], ps, pg)  # translates and turns at once
    free = planar.sample_free(40, seed=11)
    blocked = [(a, b) for a, b in zip(free[:20], free[20:]) if len(planar.intervals(a, np.r_[b[:2], a[2]])) > 0]
    assert blocked
    a, b = blocked[0]
    with pytest.raises(AssertionError):
        check_planar_path(planar, [a, np.r_[b[:2], a[2]]], a, np.r_[b[:2], a[2]])


def test_an_arm_query_grows_trees_out_of_the_roadmap():
    """A Panda goal inside MotionBenchMaker's box, which a 40-node roadmap does not reach: the
    query races trees out of the roadmap, as `viaroad query` does for arms (the paths are
    certified by the independent arm checker in the Rust tests; here a segment moves one joint,
    or, where the trees extended straight or shortening cut across, several joints at once, and
    every corner, and every 50th of a straight motion, is free)."""
    scene = viaroad.Scene.load(ARM)
    assert scene.dof == 7
    rm = viaroad.Roadmap.build(scene, nodes=40, seed=1)
    s, g = scene.queries()[0]
    r = rm.query(s, g, time=30.0)
    assert r.solved and r.outcome == "trees", r.outcome
    for path in (r.path, r.shortened):
        assert list(path[0]) == list(s) and list(path[-1]) == list(g)
        assert all(scene.is_free(q) for q in path)
        for a, b in zip(path, path[1:]):
            a, b = np.asarray(a), np.asarray(b)
            if np.count_nonzero(a != b) > 1:
                assert all(scene.is_free(a + t * (b - a)) for t in np.linspace(0.0, 1.0, 51))
    assert r.length <= r.raw_length + 1e-9
