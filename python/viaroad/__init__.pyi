"""Type stubs of the `viaroad` package (the extension module `viaroad._viaroad`)."""

import os
from typing import Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
ArrayLike1 = Union[Sequence[float], npt.NDArray[np.float64]]
ArrayLike2 = Union[Sequence[Sequence[float]], npt.NDArray[np.float64]]

class ViaroadError(Exception):
    """Base of every error viaroad raises; its message is the command line's one-line message."""

class SceneError(ViaroadError):
    """A scene file that cannot be read or makes no sense."""

class RoadmapError(ViaroadError):
    """A roadmap file that cannot be read, written, or belongs to another scene."""

class QueryError(ViaroadError):
    """A configuration that cannot be asked about: wrong length, not finite, outside the bounds, in collision."""

class LearnError(ViaroadError):
    """Learning could not run: no budget, a parameter out of range, an unknown local method."""

class MotionError(ViaroadError):
    """No straight motion joins the two configurations, or the oracle cannot answer it."""

class Scene:
    """A robot, its obstacles and configuration space, from a viaroad TOML file or an OMPL.app `.cfg`."""

    @staticmethod
    def load(path: PathLike) -> "Scene":
        """Loads a scene (`.toml` or `.cfg`); raises `SceneError`. Loader warnings become `UserWarning`s."""
    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int:
        """Degrees of freedom: the length of a configuration."""
    @property
    def space(self) -> str:
        """The space's kind: `r2`, `se2`, `se3`, ..."""
    @property
    def lower(self) -> npt.NDArray[np.float64]: ...
    @property
    def upper(self) -> npt.NDArray[np.float64]: ...
    def queries(self) -> list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
        """The scene's own queries, checked and normalised, as (start, goal) pairs."""
    def is_free(self, q: ArrayLike1) -> bool:
        """Whether `q` is in the bounds and collision-free; `QueryError` for a malformed `q`."""
    def intervals(self, q_from: ArrayLike1, q_to: ArrayLike1) -> npt.NDArray[np.float64]:
        """The exact collision intervals of the straight motion `q_from` -> `q_to` as an (m, 2) array of [lo, hi] in t in [0, 1]."""
    def sample_free(self, n: int, seed: int = 0) -> npt.NDArray[np.float64]:
        """`n` seeded uniform collision-free configurations, an (n, dof) array; `ValueError` for
        `n` beyond 2 000 000 (the ends of the most queries `query_many` takes). Ctrl-C stops it."""

class QueryResult:
    """The answer to one query."""

    solved: bool
    outcome: str
    """`direct`, `roadmap`, `grown`, `trees`, `not_attached`, `disconnected`, `timed_out`, `out_of_calls` or `error`."""
    path: npt.NDArray[np.float64]
    """The path as found, (k, dof)."""
    shortened: npt.NDArray[np.float64]
    """The shortened path, (k, dof)."""
    length: float
    raw_length: float
    calls: int
    """Collision-interval calls the query made."""
    depth: int
    grown_nodes: int
    ms: float
    """Milliseconds the Rust call took."""
    error: Optional[str]
    """Why the query could not be asked (only from `query_many`)."""

class Roadmap:
    """A roadmap learnt for one scene; queries never change it."""

    @staticmethod
    def build(
        scene: Scene,
        *,
        time: Optional[float] = None,
        nodes: Optional[int] = None,
        seed: int = 1,
        local: Optional[str] = None,
        progress: Optional[Callable[[dict], None]] = None,
        shard: Optional[tuple[int, int]] = None,
    ) -> "Roadmap":
        """Learns a roadmap until `nodes` nodes (at most 10 000 000) or `time` seconds (1000 nodes
        if neither); releases the GIL; `LearnError`. `progress` runs on the calling thread; its
        exception, or Ctrl-C, stops learning. `shard=(i, n)` (1 <= i <= n) learns shard i of n:
        its own random streams and its share of `nodes`, for `Roadmap.merge`."""
    @staticmethod
    def merge(
        parts: Sequence["Roadmap"],
        scene: Scene,
        *,
        time: Optional[float] = None,
        into: Optional["Roadmap"] = None,
    ) -> "Roadmap":
        """Joins roadmaps of `scene` learnt apart: their union, then connections across parts.
        The same parts give the same roadmap in any order; `into` keeps its node indices.
        `RoadmapError` for a part of another scene or local method. Releases the GIL."""
    @staticmethod
    def from_bytes(data: bytes, scene: Scene) -> "Roadmap":
        """A roadmap from a file's bytes, checked like `load`; `RoadmapError`."""
    def to_bytes(self) -> bytes:
        """The roadmap file's bytes; a `Roadmap` pickles through them (and its scene's path)."""
    def digest(self) -> int:
        """A digest of the content: equal roadmaps, equal digests."""
    def nodes(self) -> npt.NDArray[np.float64]:
        """The nodes, (n, dof), in index order."""
    def edge_ends(self) -> npt.NDArray[np.uint32]:
        """The edges' end nodes, (m, 2)."""
    def edge_path(self, i: int) -> npt.NDArray[np.float64]:
        """Edge i's path from its first end to its second, corners included, (k, dof)."""
    @staticmethod
    def load(path: PathLike, scene: Scene) -> "Roadmap":
        """Reads a roadmap file learnt for `scene`; `RoadmapError`."""
    def save(self, path: PathLike) -> None:
        """Saves atomically; `RoadmapError`."""
    @property
    def scene(self) -> Scene: ...
    def info(self) -> dict:
        """What `viaroad info --json` prints: nodes, edges, components, parameters, ..."""
    def query(
        self,
        start: ArrayLike1,
        goal: ArrayLike1,
        *,
        shorten: str = "fast",
        time: Optional[float] = 10.0,
        grow: bool = True,
    ) -> QueryResult:
        """Answers one query; `QueryError` for an invalid start or goal. An arm grows trees out of
        the roadmap, racing its search, where `grow` (as `viaroad query`). Releases the GIL;
        Ctrl-C stops it."""
    def query_many(
        self,
        starts: ArrayLike2,
        goals: ArrayLike2,
        *,
        shorten: str = "fast",
        time: Optional[float] = 10.0,
        grow: bool = True,
    ) -> list[QueryResult]:
        """Answers (n, dof) queries in parallel; invalid rows get `error` set instead of raising.
        `ValueError` for more than 1 000 000 rows. Ctrl-C stops the batch within about one
        query's time (`KeyboardInterrupt`)."""
