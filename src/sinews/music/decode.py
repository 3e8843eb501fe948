"""Reading and writing audio files: a mono float32 mixdown at the file's own rate.

soundfile (libsndfile) reads WAV, FLAC, OGG Vorbis/Opus and MP3 by their
content, whatever the file is called. Anything it does not recognise (M4A/AAC,
video files…) goes through ffmpeg when one is available (`sinews.music.ffmpeg`).
Every problem with a file becomes an `AudioError` whose one-line message starts
with the file's path.
"""

from __future__ import annotations

import contextlib
import os
import stat
import struct
import sys
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt
import soundfile as sf

from sinews.ffmpeg import find_ffmpeg
from sinews.files import atomic_path
from sinews.limits import MAX_SECONDS  # the longest song, checked before decoding
from sinews.music.errors import AudioError
from sinews.music.ffmpeg import FfmpegFailed, decode_with_ffmpeg

__all__ = [
    "MAX_SECONDS",
    "MIN_SECONDS",
    "SAMPLE_RATES",
    "Audio",
    "check_readable_file",
    "load_audio",
    "save_wav",
]

MIN_SECONDS = 0.5
"""Shortest song we accept: shorter files cannot carry a beat."""
SAMPLE_RATES = (8000, 192_000)
"""Lowest and highest sample rate we decode, Hz: telephone audio to studio masters (the
highest bounds a 20-minute song's memory, about 0.9 GB of float32)."""


_BLOCK_FRAMES = 8192
_READ_BLOCK_SAMPLES = 1 << 19
"""Samples (frames × channels) read at a time: 2 MiB of float32, however many channels."""
_UNRECOGNISED_FORMAT = 1  # libsndfile's SF_ERR_UNRECOGNISED_FORMAT
_NOT_DECODABLE = 7
"""libsndfile's code for bytes it took for MP3 but cannot open ("File does not exist or is
not a regular file"; the path was checked to be a regular file): ffmpeg gets a try."""
_STDERR_LOCK = threading.Lock()
_CONVERT_HINT = "convert it to WAV, FLAC, OGG or MP3"

# suffix -> (soundfile format, subtype or None for the format's default)
_WRITE_FORMATS: dict[str, tuple[str, str | None]] = {
    ".wav": ("WAV", "PCM_16"),
    ".flac": ("FLAC", "PCM_16"),
    ".ogg": ("OGG", "VORBIS"),
    ".oga": ("OGG", "VORBIS"),
    ".opus": ("OGG", "OPUS"),
    ".mp3": ("MP3", "MPEG_LAYER_III"),
}


@dataclass(frozen=True, eq=False)
class Audio:
    """A decoded song.

    Attributes:
        samples: (S,) float32 mono mixdown (the mean of the channels), nominally in [-1, 1].
        sample_rate: samples per second, exactly as the decoder returned it
            (Opus, for example, always decodes at 48 kHz).
    """

    samples: npt.NDArray[np.float32]
    sample_rate: int

    def __post_init__(self) -> None:
        samples = np.asarray(self.samples, dtype=np.float32)
        if samples.ndim != 1:
            raise ValueError(f"samples must be one mono channel (S,), got {samples.shape}")
        if self.sample_rate <= 0:
            raise ValueError(f"sample_rate must be positive, got {self.sample_rate}")
        object.__setattr__(self, "samples", samples)
        object.__setattr__(self, "sample_rate", int(self.sample_rate))

    @property
    def duration(self) -> float:
        """Length in seconds."""
        return len(self.samples) / self.sample_rate


def load_audio(path: str | os.PathLike[str]) -> Audio:
    """Decode an audio file into a mono float32 mixdown.

    Args:
        path: a WAV, FLAC, OGG (Vorbis or Opus) or MP3 file, or, when ffmpeg is
            available, anything ffmpeg decodes (M4A/AAC, video soundtracks…).

    Returns:
        The decoded `Audio`; a silent file gives silence, not an error.

    Raises:
        AudioError: a missing, unreadable, empty, truncated, corrupt or
            unsupported file, or one shorter than `MIN_SECONDS` or longer than
            `MAX_SECONDS`.
    """
    path = Path(path)
    check_readable_file(path)
    try:
        samples, rate = _decode_soundfile(path)
    except _NotForSoundfile:
        samples, rate = _decode_foreign(path)
        _checked_rate(path, rate)
    audio = Audio(samples=samples, sample_rate=rate)
    if not np.all(np.isfinite(audio.samples)):
        raise AudioError(f"{path}: corrupt audio (it contains NaN or infinite samples)")
    peak = float(np.max(np.abs(audio.samples), initial=0.0))
    if peak > 1.0:  # float files may exceed full scale, by any amount: bring them back
        audio = Audio(samples=audio.samples / np.float32(peak), sample_rate=audio.sample_rate)
    if audio.duration < MIN_SECONDS:
        raise AudioError(
            f"{path}: too short ({audio.duration:.2f} s); a song needs at least {MIN_SECONDS} s"
        )
    _check_length(path, audio.duration)
    return audio


