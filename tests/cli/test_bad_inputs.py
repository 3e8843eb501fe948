"""Bad input through the installed ``sinews``: one line on stderr, exit 2, nothing created.

Each case is a file or a number a user could hand over by mistake (or on
purpose): absurd sizes, forged headers, huge integers, deep nesting, text that
is not UTF-8. Memory is capped in the child, so an unbounded allocation fails
the test instead of the machine.
"""

from __future__ import annotations

import io
import json
import os
import resource
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from killed_runs import sinews_command

MEMORY_CAP = 4 * 2**30


def _cap_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))


def run(folder: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "XDG_DATA_HOME": str(folder / "d"), "XDG_CACHE_HOME": str(folder / "c")}
    return subprocess.run([*sinews_command(), *args], capture_output=True, text=True, cwd=folder,
                          env=env, timeout=300, preexec_fn=_cap_memory)  # fmt: skip


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder of bad inputs beside a good genome, song, trajectory and run database."""
    folder = tmp_path_factory.mktemp("bad")
    rate = 22050
    tone = np.sin(2 * np.pi * 440 * np.arange(2 * rate) / rate).astype(np.float32)
    sf.write(folder / "ok.wav", 0.3 * tone, rate)
    sf.write(folder / "ok.mp3", np.tile(0.3 * tone, 3), rate)
    sf.write(folder / "slow.wav", tone[:1000], 100)  # 10 s at 100 Hz
    mp3 = bytearray((folder / "ok.mp3").read_bytes())
    picks = np.random.default_rng(1)
    for at in picks.integers(1000, len(mp3), 200):
        mp3[at] = picks.integers(256)
    (folder / "flipped.mp3").write_bytes(bytes(mp3))  # libmpg123 prints notes about it
    (folder / "noise.mp3").write_bytes(picks.bytes(5000))
    assert run(folder, "dancer", "new", "-o", "g.json").returncode == 0
    text = (folder / "g.json").read_text()
    gene = json.dumps(json.loads(text)["body"]["stiffness"])
    for name, value in [("bigint", "1" + "0" * 400), ("hugeint", "9" * 5000),
                        ("deep", "[" * 3000 + "]" * 3000)]:  # fmt: skip
        (folder / f"{name}.json").write_text(text.replace(gene, value, 1))
    (folder / "nonutf8.toml").write_bytes(b"population = 4\n\xff\xfe")
    (folder / "nonutf8.keep").write_bytes(b"0: 1\n\xff\xfe")
    (folder / "long.toml").write_text("seconds = 1e9\n")
    (folder / "fast.toml").write_text("physics_hz = 1000000000000\n")
    (folder / "deep.toml").write_text("population = " + "[" * 100_000 + "]" * 100_000 + "\n")
    (folder / "longint.toml").write_text("population = " + "9" * 5000 + "\n")
    (folder / "infseed.toml").write_text("seed = 1e999\n")
    (folder / "softshare.toml").write_text('[strategy]\nname = "gp"\nsoft_share = 2\n')
    (folder / "softpareto.toml").write_text(
        '[strategy]\nname = "gp"\nselection = "pareto"\nsoft_share = 0.45\n'
    )
    (folder / "lamplist.toml").write_text('lamp = ["aimed"]\n')
    made = run(folder, "dance", "g.json", "-o", "d.png", "--seconds", "1", "--trajectory", "t.npz")
    assert made.returncode == 0, made.stderr
    raw = (folder / "t.npz").read_bytes()
    (folder / "trunc.npz").write_bytes(raw[: len(raw) // 2])
    flipped = bytearray(raw)
    flipped[len(raw) // 2] ^= 0xFF
    (folder / "flip.npz").write_bytes(bytes(flipped))
    arrays = dict(np.load(folder / "t.npz"))
    np.savez(folder / "strfps.npz", **{**arrays, "fps": np.array("abc")})
    nan = arrays["positions"].copy()
    nan[3, 2, 0] = np.nan
    np.savez(folder / "nanpos.npz", **{**arrays, "positions": nan})
    with zipfile.ZipFile(folder / "forged.npz", "w") as archive:  # a header of 127 GiB
        for name, value in arrays.items():
            buffer = io.BytesIO()
            np.save(buffer, value)
            data = buffer.getvalue()
            if name == "positions":
                data = data.replace(repr(value.shape).encode(), b"(1000000000, 17, 2)", 1)
            archive.writestr(f"{name}.npy", data)
    song = ["--song", "ok.wav", "--seconds", "1", "--population", "4", "--generations", "1"]
    assert run(folder, "evolve", "dancers", *song, "--executor", "serial", "--db",
               "r.db").returncode == 0  # fmt: skip
    return folder


BIG = str(2**63)
CASES = [
    ["dance", "bigint.json", "-o", "o.png"],
    ["dance", "hugeint.json", "-o", "o.png"],
    ["dance", "deep.json", "-o", "o.png"],
    ["dance", "g.json", "-o", "o.png", "--song", "ok.wav", "--bpm", "0"],
    ["dance", "g.json", "-o", "o.png", "--song", "ok.wav", "--bpm", "nan"],
    ["dance", "g.json", "-o", "o.png", "--song", "ok.wav", "--bpm", "1e300"],
    ["dance", "g.json", "-o", "o.png", "--size", "100000", "--seconds", "1"],
    ["dance", "g.json", "-o", "o.png", "--seconds", "1e12"],
    ["dance", "g.json", "-o", "o.png", "--seconds", "1", "--trajectory", "no/such/t.npz"],
    ["scene", "kittens", "-o", "k.png", "--seconds", "0.1", "--trajectory", "no/such/t.npz"],
    ["runs", "show", BIG, "--db", "r.db"],
    ["runs", "resume", "9" * 20, "--db", "r.db"],
    ["runs", "best", BIG, "-o", "b.json", "--db", "r.db"],
    ["runs", "lineage", BIG, "--db", "r.db"],
    ["runs", "export", BIG, "-o", "ex", "--db", "r.db"],
    ["runs", "resume", "1", "--generations", "-5", "--db", "r.db"],
    ["runs", "show", str(2**62), "--db", "r.db"],
    ["render", BIG, "--best", "-o", "x.png", "--db", "r.db"],
    ["studio", "--port", "80000", "--no-browser"],
    ["studio", "--port", "-1", "--no-browser"],
    ["evolve", "dancers", "--song", "ok.wav", "--config", "nonutf8.toml", "--db", "r.db"],
    ["evolve", "snake", "--controller", "springnet", "--keep", "nonutf8.keep", "--db", "r.db"],
    ["evolve", "snake", "--controller", "springnet", "--masses", "100000", "--db", "r.db"],
    ["evolve", "dancers", "--song", "ok.wav", "--population", "10000000", "--db", "r.db"],
    ["evolve", "snake", "--controller", "gp", "--db", "r.db"],
    ["evolve", "dancers", "--song", "ok.wav", "--strategy", "gp", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--strategy", "alton", "--db", "r.db"],
    ["evolve", "luxo3d", "--controller", "springnet", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--seconds", "1e9", "--db", "r.db"],
    ["evolve", "luxo3d", "--controller", "gp", "--config", "long.toml", "--db", "r.db"],
    ["evolve", "snake", "--controller", "springnet", "--seconds", "1e9", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "fast.toml", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "deep.toml", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "longint.toml", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "infseed.toml", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "softshare.toml", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--config", "softpareto.toml", "--db", "r.db"],
    ["evolve", "luxo3d", "--controller", "gp", "--lamp", "glass", "--db", "r.db"],
    ["evolve", "luxo", "--controller", "gp", "--lamp", "aimed", "--db", "r.db"],
    ["evolve", "luxo3d", "--controller", "gp", "--config", "lamplist.toml", "--db", "r.db"],
    [
        "evolve",
        "luxo",
        "--controller",
        "gp",
        "--config",
        "infseed.toml",
        "--runs",
        "2",
        "--db",
        "r.db",
    ],
    ["evolve", "luxo", "--controller", "gp", "--seed", "9" * 30, "--db", "r.db"],
    ["evolve", "snake", "--controller", "springnet", "--config", "fast.toml", "--db", "r.db"],
    ["evolve", "dancers", "--song", "ok.wav", "--generations", "10" * 7, "--db", "r.db"],
    ["score", "trunc.npz", "--song", "ok.wav"],
    ["score", "flip.npz", "--song", "ok.wav"],
    ["score", "strfps.npz", "--song", "ok.wav"],
    ["score", "forged.npz", "--song", "ok.wav"],
    ["score", "nanpos.npz", "--song", "ok.wav"],
    ["songs", "analyse", "flipped.mp3"],
    ["songs", "analyse", "noise.mp3"],
    ["songs", "analyse", "slow.wav"],
    ["dance", "g.json", "-o", "o.png", "--song", "slow.wav"],
    ["scene", "kittens", "-o", "k.png", "--height", "100000000", "--seconds", "0.1"],
    ["scene", "kittens", "-o", "k.png", "--seconds", "1e9"],
    ["sheet", "-o", "s.png", "--seconds", "1e12"],
]


@pytest.mark.parametrize("args", CASES, ids=[" ".join(c)[:60] for c in CASES])
def test_bad_input_is_one_line_exit_2(files: Path, args: list[str]) -> None:
    before = (files / "r.db").read_bytes()
    result = run(files, *args)
    assert result.returncode == 2, result.stderr[-2000:]
    assert len(result.stderr.splitlines()) == 1, result.stderr[-2000:]
    assert result.stderr.startswith("error: ")
    assert "Traceback" not in result.stdout
    assert (files / "r.db").read_bytes() == before  # nothing lost or changed


def test_an_unknown_gl_back_end_is_one_line(tmp_path: Path) -> None:
    # MuJoCo refuses a MUJOCO_GL it does not know as it loads, before any rendering.
    result = subprocess.run(
        [*sinews_command(), "evolve", "luxo", "--controller", "gp", "--db", "r.db"],
        capture_output=True, text=True, cwd=tmp_path, timeout=300,
        env={**os.environ, "MUJOCO_GL": "vulkan-please"},
    )  # fmt: skip
    assert result.returncode == 2, result.stderr[-2000:]
    assert result.stderr.splitlines() == [result.stderr.strip()]
    assert "cannot load MuJoCo" in result.stderr and "MUJOCO_GL" in result.stderr


def test_read_commands_create_nothing(tmp_path: Path) -> None:
    result = run(tmp_path, "runs", "list", "--db", "nonexist_dir/x.db")
    assert result.returncode == 2
    assert result.stderr == "error: nonexist_dir/x.db: no such run database\n"
    assert not (tmp_path / "nonexist_dir").exists()


def test_runs_list_reads_a_database_on_a_read_only_file_system(files: Path, tmp_path: Path) -> None:
    source, mounted = tmp_path / "source", tmp_path / "readonly"
    source.mkdir()
    mounted.mkdir()
    (source / "r.db").write_bytes((files / "r.db").read_bytes())
    bind = subprocess.run(["mount", "--bind", str(source), str(mounted)], capture_output=True)
    if bind.returncode != 0:
        pytest.skip("a read-only bind mount needs root")
    try:
        remount = ["mount", "-o", "remount,bind,ro", str(mounted)]
        assert subprocess.run(remount, capture_output=True).returncode == 0
        result = run(tmp_path, "runs", "list", "--db", str(mounted / "r.db"))
        shown = run(tmp_path, "runs", "show", "1", "--db", str(mounted / "r.db"))
    finally:
        subprocess.run(["umount", str(mounted)], check=True)
    assert result.returncode == 0, result.stderr
    assert "dancers" in result.stdout
    assert shown.returncode == 0, shown.stderr


@pytest.mark.parametrize("song", ["demo:groove", "huge.wav"])
def test_songs_a_user_may_give_dance_to(files: Path, song: str) -> None:
    """Demo songs work for ``dance`` as for ``evolve``; a float file far past full scale plays."""
    rate = 22050
    tone = np.sin(2 * np.pi * 440 * np.arange(2 * rate) / rate)
    sf.write(files / "huge.wav", (1e20 * tone).astype(np.float32), rate, subtype="FLOAT")
    result = run(files, "dance", "g.json", "-o", "s.png", "--song", song, "--seconds", "1")
    assert result.returncode == 0, result.stderr


def test_score_counts_the_beats_of_the_motion_not_of_the_song(files: Path) -> None:
    result = run(files, "score", "t.npz", "--song", "demo:groove")
    assert result.returncode == 0, result.stderr
    heard = int(result.stdout.split("(")[1].split()[0])
    assert 1 <= heard <= 4  # a 1 s motion; the demo song has dozens of beats
    assert "in the 1.0 s motion" in result.stdout
