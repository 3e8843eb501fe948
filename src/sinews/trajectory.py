"""The one artifact every consumer reads: a recorded motion and its `.npz` file.

A `Trajectory` holds the node positions of one body (or one scene) per frame,
plus what a renderer or a fitness term needs to read them: the edges between
nodes, node names, radii and colours, and optionally the music's beats and the
responders' triggers, the per-node forces for a debug overlay, a rigid
figure's generalised coordinates, or for scenes whose parts appear and
vanish (balloons, babies, links) which nodes and edges show in each frame.
"""

from __future__ import annotations

import os
import zipfile
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.files import atomic_path
from sinews.limits import MAX_TRAJECTORY_BYTES

__all__ = ["NODE_SHAPES", "Trajectory", "TrajectoryError"]

FORMAT_VERSION = 1


class TrajectoryError(SinewsError):
    """A trajectory file or array that cannot be used, with a one-line reason."""


FloatArray = npt.NDArray[np.floating]

_OPTIONAL = (
    "radii", "colors", "beats", "triggers", "trigger_nodes", "forces", "qpos", "body_pos",
    "node_visible", "edge_visible", "node_shapes",
)  # fmt: skip

NODE_SHAPES = frozenset({"disc", "heart", "spike"})
"""How a node can be drawn (`Trajectory.node_shapes`)."""