def save_wav(path: str | os.PathLike[str], samples: npt.ArrayLike, sample_rate: int) -> Path:
    """Write samples to an audio file in 8192-frame blocks, atomically.

    The format follows the suffix: ``.wav`` and ``.flac`` (16-bit), ``.ogg``/
    ``.oga`` (Vorbis), ``.opus`` (needs 8, 12, 16, 24 or 48 kHz) or ``.mp3``.
    Writing block by block avoids a libsndfile crash seen when a long OGG was
    written in one call. Samples beyond [-1, 1] are clipped by the encoder.

    Args:
        path: where to write; its suffix picks the format.
        samples: (S,) mono or (S, C) multichannel float samples.
        sample_rate: samples per second.

    Returns:
        The written path.

    Raises:
        AudioError: an unsupported suffix, bad samples or a failed write.
    """
    path = Path(path)
    fmt = _WRITE_FORMATS.get(path.suffix.lower())
    if fmt is None:
        known = ", ".join(sorted(_WRITE_FORMATS))
        raise AudioError(f"{path}: cannot write '{path.suffix}' audio; use one of {known}")
    data = np.asarray(samples, dtype=np.float32)
    if data.ndim == 1:
        data = data[:, None]
    if data.ndim != 2 or data.shape[0] == 0 or not np.all(np.isfinite(data)):
        raise AudioError(f"{path}: samples must be a finite (S,) or (S, C) array with S > 0")
    if not path.parent.is_dir():  # libsndfile would only say "System error"
        raise AudioError(f"{path}: cannot write audio ({path.parent} is not a directory)")
    try:
        with (
            atomic_path(path) as tmp,
            sf.SoundFile(
                str(tmp), "w", int(sample_rate), data.shape[1], subtype=fmt[1], format=fmt[0]
            ) as out,
        ):
            for start in range(0, data.shape[0], _BLOCK_FRAMES):
                out.write(data[start : start + _BLOCK_FRAMES])
    except (OSError, sf.SoundFileError, ValueError) as exc:
        raise AudioError(f"{path}: cannot write audio ({_reason(exc)})") from None
    return path


def check_readable_file(path: Path) -> None:
    """Raise AudioError unless ``path`` is a non-empty regular file we may read."""
    try:
        mode = path.stat().st_mode
        size = path.stat().st_size
    except FileNotFoundError:
        raise AudioError(f"{path}: no such file") from None
    except OSError as exc:
        raise AudioError(f"{path}: cannot read ({_reason(exc)})") from None
    if stat.S_ISDIR(mode):
        raise AudioError(f"{path}: is a directory, not an audio file")
    if not stat.S_ISREG(mode):
        raise AudioError(f"{path}: not a regular file")
    if size == 0:
        raise AudioError(f"{path}: the file is empty")
    try:
        with open(path, "rb") as fh:
            fh.read(1)
    except OSError as exc:
        raise AudioError(f"{path}: cannot read ({_reason(exc)})") from None


def _check_length(path: Path, seconds: float) -> None:
    if seconds > MAX_SECONDS:
        raise AudioError(
            f"{path}: too long ({seconds / 60:.1f} min); songs may last at most "
            f"{MAX_SECONDS / 60:.0f} min"
        )


def _checked_rate(path: Path, rate: int) -> int:
    low, high = SAMPLE_RATES
    if not low <= rate <= high:
        raise AudioError(f"{path}: a sample rate of {rate} Hz; songs are read at {low} to "
                         f"{high} Hz")  # fmt: skip
    return rate


class _NotForSoundfile(Exception):
    """libsndfile does not recognise the file's format."""


