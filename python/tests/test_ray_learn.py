"""The Ray example, run on a local Ray runtime with 2 workers when `ray` is installed: the merged
roadmap's edges re-checked by an independent check on a sample, queries answered with clear
paths, and the same file from two runs."""

import importlib.util
from pathlib import Path

import pytest

import viaroad
from disc_check import discs_of, edges_clear, path_clear

ray = pytest.importorskip("ray")

ROOT = Path(__file__).resolve().parents[2]
DISCS = ROOT / "scenes" / "discs-cluttered.toml"
EXAMPLE = ROOT / "python" / "examples" / "ray_learn.py"


def example():
    spec = importlib.util.spec_from_file_location("ray_learn", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_two_workers_learn_merge_and_agree(tmp_path):
    ray_learn = example()
    outs = [tmp_path / f"run{k}.bin" for k in (1, 2)]
    for out in outs:
        ray_learn.main(
            [str(DISCS), "--workers", "2", "--nodes", "800", "--seed", "7", "--cpus", "2",
             "-o", str(out)]
        )
    assert outs[0].read_bytes() == outs[1].read_bytes()

    scene = viaroad.Scene.load(DISCS)
    merged = viaroad.Roadmap.load(outs[0], scene)
    info = merged.info()
    assert info["nodes"] >= 800
    shards = [viaroad.Roadmap.build(scene, nodes=800, seed=7, shard=(i, 2)) for i in (1, 2)]
    assert merged.to_bytes() == viaroad.Roadmap.merge(shards, scene).to_bytes()
    centres, radii = discs_of(DISCS)
    assert edges_clear(merged, centres, radii, sample=300, seed=1) == []
    pairs = scene.sample_free(40, seed=5)
    answers = merged.query_many(pairs[:20], pairs[20:], grow=False)
    assert sum(r.solved for r in answers) >= 18
    for r in answers:
        if r.solved:
            assert path_clear(r.shortened, centres, radii)
