"""Fixtures for the render tests (helpers live in render_helpers.py)."""

from __future__ import annotations

import pytest

from render_helpers import make_dancer
from sinews.trajectory import Trajectory


@pytest.fixture
def dancer() -> Trajectory:
    """The default 30-frame dancer with colours, radii, forces and triggers."""
    return make_dancer()
