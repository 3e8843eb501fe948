"""The wiring of each kind of experiment; the CLI and the studio call these."""

from __future__ import annotations
