"""An independent check of disc-scene paths for the shard and Ray tests: the discs read from the
TOML text with a regular expression (not the loader), segment-disc distances in numpy."""

import re

import numpy as np


def discs_of(path):
    """The discs of a TOML disc scene as (centres, radii)."""
    found = re.findall(
        r"disc\s*=\s*\{\s*center\s*=\s*\[([^\]]*)\]\s*,\s*radius\s*=\s*([0-9.eE+-]+)",
        path.read_text(),
    )
    centres = np.array([[float(x) for x in c.split(",")] for c, _ in found])
    radii = np.array([float(r) for _, r in found])
    assert len(radii) > 0
    return centres, radii


def segment_clear(a, b, centres, radii):
    """Whether the segment a-b stays in the unit square and out of every disc (touching is
    collision)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if np.any(np.concatenate([a, b]) < 0.0) or np.any(np.concatenate([a, b]) > 1.0):
        return False
    ab = b - a
    den = float(ab @ ab)
    t = np.zeros(len(centres)) if den == 0 else np.clip((centres - a) @ ab / den, 0.0, 1.0)
    nearest = a + t[:, None] * ab
    return bool(np.min(np.linalg.norm(centres - nearest, axis=1) - radii) > 0.0)


def path_clear(path, centres, radii):
    """Every consecutive pair of `path` is a clear segment."""
    path = np.asarray(path)
    return len(path) >= 2 and all(
        segment_clear(a, b, centres, radii) for a, b in zip(path[:-1], path[1:])
    )


def edges_clear(roadmap, centres, radii, sample=None, seed=0):
    """Edges of `roadmap` that are not clear (all of them, or a seeded sample of `sample`)."""
    m = roadmap.info()["edges"]
    idx = range(m)
    if sample is not None and sample < m:
        idx = np.random.default_rng(seed).choice(m, size=sample, replace=False)
    return [int(i) for i in idx if not path_clear(roadmap.edge_path(int(i)), centres, radii)]
