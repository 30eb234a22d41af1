"""Shards and merges from Python: shards reproducible, roadmaps pickled through their bytes, a
merge the same in any order and valid by an independent check of every edge, answering the
queries its parts answer, parts of another scene refused, a base keeping its node indices."""

import pickle
from pathlib import Path

import numpy as np
import pytest

import viaroad
from disc_check import discs_of, edges_clear, path_clear

ROOT = Path(__file__).resolve().parents[2]
DISCS = ROOT / "scenes" / "discs-cluttered.toml"
OTHER = ROOT / "scenes" / "discs-example.toml"


@pytest.fixture(scope="module")
def scene():
    return viaroad.Scene.load(DISCS)


@pytest.fixture(scope="module")
def parts(scene):
    return [viaroad.Roadmap.build(scene, nodes=600, seed=3, shard=(i, 3)) for i in (1, 2, 3)]


def test_shards_are_reproducible_and_split_the_budget(scene, parts):
    again = viaroad.Roadmap.build(scene, nodes=600, seed=3, shard=(2, 3))
    assert again.to_bytes() == parts[1].to_bytes()
    assert len({p.info()["seed"] for p in parts}) == 3
    assert all(p.info()["node_budget"] == 200 for p in parts)
    with pytest.raises(viaroad.LearnError, match="does not exist"):
        viaroad.Roadmap.build(scene, nodes=10, shard=(4, 3))


def test_a_roadmap_pickles_through_its_bytes(scene, parts):
    back = pickle.loads(pickle.dumps(parts[0]))
    assert back.to_bytes() == parts[0].to_bytes()
    assert back.digest() == parts[0].digest()
    assert back.scene.name == scene.name
    s = pickle.loads(pickle.dumps(scene))
    assert (s.name, s.dof) == (scene.name, scene.dof)
    assert viaroad.Roadmap.from_bytes(parts[0].to_bytes(), scene).digest() == parts[0].digest()


def test_merge_is_order_independent_valid_and_answers(scene, parts):
    merged = viaroad.Roadmap.merge(parts, scene)
    for order in ([2, 0, 1], [1, 2, 0]):
        assert viaroad.Roadmap.merge([parts[i] for i in order], scene).to_bytes() == (
            merged.to_bytes()
        )
    centres, radii = discs_of(DISCS)
    assert edges_clear(merged, centres, radii) == []
    nodes = merged.nodes()
    for p in parts:
        own = {tuple(q) for q in nodes}
        assert all(tuple(q) in own for q in p.nodes())
    assert merged.info()["components"] < sum(p.info()["components"] for p in parts)
    pairs = scene.sample_free(60, seed=9)
    starts, goals = pairs[:30], pairs[30:]
    by_part = np.zeros(30, bool)
    for p in parts:
        by_part |= [r.solved for r in p.query_many(starts, goals, grow=False)]
    answers = merged.query_many(starts, goals, grow=False)
    assert by_part.sum() >= 15
    for k, r in enumerate(answers):
        assert r.solved or not by_part[k], k
        if r.solved:
            assert path_clear(r.shortened, centres, radii)
            assert path_clear(r.path, centres, radii)


def test_merge_refuses_another_scene_and_keeps_a_base(scene, parts):
    other = viaroad.Scene.load(OTHER)
    with pytest.raises(viaroad.RoadmapError, match="another scene"):
        viaroad.Roadmap.merge(parts, other)
    with pytest.raises(viaroad.RoadmapError, match="nothing to merge"):
        viaroad.Roadmap.merge([], scene)
    base = viaroad.Roadmap.merge(parts[:2], scene)
    grown = viaroad.Roadmap.merge([parts[2]], scene, into=base)
    n = base.info()["nodes"]
    assert np.array_equal(grown.nodes()[:n], base.nodes())
    m = base.info()["edges"]
    assert np.array_equal(grown.edge_ends()[:m], base.edge_ends())
    # a merge of merges holds every shard
    top = viaroad.Roadmap.merge([base, viaroad.Roadmap.merge(parts[2:], scene)], scene)
    assert top.info()["nodes"] >= sum(p.info()["nodes"] for p in parts)
