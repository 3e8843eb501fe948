"""``sinews bench`` through the installed script: skips a missing anchor, refuses bad names.

The anchors' tools (the ``[bench]`` extra) are hidden from the child by a folder on
its PYTHONPATH whose package of the same name fails to import, as a missing one does.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from killed_runs import sinews_command


def bench(tmp_path: Path, *args: str, hide: str | None = None) -> subprocess.CompletedProcess[str]:
    env = {
        **os.environ,
        "XDG_DATA_HOME": str(tmp_path / "d"),
        "XDG_CACHE_HOME": str(tmp_path / "c"),
    }
    if hide is not None:
        package = tmp_path / "hidden" / hide
        package.mkdir(parents=True)
        (package / "__init__.py").write_text(f"raise ImportError('{hide} is hidden')\n")
        env["PYTHONPATH"] = str(tmp_path / "hidden")
    return subprocess.run([*sinews_command(), "bench", *args], capture_output=True, text=True,
                          cwd=tmp_path, env=env, timeout=600)  # fmt: skip


def test_a_missing_anchor_is_skipped_with_one_line(tmp_path: Path) -> None:
    done = bench(tmp_path, "music", "--scale", "tiny", hide="librosa")
    assert done.returncode == 0, done.stderr
    reason = (
        "skipped analysis vs librosa onset_strength + beat_track: "
        "librosa is not installed (pip install 'sinews[bench]')"
    )
    assert reason in done.stdout.splitlines()
    assert "soundfile decoding it from FLAC" in done.stdout  # the other cases still ran
    assert "Traceback" not in done.stderr


def test_an_installed_anchor_is_measured_beside_ours(tmp_path: Path) -> None:
    done = bench(tmp_path, "music", "--scale", "tiny")
    assert done.returncode == 0, done.stderr
    assert "librosa onset_strength + beat_track, warm" in done.stdout
    assert "skipped" not in done.stdout


def test_bad_names_and_sizes_exit_2_without_a_traceback(tmp_path: Path) -> None:
    for args in (["nosuch"], ["music", "--scale", "huge"]):
        done = bench(tmp_path, *args)
        assert done.returncode == 2, args
        assert "Traceback" not in done.stderr
    named = bench(tmp_path, "gp", "nosuch")
    assert named.returncode == 2
    [line] = named.stderr.strip().splitlines()
    assert "no benchmark called 'nosuch'" in line
    assert named.stdout == ""  # refused before any benchmark ran
