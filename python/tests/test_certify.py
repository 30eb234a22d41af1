"""`Scene.certify` and `Scene.repair`: a path through a disc is flagged with a witness inside
the disc, a path beside it is proved free, and the repaired path passes a segment-disc distance
check written here in numpy (no code shared with the library)."""

from pathlib import Path

import numpy as np

import viaroad

ROOT = Path(__file__).resolve().parents[2]
DISCS = ROOT / "scenes" / "discs-example.toml"
CENTRE, RADIUS = np.array([0.30, 0.40]), 0.05


def segment_distance(a, b, c):
    ab, ac = b - a, c - a
    t = np.clip(ac @ ab / max(ab @ ab, 1e-300), 0.0, 1.0)
    return np.linalg.norm(a + t * ab - c)


def test_a_path_through_the_disc_collides_and_one_beside_it_is_free():
    scene = viaroad.Scene.load(DISCS)
    through = np.array([[0.02, 0.98], [0.30, 0.40], [0.98, 0.02]])
    c = scene.certify(through)
    assert c["status"] == "collides"
    assert list(c["codes"]) == [1, 1]
    w = c["witnesses"][0]
    assert np.linalg.norm(w - CENTRE) <= RADIUS
    beside = np.array([[0.02, 0.98], [0.98, 0.98], [0.98, 0.02]])
    assert scene.certify(beside)["status"] == "free"
    # no time left: undecided, never free
    assert scene.certify(beside, time=0.0)["status"] == "undecided"


def test_repair_gives_a_path_the_distance_check_accepts():
    scene = viaroad.Scene.load(DISCS)
    through = np.array([[0.02, 0.98], [0.30, 0.40], [0.98, 0.02]])
    fixed, report = scene.repair(through, time=10.0)
    assert report["certified"]
    assert report["certificate"]["status"] == "free"
    assert np.allclose(fixed[0], through[0]) and np.allclose(fixed[-1], through[-1])
    for a, b in zip(fixed[:-1], fixed[1:]):
        assert segment_distance(a, b, CENTRE) > RADIUS
