"""Open a sinews database safely: recognise it, refuse others, migrate it.

A sinews database carries ``PRAGMA application_id = APPLICATION_ID`` and its
schema version in ``PRAGMA user_version``. Opening a path:

* missing or empty file → a new database is created;
* not an SQLite file (garbage bytes) → `StoreError`, the file is untouched;
* an SQLite file of another application (other application_id, or any
  tables without ours) → `StoreError`, untouched;
* a sinews database of an older schema → migrated in one transaction;
  of a newer one → `StoreError`.

Connections run in WAL mode with ``synchronous=NORMAL`` (a commit survives a
crash of the program; a power cut may lose the last commits but never
corrupts), foreign keys on, and explicit transactions (autocommit otherwise).
"""

from __future__ import annotations

import sqlite3
import threading
from collections import Counter
from pathlib import Path

from sinews.store.errors import StoreError

__all__ = ["APPLICATION_ID", "MIGRATIONS", "SCHEMA_VERSION", "connect", "hold", "release"]

APPLICATION_ID = 0x53494E57
"""``PRAGMA application_id`` of sinews databases ("SINW")."""

_SQLITE_MAGIC = b"SQLite format 3\x00"

MIGRATIONS: tuple[str, ...] = (
    # 1: runs, individuals, parents, generations, media.
    """
    CREATE TABLE runs (
        id INTEGER PRIMARY KEY,
        kind TEXT NOT NULL,
        config TEXT NOT NULL,
        seed INTEGER NOT NULL,
        song_hash TEXT,
        song_path TEXT,
        code_version TEXT NOT NULL,
        genome_codec TEXT NOT NULL,
        status TEXT NOT NULL CHECK (status IN ('running', 'finished', 'failed')),
        created TEXT NOT NULL,
        updated TEXT NOT NULL
    );
    CREATE TABLE individuals (
        id INTEGER PRIMARY KEY,
        run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
        generation INTEGER NOT NULL,
        idx INTEGER NOT NULL,
        genome BLOB NOT NULL,
        seed INTEGER,
        fitness REAL,
        terms TEXT,
        picked INTEGER NOT NULL DEFAULT 0,
        failed INTEGER NOT NULL DEFAULT 0,
        UNIQUE (run_id, generation, idx)
    );
    CREATE TABLE parents (
        child INTEGER NOT NULL REFERENCES individuals(id) ON DELETE CASCADE,
        slot INTEGER NOT NULL CHECK (slot IN (0, 1)),
        parent INTEGER NOT NULL REFERENCES individuals(id) ON DELETE CASCADE,
        PRIMARY KEY (child, slot)
    ) WITHOUT ROWID;
    CREATE INDEX parents_by_parent ON parents(parent);
    CREATE TABLE generations (
        run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
        generation INTEGER NOT NULL,
        checkpoint BLOB NOT NULL,
        created TEXT NOT NULL,
        PRIMARY KEY (run_id, generation)
    );
    CREATE TABLE media (
        id INTEGER PRIMARY KEY,
        run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
        individual_id INTEGER REFERENCES individuals(id) ON DELETE CASCADE,
        kind TEXT NOT NULL,
        path TEXT NOT NULL,
        created TEXT NOT NULL
    );
    CREATE INDEX media_by_run ON media(run_id);
    """,
)
"""Schema scripts; script k takes a database from ``user_version`` k to k + 1."""

SCHEMA_VERSION = len(MIGRATIONS)


