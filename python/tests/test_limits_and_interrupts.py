"""Counts past viaroad's limits are refused before anything is allocated, and Ctrl-C stops long
calls (a batch of queries, sampling, learning) promptly instead of after the whole call."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import viaroad

ROOT = Path(__file__).resolve().parents[2]
DISCS = ROOT / "scenes" / "discs-cluttered.toml"
DISCS_MAP = ROOT / "roadmaps" / "discs-cluttered.bin"
ARM = ROOT / "scenes" / "arms" / "panda-box-1.toml"

# viaroad::limits: MAX_QUERIES and MAX_NODES
MAX_QUERIES = 1_000_000
MAX_NODES = 10_000_000


@pytest.fixture(scope="module")
def discs():
    return viaroad.Scene.load(DISCS)


def test_sample_free_of_a_trillion_is_refused_before_allocating(discs):
    # in a child, so that a draw that runs (until memory runs out) fails the test, not hangs it
    code = f"""
import resource, viaroad
scene = viaroad.Scene.load({str(DISCS)!r})
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
try:
    scene.sample_free(10**12)
except ValueError as e:
    print(type(e).__name__, e)
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before)
"""
    o = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert o.returncode == 0, o.stderr
    message, grown = o.stdout.splitlines()
    assert message.startswith(f"ValueError n 1000000000000 is more than the {2 * MAX_QUERIES} viaroad accepts"), message
    # nothing was allocated (a trillion 2-d points: 16 TB)
    assert int(grown) < 50_000  # KiB
    # an int no machine holds, and a negative one: the same error, not an OverflowError
    with pytest.raises(ValueError, match="more than the"):
        discs.sample_free(10**40)
    with pytest.raises(ValueError, match="must not be negative"):
        discs.sample_free(-1)
    with pytest.raises(TypeError):
        discs.sample_free(3.5)
    # an empty draw, and numpy ints, are fine
    assert discs.sample_free(0).shape == (0, 2)
    assert discs.sample_free(np.int64(5), seed=3).shape == (5, 2)


def test_counts_past_the_cli_bounds_are_refused_in_every_entry_point(discs):
    rm = viaroad.Roadmap.load(DISCS_MAP, discs)
    too_many = np.full((MAX_QUERIES + 1, 2), 0.5)
    with pytest.raises(ValueError, match=f"starts: {MAX_QUERIES + 1} rows is more than the {MAX_QUERIES} viaroad accepts"):
        rm.query_many(too_many, too_many)
    del too_many
    # learning: the node bound, for ints of any size (LearnError, as for nodes=0)
    for n in (MAX_NODES + 1, 10**30):
        with pytest.raises(viaroad.LearnError, match=f"is more than the {MAX_NODES} viaroad accepts"):
            viaroad.Roadmap.build(discs, nodes=n)
    with pytest.raises(viaroad.LearnError, match="nodes must be at least 1"):
        viaroad.Roadmap.build(discs, nodes=-5)
    # times past viaroad's longest budget
    with pytest.raises(viaroad.LearnError, match="at most 1e9"):
        viaroad.Roadmap.build(discs, time=1e300)
    with pytest.raises(viaroad.QueryError, match="at most 1e9"):
        rm.query([0.02, 0.98], [0.98, 0.02], time=1e12)
    with pytest.raises(viaroad.QueryError, match="at most 1e9"):
        rm.query_many([[0.02, 0.98]], [[0.98, 0.02]], time=float("inf"))


def interrupted(setup, call, *, before_signal=1.0):
    """Runs `setup` then `call` in a child Python, sends it SIGINT `before_signal` seconds
    into `call`, and returns (seconds from the signal to the child's exit, its output). The
    child exits 3 on KeyboardInterrupt, 0 if `call` ended before the signal."""
    code = "\n".join(
        [
            "import signal, sys, time",
            # a child started from a non-interactive shell's background job inherits SIGINT
            # ignored, and Python then installs no KeyboardInterrupt handler: restore it
            "signal.signal(signal.SIGINT, signal.default_int_handler)",
            "import numpy as np",
            "import viaroad",
            textwrap.dedent(setup),
            'print("go", flush=True)',
            "try:",
            f"    {call}",
            "except KeyboardInterrupt:",
            '    print("KeyboardInterrupt", flush=True)',
            "    sys.exit(3)",
            'print("finished", flush=True)',
        ]
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert p.stdout.readline().strip() == "go", p.stderr.read()
        time.sleep(before_signal)
        os.kill(p.pid, signal.SIGINT)
        sent = time.monotonic()
        out, err = p.communicate(timeout=120)
        took = time.monotonic() - sent
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert p.returncode == 3, (p.returncode, out, err)
    assert "KeyboardInterrupt" in out
    return took


# In the child: `starts` and `goals` repeated into a batch of at least `seconds` of work on
# this machine's cores (as single queries of them measure it), up to the most a batch holds.
BATCH_OF = f"""
import os
def batch_of(rm, starts, goals, seconds=60.0, **options):
    n = len(starts)
    t = time.monotonic()
    for s, g in zip(starts[:50], goals[:50]):
        rm.query(s, g, **options)
    per_query = (time.monotonic() - t) / min(n, 50) / len(os.sched_getaffinity(0))
    size = min({MAX_QUERIES}, max(n, int(seconds / per_query)))
    print("batch of", size, "expected", size * per_query, "s", file=sys.stderr, flush=True)
    rows = np.arange(size) % n
    return starts[rows], goals[rows]
"""


def test_ctrl_c_stops_query_many_within_about_a_query():
    """A batch of disc queries worth a minute or more (up to a million of them) is stopped a
    second in: KeyboardInterrupt within seconds, not after the whole batch."""
    setup = BATCH_OF + f"""
scene = viaroad.Scene.load({str(DISCS)!r})
rm = viaroad.Roadmap.load({str(DISCS_MAP)!r}, scene)
free = scene.sample_free(4000, seed=5)
starts, goals = batch_of(rm, free[:2000], free[2000:], time=None, grow=False)
"""
    took = interrupted(setup, "rm.query_many(starts, goals, time=None, grow=False)")
    assert took < 10.0, took


def test_ctrl_c_stops_an_arm_batch_racing_trees():
    """Panda queries that race trees out of a 40-node roadmap (the arm's race path), a minute's
    worth of them or more: stopped a second in, not after the batch."""
    setup = BATCH_OF + f"""
scene = viaroad.Scene.load({str(ARM)!r})
rm = viaroad.Roadmap.build(scene, nodes=40, seed=1)
s, g = scene.queries()[0]
assert rm.query(s, g, time=30.0).outcome == "trees"
starts, goals = batch_of(rm, np.tile(s, (5, 1)), np.tile(g, (5, 1)), time=30.0)
"""
    took = interrupted(setup, "rm.query_many(starts, goals, time=30.0)")
    assert took < 10.0, took


def test_ctrl_c_stops_sampling_learning_and_a_long_query():
    """Two million free Panda configurations (half a minute or more), learning a Panda roadmap
    for ten minutes, and a query shortened exactly along a 2-node roadmap (seconds): each
    stopped a second in."""
    arm = f"scene = viaroad.Scene.load({str(ARM)!r})"
    assert interrupted(arm, "scene.sample_free(2_000_000)") < 10.0
    assert interrupted(arm, "viaroad.Roadmap.build(scene, time=600.0)") < 10.0
    setup = arm + "\nrm = viaroad.Roadmap.build(scene, nodes=2, seed=1)\ns, g = scene.queries()[0]"
    assert interrupted(setup, "rm.query(s, g, time=None, grow=False, shorten='exact')") < 10.0


def test_progress_runs_on_the_calling_thread_and_its_exception_stops_learning(discs):
    seen = []

    def progress(p):
        seen.append(threading.get_ident())
        if p["nodes"] >= 200:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        viaroad.Roadmap.build(discs, nodes=MAX_NODES, progress=progress)
    assert seen and set(seen) == {threading.get_ident()}
