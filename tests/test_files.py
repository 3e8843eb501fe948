"""Atomic writes: a failed write keeps the old file whole and leaves no temporary behind."""

from __future__ import annotations

from pathlib import Path

import pytest

from sinews.files import atomic_path


def test_failed_write_keeps_the_old_file(tmp_path: Path) -> None:
    target = tmp_path / "song.wav"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("writer died")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["song.wav"]


def test_temporaries_are_unique_and_keep_the_suffix(tmp_path: Path) -> None:
    target = tmp_path / "motion.npz"
    with atomic_path(target) as first, atomic_path(target) as second:
        assert first != second
        assert first.suffix == second.suffix == ".npz"
        assert first.parent == tmp_path
        first.write_text("a")
        second.write_text("b")
    assert target.read_text() == "a"  # the outer block finished last
