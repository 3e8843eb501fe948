"""Synthetic trajectories for the render tests: a 17-node stick-figure dancer."""

from __future__ import annotations

import subprocess
import wave
from pathlib import Path

import numpy as np

from sinews.render.mp4 import ffmpeg_exe
from sinews.trajectory import Trajectory

# name: (x, y) rest position in metres, radius in metres
NODES: dict[str, tuple[float, float, float]] = {
    "head": (0.0, 1.62, 0.11),
    "neck": (0.0, 1.45, 0.04),
    "chest": (0.0, 1.30, 0.07),
    "spine": (0.0, 1.12, 0.06),
    "pelvis": (0.0, 0.95, 0.07),
    "l_shoulder": (-0.20, 1.40, 0.05),
    "r_shoulder": (0.20, 1.40, 0.05),
    "l_elbow": (-0.42, 1.22, 0.04),
    "r_elbow": (0.42, 1.22, 0.04),
    "l_hand": (-0.55, 1.02, 0.045),
    "r_hand": (0.55, 1.02, 0.045),
    "l_hip": (-0.12, 0.92, 0.05),
    "r_hip": (0.12, 0.92, 0.05),
    "l_knee": (-0.16, 0.50, 0.045),
    "r_knee": (0.16, 0.50, 0.045),
    "l_foot": (-0.20, 0.05, 0.05),
    "r_foot": (0.20, 0.05, 0.05),
}
NAMES = tuple(NODES)
BONES = [
    ("head", "neck"),
    ("neck", "chest"),
    ("chest", "spine"),
    ("spine", "pelvis"),
    ("neck", "l_shoulder"),
    ("neck", "r_shoulder"),
    ("l_shoulder", "spine"),
    ("r_shoulder", "spine"),
    ("l_shoulder", "r_shoulder"),
    ("l_shoulder", "l_elbow"),
    ("l_elbow", "l_hand"),
    ("r_shoulder", "r_elbow"),
    ("r_elbow", "r_hand"),
    ("pelvis", "l_hip"),
    ("pelvis", "r_hip"),
    ("l_hip", "r_hip"),
    ("l_hip", "spine"),
    ("r_hip", "spine"),
    ("l_hip", "l_knee"),
    ("l_knee", "l_foot"),
    ("r_hip", "r_knee"),
    ("r_knee", "r_foot"),
]
RESPONDER_NODES = (NAMES.index("l_hand"), NAMES.index("r_foot"), NAMES.index("head"))
# Strong, distinct colours so tests can find each node in a picture.
PALETTE = np.array(
    [
        [230, 25, 75],
        [60, 180, 75],
        [255, 225, 25],
        [0, 130, 200],
        [245, 130, 48],
        [145, 30, 180],
        [70, 240, 240],
        [240, 50, 230],
        [210, 245, 60],
        [250, 190, 212],
        [0, 128, 128],
        [220, 190, 255],
        [170, 110, 40],
        [128, 0, 0],
        [170, 255, 195],
        [128, 128, 0],
        [0, 0, 128],
    ],
    dtype=np.uint8,
)


def make_dancer(
    n_frames: int = 30,
    fps: float = 30.0,
    *,
    colors: bool = True,
    extras: bool = True,
    scale: float = 1.0,
) -> Trajectory:
    """A stick figure standing on the floor, waving its arms and bobbing.

    Args:
        n_frames: number of frames T.
        fps: frames per second.
        colors: give every node a distinct colour (else leave colours None).
        extras: add radii, forces (T, N, 2) and triggers (T, 3).
        scale: size factor of the whole body (feet stay on the floor).
    """
    rest = np.array([v[:2] for v in NODES.values()], dtype=np.float64)
    t = np.arange(n_frames) / fps
    phase = 2 * np.pi * 1.2 * t[:, None]
    pos = np.repeat(rest[None], n_frames, axis=0)
    arm = np.array([n.endswith(("elbow", "hand")) for n in NAMES])
    side = np.array([-1.0 if n.startswith("l_") else 1.0 for n in NAMES])
    upper = rest[:, 1] > 0.9
    pos[:, arm, 1] += 0.25 * np.sin(phase + side[arm] * 0.8) * (rest[arm, 0] ** 2 * 4)
    pos[:, upper, 1] -= 0.04 * (1 - np.cos(phase))
    pos[:, :, 0] += 0.03 * np.sin(phase / 2)
    pos *= scale
    edges = np.array([(NAMES.index(a), NAMES.index(b)) for a, b in BONES], dtype=np.int32)
    radii = np.array([v[2] for v in NODES.values()], dtype=np.float32) * scale
    forces = None
    triggers = None
    if extras:
        forces = np.zeros((n_frames, len(NAMES), 2), dtype=np.float32)
        forces[:, :, 1] = -9.81 * radii * 10  # "gravity"
        forces[:, arm, 0] = 6.0 * np.cos(phase) * side[arm]
        triggers = np.zeros((n_frames, len(RESPONDER_NODES)), dtype=bool)
        triggers[::4, 0] = True
        triggers[2::6, 1] = True
    return Trajectory(
        positions=pos.astype(np.float32),
        fps=fps,
        edges=edges,
        node_names=NAMES,
        radii=radii if extras else None,
        colors=PALETTE.copy() if colors else None,
        forces=forces,
        triggers=triggers,
    )


def write_sine_wav(
    path: Path, seconds: float, *, start: float = 0.0, rate: int = 22050, freq: float = 440.0
) -> Path:
    """A mono 16-bit sine tone, silent before ``start`` seconds."""
    t = np.arange(int(seconds * rate)) / rate
    samples = (0.3 * 32767 * np.sin(2 * np.pi * freq * t) * (t >= start)).astype("<i2")
    with wave.open(str(path), "wb") as wav:
        wav.setnchannels(1)
        wav.setsampwidth(2)
        wav.setframerate(rate)
        wav.writeframes(samples.tobytes())
    return path


def decode_audio(path: Path, rate: int = 8000) -> np.ndarray:
    """The sound track of a media file as mono float samples in [-1, 1]."""
    result = subprocess.run(
        [
            ffmpeg_exe(),
            "-v",
            "error",
            "-i",
            str(path),
            "-f",
            "s16le",
            "-ac",
            "1",
            "-ar",
            str(rate),
            "-",
        ],
        capture_output=True,
        check=True,
    )
    return np.frombuffer(result.stdout, dtype="<i2") / 32768.0


def probe(path: Path) -> str:
    """ffmpeg's description of a media file's streams (``ffmpeg -i``'s stderr)."""
    result = subprocess.run(
        [ffmpeg_exe(), "-hide_banner", "-i", str(path)],
        capture_output=True,
        text=True,
        check=False,
    )
    return result.stderr
