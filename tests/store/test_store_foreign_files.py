"""Corrupt, foreign and too-new database files are refused with one line, never touched."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import numpy as np
import pytest

from sinews.store import SCHEMA_VERSION, RunStore, StoreError


def refuse(path: Path, message: str) -> None:
    before = path.read_bytes()
    with pytest.raises(StoreError, match=message) as caught:
        RunStore(path)
    assert "\n" not in str(caught.value)
    assert path.read_bytes() == before


def test_garbage_bytes_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "runs.db"
    path.write_bytes(np.random.default_rng(0).bytes(5000))
    refuse(path, "not a sinews database \\(not an SQLite file\\)")


def test_a_text_file_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "notes.db"
    path.write_text("hello\n")
    refuse(path, "not an SQLite file")


def test_an_sqlite_header_with_garbage_pages_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "runs.db"
    path.write_bytes(b"SQLite format 3\x00" + bytes(range(256)) * 20)
    refuse(path, "not a usable sinews database")


def test_another_applications_database_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "other.db"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE contacts (name TEXT)")
    conn.commit()
    conn.close()
    refuse(path, "another application")


def test_another_application_id_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "other.db"
    conn = sqlite3.connect(path)
    conn.execute("PRAGMA application_id = 1234")
    conn.commit()
    conn.close()
    refuse(path, "another application")


def test_a_newer_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "runs.db"
    RunStore(path).close()
    conn = sqlite3.connect(path)
    conn.execute(f"PRAGMA user_version = {SCHEMA_VERSION + 1}")
    conn.commit()
    conn.close()
    with pytest.raises(StoreError, match="newer sinews"):
        RunStore(path)


def test_an_empty_file_becomes_a_database_and_reopens(tmp_path: Path) -> None:
    path = tmp_path / "runs.db"
    path.touch()
    with RunStore(path) as store:
        run = store.create_run("test", config={}, seed=0, genome_codec="float64")
    with RunStore(path) as store:
        assert store.run(run).kind == "test"


def test_corruption_found_later_is_a_one_line_error(tmp_path: Path) -> None:
    path = tmp_path / "runs.db"
    with RunStore(path) as store:
        for _ in range(200):
            store.create_run("test", config={"pad": "x" * 500}, seed=0, genome_codec="float64")
    conn = sqlite3.connect(path)
    conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    conn.close()
    data = bytearray(path.read_bytes())
    data[8192:] = bytes(len(data) - 8192)  # wipe every page after the second
    path.write_bytes(bytes(data))
    with (
        pytest.raises(StoreError, match=r"database error|not a usable") as caught,
        RunStore(path) as store,
    ):
        store.runs()
    assert "\n" not in str(caught.value)
