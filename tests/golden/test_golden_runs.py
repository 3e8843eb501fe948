"""Golden runs: a tiny run of every kind, evolved and replayed, must not drift between versions.

Each case runs ``sinews evolve`` in a subprocess (the real entry point, serial
executor), then hashes what the run store holds (genomes, fitness, terms,
lineage) and the replayed trajectory of the run's best. The hashes are in
``golden_runs.json``; ``SINEWS_GOLDEN_UPDATE=1 pytest tests/golden`` rewrites
them, which is only right when a change of physics or evolution is intended
(say so in the commit message).
"""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from golden_replays import replay_positions
from killed_runs import sinews_command
from sinews.store import RunStore

GOLDEN = Path(__file__).with_name("golden_runs.json")
CASES: dict[str, list[str]] = {
    "dancers": ["dancers", "--song", "demo:groove", "--population", "4", "--generations",
                "2", "--seconds", "2", "--seed", "3"],
    "springnet-snake": ["snake", "--population", "8", "--generations", "2", "--seconds",
                        "1", "--seed", "3"],
    "gp-luxo": ["luxo", "--controller", "gp", "--task", "hop", "--population", "8",
                "--generations", "2", "--seconds", "0.5", "--seed", "3"],
    "gp-luxo3d": ["luxo3d", "--controller", "gp", "--task", "hop", "--target", "1.0,0.5",
                  "--population", "8", "--generations", "2", "--seconds", "0.5", "--seed", "3"],
    "gp-humanoid3d": ["humanoid3d", "--controller", "gp", "--task", "touch", "--population",
                      "6", "--generations", "2", "--seconds", "0.3", "--seed", "3"],
}  # fmt: skip


def _digest(*arrays: np.ndarray) -> str:
    hasher = hashlib.sha256()
    for array in arrays:
        array = np.ascontiguousarray(array)
        hasher.update(f"{array.dtype.str}{array.shape}".encode())
        hasher.update(array.tobytes())
    return hasher.hexdigest()[:32]


def _private_env(tmp_path: Path) -> dict[str, str]:
    """This environment with XDG data and cache folders under ``tmp_path``, and numpy's
    SIMD loops held at the level the hashes were made at (`AVX512_LOOPS` off)."""
    return {**os.environ, "XDG_DATA_HOME": str(tmp_path / "data"),
            "XDG_CACHE_HOME": str(tmp_path / "cache"),
            "NPY_DISABLE_CPU_FEATURES": " ".join(_avx512_loops())}  # fmt: skip


AVX512_LOOPS = ("X86_V4", "AVX512_ICL", "AVX512_SPR")
"""numpy's AVX-512 loops: they round some functions (sin, exp, ...) differently in the last
bit from its AVX2 loops (X86_V3), which made the hashes; on such a CPU the dancers and
the 3D lamp evolve differently (measured on a Xeon with AVX-512, numpy 2.4)."""


def _avx512_loops() -> list[str]:
    """The `AVX512_LOOPS` this CPU has (numpy refuses to disable one it lacks)."""
    found = importlib.import_module("numpy._core._multiarray_umath").__cpu_features__
    return [name for name in AVX512_LOOPS if found.get(name)]


def _exact(value: object) -> list[str]:
    """An array as the hex of its float64 values (no rounding), for json.dumps."""
    return [float(v).hex() for v in np.asarray(value, dtype=np.float64).ravel()]


def _stored(db: Path) -> tuple[str, str]:
    """Hashes of the run's stored individuals and of its best's replayed positions."""
    with RunStore(db) as store:
        (info,) = store.runs()
        people = store.individuals(info.id)
        genomes = json.dumps([p.genome for p in people], sort_keys=True, default=_exact)
        numbers = np.array(
            [[p.fitness if p.fitness is not None else np.nan, p.seed or 0] for p in people]
        )
        terms = json.dumps([p.terms for p in people], sort_keys=True)
        lineage = json.dumps([p.parents for p in people])
        stored = _digest(
            np.frombuffer((genomes + terms + lineage).encode(), dtype=np.uint8), numbers
        )
        return stored, _digest(replay_positions(store, info.id))


@pytest.mark.parametrize("kind", list(CASES))
def test_a_tiny_run_of_every_kind_matches_its_golden_hashes(kind: str, tmp_path: Path) -> None:
    db = tmp_path / "runs.db"
    done = subprocess.run(
        [*sinews_command(), "evolve", *CASES[kind], "--executor", "serial", "--db", str(db)],
        capture_output=True,
        text=True,
        timeout=600,
        env=_private_env(tmp_path),
    )
    assert done.returncode == 0, done.stderr
    got = dict(zip(("stored", "replayed"), _stored(db), strict=True))
    golden = json.loads(GOLDEN.read_text()) if GOLDEN.exists() else {}
    if os.environ.get("SINEWS_GOLDEN_UPDATE") == "1":
        golden[kind] = got
        GOLDEN.write_text(json.dumps(golden, indent=1, sort_keys=True) + "\n")
    assert golden.get(kind) == got


def test_a_studio_session_matches_its_golden_hash(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Breeding by picks, with a mutation change and a branch from an earlier generation."""
    from golden_replays import studio_session

    for name in ("XDG_DATA_HOME", "XDG_CACHE_HOME"):
        monkeypatch.setenv(name, str(tmp_path / name))
    hashes = []
    with RunStore(tmp_path / "studio.db") as store:
        for run_id in studio_session(store, tmp_path / "songs"):
            people = store.individuals(run_id)
            rows = [[p.genome, p.parents, p.picked, p.seed] for p in people]
            text = json.dumps(rows, default=_exact)
            hashes.append(_digest(np.frombuffer(text.encode(), dtype=np.uint8)))
    got = {"stored": ",".join(hashes)}
    golden = json.loads(GOLDEN.read_text())
    if os.environ.get("SINEWS_GOLDEN_UPDATE") == "1":
        golden["studio"] = got
        GOLDEN.write_text(json.dumps(golden, indent=1, sort_keys=True) + "\n")
    assert golden.get("studio") == got