def connect(path: Path, *, readonly: bool = False) -> sqlite3.Connection:
    """Open the sinews database at ``path``, migrated to `SCHEMA_VERSION`.

    Args:
        path: the database file; created (with its folder) unless ``readonly``.
        readonly: only read: nothing is created or written, and a database on
            a read-only file system opens too.

    Raises:
        StoreError: the file is missing (``readonly``), is not SQLite, belongs
            to another application, was written by a newer (or, read-only, an
            older) sinews, or cannot be opened.
    """
    if not _in_use(path):
        _check_header(path)
    if readonly:
        return _connect_readonly(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        conn = sqlite3.connect(path, isolation_level=None, timeout=30.0)
    except (OSError, sqlite3.Error) as exc:
        raise StoreError(f"{path}: cannot open the database ({exc})") from None
    try:
        _identify_and_migrate(conn, path)
        conn.execute("PRAGMA journal_mode = WAL")
        conn.execute("PRAGMA synchronous = NORMAL")
        conn.execute("PRAGMA foreign_keys = ON")
    except sqlite3.DatabaseError as exc:
        conn.close()
        raise StoreError(f"{path}: not a usable sinews database ({exc})") from None
    except StoreError:
        conn.close()
        raise
    return conn


def _connect_readonly(path: Path) -> sqlite3.Connection:
    """A read-only connection; ``immutable`` where WAL's shared memory cannot be made."""
    if not path.is_file():
        raise StoreError(f"{path}: no such run database")
    uri = path.resolve().as_uri()
    conn: sqlite3.Connection | None = None
    for mode in ("?mode=ro", "?mode=ro&immutable=1"):
        try:
            conn = sqlite3.connect(uri + mode, uri=True, isolation_level=None, timeout=30.0)
            conn.execute("SELECT count(*) FROM sqlite_master").fetchone()
            break
        except sqlite3.OperationalError:
            if conn is not None:
                conn.close()
            conn = None
        except sqlite3.DatabaseError as exc:
            raise StoreError(f"{path}: not a usable sinews database ({exc})") from None
    if conn is None:
        raise StoreError(f"{path}: cannot open the database to read it")
    app_id = conn.execute("PRAGMA application_id").fetchone()[0]
    version = conn.execute("PRAGMA user_version").fetchone()[0]
    if app_id != APPLICATION_ID or version != SCHEMA_VERSION:
        conn.close()
        if app_id != APPLICATION_ID:
            raise StoreError(f"{path}: not a sinews database; refusing to touch it")
        raise StoreError(
            f"{path}: schema {version}, this sinews reads {SCHEMA_VERSION}; "
            "a command that writes (e.g. sinews runs resume) upgrades it"
        )
    return conn


_OPEN: Counter[Path] = Counter()
"""Databases this process has open, by resolved path (see `hold`)."""
_OPEN_LOCK = threading.Lock()


def _in_use(path: Path) -> bool:
    with _OPEN_LOCK:
        return _OPEN[path.resolve()] > 0


def hold(path: Path) -> None:
    """Count ``path`` as open in this process (a `RunStore` opened it; `release` when closed).

    A second connection to a database this process already has open skips the
    header check: reading the header opens and closes the file, and closing any
    descriptor of a file drops every POSIX lock the process holds on it, so the
    first connection's SQLite locks would be lost and another process closing
    the database last could delete the WAL under it.
    """
    with _OPEN_LOCK:
        _OPEN[path.resolve()] += 1


def release(path: Path) -> None:
    """Undo one `hold`."""
    with _OPEN_LOCK:
        _OPEN[path.resolve()] -= 1


def _check_header(path: Path) -> None:
    """Refuse a non-empty file that does not start like an SQLite database."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(len(_SQLITE_MAGIC))
    except FileNotFoundError:
        return
    except OSError as exc:
        raise StoreError(f"{path}: cannot read ({exc.strerror or exc})") from None
    if head and head != _SQLITE_MAGIC:
        raise StoreError(
            f"{path}: not a sinews database (not an SQLite file); refusing to touch it"
        )


def _identify_and_migrate(conn: sqlite3.Connection, path: Path) -> None:
    app_id = conn.execute("PRAGMA application_id").fetchone()[0]
    version = conn.execute("PRAGMA user_version").fetchone()[0]
    if app_id != APPLICATION_ID:
        tables = conn.execute("SELECT count(*) FROM sqlite_master").fetchone()[0]
        if app_id != 0 or tables or version:
            raise StoreError(
                f"{path}: an SQLite database of another application, not sinews; "
                "refusing to touch it"
            )
    if version > SCHEMA_VERSION:
        raise StoreError(
            f"{path}: made by a newer sinews (schema {version}, this one knows {SCHEMA_VERSION})"
        )
    if version == SCHEMA_VERSION:
        return
    conn.execute("BEGIN IMMEDIATE")
    try:
        # Re-read inside the write lock: another process may have migrated meanwhile.
        version = conn.execute("PRAGMA user_version").fetchone()[0]
        for step in range(version, SCHEMA_VERSION):
            for statement in _statements(MIGRATIONS[step]):
                conn.execute(statement)
        conn.execute(f"PRAGMA application_id = {APPLICATION_ID}")
        conn.execute(f"PRAGMA user_version = {SCHEMA_VERSION}")
        conn.execute("COMMIT")
    except BaseException:
        conn.execute("ROLLBACK")
        raise


def _statements(script: str) -> list[str]:
    """Split a migration script into statements (ours contain no ';' inside strings)."""
    return [s.strip() for s in script.split(";") if s.strip()]