@dataclass(frozen=True, eq=False)
class Trajectory:
    """Node positions over time with what is needed to draw or score them.

    Attributes:
        positions: (T, N, 2) float32, metres, y up.
        fps: frames per second; frame k is at time ``k / fps``.
        edges: (E, 2) int32 node indices.
        node_names: (N,) names, e.g. ``"l_hand"``.
        radii: (N,) float32 metres, or None.
        colors: (N, 3) uint8 RGB, or None.
        beats: (B,) float64 seconds of the music's beats, or None.
        triggers: (T, R) bool, which responder fired in each frame, or None.
        trigger_nodes: (R,) int node index of each responder in ``triggers``, or None.
        forces: (T, N, 2) float32 newtons on each node (debug overlay), or None.
        qpos: (T, nq) float64 generalised coordinates of a rigid figure, or None.
        body_pos: (T, B, 3) float32 rigid-body positions of a figure, or None.
        node_visible: (T, N) bool, which nodes show in each frame, or None (all).
        edge_visible: (T, E) bool, which edges show in each frame, or None (all).
        node_shapes: (N,) one of `NODE_SHAPES` per node, or None (all discs).
        failed: True if the simulation blew up (NaN/inf or runaway energy).
    """

    positions: FloatArray
    fps: float
    edges: npt.NDArray[np.integer]
    node_names: tuple[str, ...]
    radii: FloatArray | None = None
    colors: npt.NDArray[np.uint8] | None = None
    beats: FloatArray | None = None
    triggers: npt.NDArray[np.bool_] | None = None
    trigger_nodes: npt.NDArray[np.integer] | None = None
    forces: FloatArray | None = None
    qpos: FloatArray | None = None
    body_pos: FloatArray | None = None
    node_visible: npt.NDArray[np.bool_] | None = None
    edge_visible: npt.NDArray[np.bool_] | None = None
    node_shapes: tuple[str, ...] | None = None
    failed: bool = False

    def __post_init__(self) -> None:
        pos = np.asarray(self.positions)
        if pos.ndim != 3 or pos.shape[2] != 2:
            raise TrajectoryError(f"positions must have shape (T, N, 2), got {pos.shape}")
        if not np.isfinite(self.fps) or self.fps <= 0:
            raise TrajectoryError(f"fps must be a positive number, got {self.fps}")
        n_frames, n_nodes = pos.shape[:2]
        object.__setattr__(self, "positions", pos.astype(np.float32, copy=False))
        edges = np.asarray(self.edges, dtype=np.int32).reshape(-1, 2)
        if edges.size and (edges.min() < 0 or edges.max() >= n_nodes):
            raise TrajectoryError("edges refer to nodes that do not exist")
        object.__setattr__(self, "edges", edges)
        names = tuple(str(n) for n in self.node_names)
        if len(names) != n_nodes:
            raise TrajectoryError(f"{len(names)} node names for {n_nodes} nodes")
        object.__setattr__(self, "node_names", names)
        expected = {
            "radii": (n_nodes,),
            "colors": (n_nodes, 3),
            "forces": (n_frames, n_nodes, 2),
        }
        for name, shape in expected.items():
            value = getattr(self, name)
            if value is not None and np.shape(value) != shape:
                raise TrajectoryError(f"{name} must have shape {shape}, got {np.shape(value)}")
        if self.triggers is not None and np.shape(self.triggers)[0] != n_frames:
            raise TrajectoryError("triggers must have one row per frame")
        if self.trigger_nodes is not None:
            nodes = np.asarray(self.trigger_nodes)
            if self.triggers is None or nodes.shape != np.shape(self.triggers)[1:]:
                raise TrajectoryError("trigger_nodes must name one node per trigger column")
            if nodes.size and (nodes.min() < 0 or nodes.max() >= n_nodes):
                raise TrajectoryError("trigger_nodes refer to nodes that do not exist")
        if self.qpos is not None and np.shape(self.qpos)[0] != n_frames:
            raise TrajectoryError("qpos must have one row per frame")
        if self.body_pos is not None and np.shape(self.body_pos)[0] != n_frames:
            raise TrajectoryError("body_pos must have one row per frame")
        self._check_visibility(n_frames, n_nodes, len(edges))

    def _check_visibility(self, n_frames: int, n_nodes: int, n_edges: int) -> None:
        for name, shape in (
            ("node_visible", (n_frames, n_nodes)),
            ("edge_visible", (n_frames, n_edges)),
        ):
            value = getattr(self, name)
            if value is not None:
                if np.shape(value) != shape:
                    raise TrajectoryError(f"{name} must have shape {shape}, got {np.shape(value)}")
                object.__setattr__(self, name, np.asarray(value, dtype=bool))
        if self.node_shapes is not None:
            shapes = tuple(str(s) for s in self.node_shapes)
            if len(shapes) != n_nodes:
                raise TrajectoryError(f"{len(shapes)} node shapes for {n_nodes} nodes")
            unknown = sorted(set(shapes) - NODE_SHAPES)
            if unknown:
                raise TrajectoryError(f"unknown node shape {unknown[0]!r}")
            object.__setattr__(self, "node_shapes", shapes)

    @property
    def n_frames(self) -> int:
        """Number of frames T."""
        return int(self.positions.shape[0])

    @property
    def n_nodes(self) -> int:
        """Number of nodes N."""
        return int(self.positions.shape[1])

    @property
    def time(self) -> FloatArray:
        """(T,) seconds of each frame."""
        return np.arange(self.n_frames, dtype=np.float64) / self.fps

    @property
    def duration(self) -> float:
        """Seconds from the first to one frame past the last."""
        return self.n_frames / self.fps

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the trajectory to a compressed ``.npz`` file and return its path.

        Raises:
            TrajectoryError: the file cannot be written (a missing or read-only folder, a
                full disk), in one line.
        """
        path = Path(path)
        arrays: dict[str, npt.ArrayLike] = {
            "format_version": np.int32(FORMAT_VERSION),
            "positions": self.positions,
            "time": self.time,
            "fps": np.float64(self.fps),
            "edges": self.edges,
            "node_names": np.array(self.node_names, dtype=str),
            "failed": np.bool_(self.failed),
        }
        for name in _OPTIONAL:
            value = getattr(self, name)
            if value is not None:
                arrays[name] = np.array(value, dtype=str) if name == "node_shapes" else value
        try:
            with atomic_path(path) as tmp, open(tmp, "wb") as fh:
                np.savez_compressed(fh, **arrays)  # type: ignore[arg-type]
        except OSError as exc:
            raise TrajectoryError(f"cannot write {path}: {exc.strerror or exc}") from None
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Trajectory:
        """Read a trajectory written by `save`; raise `TrajectoryError` on a bad file."""
        path = Path(path)
        try:
            _check_declared_sizes(path)
            with np.load(path, allow_pickle=False) as data:
                contents = {k: data[k] for k in data.files}
        except FileNotFoundError:
            raise TrajectoryError(f"{path}: no such file") from None
        except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
            raise TrajectoryError(f"{path}: not a trajectory file ({exc})") from None
        missing = [k for k in ("positions", "fps", "edges", "node_names") if k not in contents]
        if missing:
            raise TrajectoryError(f"{path}: not a trajectory file (missing {', '.join(missing)})")
        version = int(contents.get("format_version", FORMAT_VERSION))
        if version > FORMAT_VERSION:
            raise TrajectoryError(f"{path}: format version {version} is newer than this sinews")
        known = {f.name for f in fields(cls)}
        kwargs = {k: v for k, v in contents.items() if k in known}
        try:
            kwargs["fps"] = float(contents["fps"])
            kwargs["failed"] = bool(contents.get("failed", False))
        except (TypeError, ValueError):
            raise TrajectoryError(f"{path}: fps and failed must be numbers") from None
        kwargs["node_names"] = tuple(str(n) for n in np.atleast_1d(contents["node_names"]))
        if not np.issubdtype(contents["positions"].dtype, np.number) or not np.all(
            np.isfinite(contents["positions"])
        ):
            raise TrajectoryError(f"{path}: positions must be finite numbers (NaN or inf found)")
        try:
            return cls(**kwargs)
        except TrajectoryError as exc:
            raise TrajectoryError(f"{path}: {exc}") from None


def _check_declared_sizes(path: Path) -> None:
    """Refuse arrays whose headers promise more data than their file holds, or too much.

    `numpy.load` allocates what an array's header declares before reading it,
    so a forged header of shape (1e9, 17, 2) would take 127 GiB.
    """
    total = 0
    with zipfile.ZipFile(path) as archive:
        for info in archive.infolist():
            with archive.open(info) as member:
                version = np.lib.format.read_magic(member)
                if version == (1, 0):
                    shape, _, dtype = np.lib.format.read_array_header_1_0(member)
                else:
                    shape, _, dtype = np.lib.format.read_array_header_2_0(member)
            declared = dtype.itemsize * int(np.prod(shape, dtype=object))
            if declared > info.file_size:
                raise ValueError(f"{info.filename} declares more data than it holds")
            total += declared
    if total > MAX_TRAJECTORY_BYTES:
        raise ValueError(f"arrays larger than {MAX_TRAJECTORY_BYTES // 2**30} GiB")
