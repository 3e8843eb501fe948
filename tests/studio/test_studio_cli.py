"""``sinews studio`` refuses bad settings with one line, before serving anything."""

from __future__ import annotations

import socket
from pathlib import Path

import pytest

from sinews.cli import main


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--song", "{tmp}/missing.wav"], "missing.wav: cannot read"),
        (["--song", "{tmp}/junk.mp3"], "junk.mp3: not an audio file"),
        (["--resume", "999"], "no run 999"),
        (["--population", "30"], "population must be 12–20"),
    ],
)
def test_bad_settings_stop_the_studio_with_one_line(
    tmp_path: Path,
    studio_home: None,
    capsys: pytest.CaptureFixture[str],
    options: list[str],
    message: str,
) -> None:
    (tmp_path / "junk.mp3").write_bytes(b"not audio at all")
    args = [o.format(tmp=tmp_path) for o in options]
    status = main(["studio", "--no-browser", "--port", "0", "--db", str(tmp_path / "s.db"), *args])
    err = capsys.readouterr().err
    assert status == 2 and message in err and len(err.strip().splitlines()) == 1


def test_a_busy_port_is_named(
    tmp_path: Path, studio_home: None, capsys: pytest.CaptureFixture[str]
) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = str(taken.getsockname()[1])
        status = main(["studio", "--no-browser", "--port", port, "--db", str(tmp_path / "s.db")])
    assert status == 2 and f"cannot listen on 127.0.0.1:{port}" in capsys.readouterr().err
