"""The README opens with the two commands, and CI runs the test one."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def readme_commands() -> list[str]:
    text = (ROOT / "README.md").read_text()
    return re.findall(r"```bash\n(.+?)\n```", text, flags=re.S)


def test_readme_opens_with_setup_and_test_commands() -> None:
    main_job, tests = readme_commands()[:2]
    assert "python3 -m venv" in main_job and "sinews " in main_job
    assert "python3 -m venv" in tests and "pytest" in tests


def test_ci_runs_the_readme_test_command() -> None:
    tests = readme_commands()[1]
    assert tests in (ROOT / ".ci" / "run").read_text()
