"""Where the run database lives by default, and which code a run was made by."""

from __future__ import annotations

import subprocess
from pathlib import Path

import sinews

__all__ = ["code_version", "default_db_path"]


def default_db_path() -> Path:
    """``<user data dir>/sinews/sinews.db`` (platformdirs)."""
    import platformdirs

    return Path(platformdirs.user_data_dir("sinews")) / "sinews.db"


def code_version() -> str:
    """This sinews's version, plus ``+g<commit>[.dirty]`` when it runs from a git checkout."""
    root = Path(sinews.__file__).resolve().parents[2]
    if not (root / ".git").exists():
        return sinews.__version__
    try:
        described = subprocess.run(
            ["git", "-C", str(root), "describe", "--always", "--dirty=.dirty", "--abbrev=10"],
            capture_output=True,
            text=True,
            timeout=10,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return sinews.__version__
    return f"{sinews.__version__}+g{described}"
