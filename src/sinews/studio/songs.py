"""The studio's songs: the bundled demos and uploads, each known by a generated id.

No request ever names a file. A demo song is ``demo-<name>``; an upload is
checked by decoding it (`sinews.music.analyse_file` reads it with
`sinews.music.load_audio`, which refuses anything that is not audio), then
stored in the library folder as ``u<16 hex digits of its SHA-256>`` plus a
known extension, beside a small JSON file with the name to show. A run
stores its song the way `sinews.experiments.dancers.run` expects
(``demo:<name>`` or the file's absolute path).
"""

from __future__ import annotations

import json
import os
import re
import secrets
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from sinews.errors import SinewsError
from sinews.experiments.dancers.settings import song_path
from sinews.music import DEFAULT_DEMO, DEMO_NAMES, AudioError, MusicFeatures, analyse_file
from sinews.store import RunInfo

__all__ = ["MAX_UPLOAD_BYTES", "Song", "SongError", "SongLibrary"]

MAX_UPLOAD_BYTES = 30 * 1024 * 1024
"""Largest song file the studio accepts (30 MB: about 3 minutes of CD-quality WAV)."""

_DEMO = "demo-"
_UPLOAD_ID = re.compile(r"u[0-9a-f]{16}")
_EXTENSIONS = (".wav", ".flac", ".ogg", ".oga", ".opus", ".mp3", ".m4a", ".aac", ".aiff", ".aif")


class SongError(SinewsError):
    """A song that cannot be used (unknown id, too big, not audio)."""


@dataclass(frozen=True)
class Song:
    """One song the studio can play and dance to.

    Attributes:
        id: ``demo-<name>`` or ``u<hex>``; what the page sends.
        name: what the page shows.
        setting: how a run stores it: ``demo:<name>`` or the file's absolute path.
    """

    id: str
    name: str
    setting: str

    @property
    def path(self) -> Path:
        """The audio file (a demo song is synthesised on first use)."""
        return song_path(self.setting)


class SongLibrary:
    """Demo songs and uploaded songs kept in one folder.

    Args:
        folder: where uploads live (created when needed).
        max_bytes: size limit of an upload.
    """

    def __init__(self, folder: Path, *, max_bytes: int = MAX_UPLOAD_BYTES) -> None:
        self.folder = folder
        self.max_bytes = max_bytes

    def songs(self) -> list[Song]:
        """The demo songs, then the uploads by name."""
        demos = [self.demo(name) for name in DEMO_NAMES]
        uploads = [self._upload(p.stem) for p in self._upload_files()]
        return demos + sorted(uploads, key=lambda s: (s.name.lower(), s.id))

    def demo(self, name: str = DEFAULT_DEMO) -> Song:
        """A bundled demo song by name."""
        if name not in DEMO_NAMES:
            raise SongError(f"no demo song {name!r}; choose from {', '.join(DEMO_NAMES)}")
        return Song(id=f"{_DEMO}{name}", name=f"{name} (demo)", setting=f"demo:{name}")

    def get(self, song_id: str) -> Song:
        """The song with this id; `SongError` if there is none."""
        if song_id.startswith(_DEMO) and song_id[len(_DEMO) :] in DEMO_NAMES:
            return self.demo(song_id[len(_DEMO) :])
        if _UPLOAD_ID.fullmatch(song_id) and self._audio_file(song_id) is not None:
            return self._upload(song_id)
        raise SongError(f"no song {song_id!r}")

    def of_run(self, info: RunInfo) -> Song:
        """The song a run dances to (a run made elsewhere shows its file's name)."""
        setting = str(info.config.get("song", ""))
        if setting.startswith("demo:"):
            return self.demo(setting.removeprefix("demo:"))
        path = Path(setting)
        if path.parent == self.folder.resolve() and _UPLOAD_ID.fullmatch(path.stem):
            return self._upload(path.stem)
        return Song(id=f"run-{info.id}", name=path.name, setting=setting)

    def incoming(self) -> Path:
        """A fresh file name for an upload being received (under the library folder)."""
        folder = self.folder / "incoming"
        folder.mkdir(parents=True, exist_ok=True)
        return folder / f"{secrets.token_hex(8)}.part"

    def accept(self, received: Path, filename: str) -> tuple[Song, MusicFeatures]:
        """Check a received upload by decoding and analysing it, then keep it.

        Args:
            received: the bytes as written (by `incoming`); moved or deleted here.
            filename: the name the person's file had (only shown, never used as a path).

        Returns:
            The stored song and its analysis.

        Raises:
            SongError: too big, or not audio this studio can read (the
                message names the upload, not the server's files).
        """
        name = _display_name(filename)
        try:
            if received.stat().st_size > self.max_bytes:
                raise SongError(f"{name}: larger than {self.max_bytes // (1024 * 1024)} MB")
            try:
                features = analyse_file(received)
            except AudioError as exc:
                raise SongError(str(exc).replace(str(received), name)) from None
            song_id = "u" + features.song_hash[:16]
            suffix = Path(filename).suffix.lower()
            target = self.folder / f"{song_id}{suffix if suffix in _EXTENSIONS else '.audio'}"
            if self._audio_file(song_id) is None:
                try:
                    (self.folder / f"{song_id}.json").write_text(json.dumps({"name": name}))
                    os.replace(received, target)
                except OSError as exc:
                    (self.folder / f"{song_id}.json").unlink(missing_ok=True)
                    raise SongError(f"{name}: cannot store the song ({exc.strerror})") from None
            return self._upload(song_id), features
        finally:
            received.unlink(missing_ok=True)

    def import_file(self, path: Path) -> Song:
        """Copy a song file given on the command line into the library."""
        received = self.incoming()
        try:
            with open(path, "rb") as source, open(received, "wb") as sink:
                while chunk := source.read(1 << 20):
                    sink.write(chunk)
        except OSError as exc:
            received.unlink(missing_ok=True)
            raise SongError(f"{path}: cannot read ({exc.strerror or exc})") from None
        return self.accept(received, path.name)[0]

    def _upload_files(self) -> Iterable[Path]:
        if not self.folder.is_dir():
            return []
        return [
            p for p in self.folder.iterdir() if _UPLOAD_ID.fullmatch(p.stem) and p.suffix != ".json"
        ]

    def _audio_file(self, song_id: str) -> Path | None:
        return next((p for p in self._upload_files() if p.stem == song_id), None)

    def _upload(self, song_id: str) -> Song:
        path = self._audio_file(song_id)
        if path is None:
            raise SongError(f"no song {song_id!r}")
        try:
            name = str(json.loads((self.folder / f"{song_id}.json").read_text())["name"])
        except (OSError, ValueError, KeyError, TypeError):
            name = song_id
        return Song(id=song_id, name=name, setting=str(path.resolve()))


def _display_name(filename: str) -> str:
    """The last part of an uploaded file's name, printable and at most 80 characters."""
    base = re.split(r"[\\/]", filename)[-1]
    clean = "".join(c for c in base if c.isprintable()).strip() or "upload"
    return clean[:80]