def _decode_soundfile(path: Path) -> tuple[npt.NDArray[np.float32], int]:
    """Decode with soundfile block by block, mixing down to mono as we go.

    The length limit is checked from the header before anything is decoded.
    """
    blocks: list[npt.NDArray[np.float32]] = []
    try:
        with _c_stderr_dropped(), sf.SoundFile(str(path)) as source:
            rate = _checked_rate(path, int(source.samplerate))
            promised = int(source.frames)
            if source.format == "WAV":
                promised = max(promised, _wav_promised_frames(path) or 0)
            _check_length(path, promised / rate)
            frames = max(1, _READ_BLOCK_SAMPLES // source.channels)
            while len(block := source.read(frames, "float32", always_2d=True)):
                blocks.append(block.mean(axis=1, dtype=np.float32))
    except sf.LibsndfileError as exc:
        if exc.code in (_UNRECOGNISED_FORMAT, _NOT_DECODABLE):
            raise _NotForSoundfile from None
        raise AudioError(f"{path}: corrupt or truncated audio ({_reason(exc)})") from None
    except (sf.SoundFileError, RuntimeError) as exc:
        raise AudioError(f"{path}: corrupt or truncated audio ({_reason(exc)})") from None
    samples = np.concatenate(blocks) if blocks else np.zeros(0, np.float32)
    _check_complete(path, promised, len(samples), rate)
    return samples, rate


@contextlib.contextmanager
def _c_stderr_dropped() -> Iterator[None]:
    """Send what C code writes to file descriptor 2 to /dev/null meanwhile.

    libmpg123 (inside libsndfile) prints notes on a corrupt MP3 ("Illegal Audio-MPEG-Header",
    "dequantization failed"); the file gets our one-line error instead. Process-wide, so other
    threads' stderr is dropped too for the moment; the lock keeps two decodes from crossing
    their saves and restores.
    """
    with _STDERR_LOCK:
        sys.stderr.flush()
        saved = os.dup(2)
        try:
            with open(os.devnull, "wb") as null:
                os.dup2(null.fileno(), 2)
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)


def _check_complete(path: Path, promised: int, decoded: int, rate: int) -> None:
    """Raise AudioError if the header promises clearly more audio than was decoded.

    MP3 headers may only estimate the length, hence the tolerance.
    """
    if decoded == 0:
        raise AudioError(f"{path}: no decodable audio in the file (truncated or corrupt)")
    tolerance = max(0.5 * rate, 0.02 * promised)
    if promised - decoded > tolerance:
        raise AudioError(
            f"{path}: truncated or corrupt: the header promises {promised / rate:.1f} s "
            f"of audio but only {decoded / rate:.1f} s could be decoded"
        )


def _wav_promised_frames(path: Path) -> int | None:
    """Frames the RIFF ``data`` chunk header declares (libsndfile silently trims it).

    Returns None for an unknown size (streamed WAVs write 0 or 0xFFFFFFFF) or
    when the chunks cannot be walked.
    """
    with open(path, "rb") as fh:
        head = fh.read(12)
        if len(head) < 12 or head[:4] != b"RIFF" or head[8:12] != b"WAVE":
            return None
        block_align = 0
        while True:
            chunk = fh.read(8)
            if len(chunk) < 8:
                return None
            name, size = chunk[:4], struct.unpack("<I", chunk[4:])[0]
            if name == b"fmt ":
                fmt = fh.read(size + size % 2)
                block_align = struct.unpack("<H", fmt[12:14])[0] if len(fmt) >= 14 else 0
                continue
            if name == b"data":
                if size in (0, 0xFFFFFFFF) or block_align == 0:
                    return None
                return size // block_align
            fh.seek(size + size % 2, os.SEEK_CUR)


def _decode_foreign(path: Path) -> tuple[npt.NDArray[np.float32], int]:
    """Decode a format soundfile does not know through ffmpeg, or explain what to do."""
    exe = find_ffmpeg()
    if exe is None:
        raise AudioError(
            f"{path}: not a format soundfile can read and no ffmpeg was found; {_CONVERT_HINT}"
        )
    try:
        samples, rate = decode_with_ffmpeg(exe, path, MAX_SECONDS + 1.0)
    except FfmpegFailed as exc:
        raise AudioError(
            f"{path}: not an audio file soundfile or ffmpeg can read ({_reason(exc)})"
        ) from None
    except OSError as exc:
        raise AudioError(
            f"{path}: could not run ffmpeg ({_reason(exc)}); {_CONVERT_HINT}"
        ) from None
    return samples.mean(axis=1, dtype=np.float32), rate


def _reason(exc: BaseException) -> str:
    """An exception's message as one short line, without libsndfile's path prefix."""
    text = " ".join(str(exc).split()) or type(exc).__name__
    if text.startswith("Error opening") and "': " in text:
        text = text.split("': ", 1)[1]
    if text.startswith("Error : "):
        text = text[len("Error : ") :]
    return text.rstrip(".")
