"""viaroad: multi-query motion planning from Python.

A probabilistic roadmap (Overmars and Švestka) whose local method is the recursive via-point
planner of Chadzelek, Hotz and Schömer: it asks the scene for *all* collision intervals of a
straight motion instead of sampling along it.

    import viaroad
    scene = viaroad.Scene.load("scenes/discs-cluttered.toml")
    rm = viaroad.Roadmap.build(scene, nodes=1000, seed=1)
    res = rm.query([0.02, 0.98], [0.98, 0.02])
    res.solved, res.shortened            # an (k, dof) numpy array

Errors are `ViaroadError` subclasses carrying the command line's one-line messages.
"""

from ._viaroad import (
    LearnError,
    MotionError,
    QueryError,
    QueryResult,
    Roadmap,
    RoadmapError,
    Scene,
    SceneError,
    ViaroadError,
    __version__,
)



def _scene_from_file(path):
    """Unpickles a `Scene`: loads its file again."""
    return Scene.load(path)


def _scene_from_moveit(robot, scene, request):
    """Unpickles a `Scene` of `Scene.load_moveit`: loads its three files again."""
    return Scene.load_moveit(robot, scene, request)


def _roadmap_from_bytes(data, scene):
    """Unpickles a `Roadmap`: its file's bytes, checked against its scene."""
    return Roadmap.from_bytes(data, scene)


__all__ = [
    "Scene",
    "Roadmap",
    "QueryResult",
    "ViaroadError",
    "SceneError",
    "RoadmapError",
    "QueryError",
    "LearnError",
    "MotionError",
    "__version__",
]
