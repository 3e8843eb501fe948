"""Articulated planar figures on MuJoCo: Luxo lamp, snake, humanoid, and batched rollouts.

Importing this package needs no MuJoCo; building a figure or running a rollout
does, and raises a `sinews.errors.SinewsError` naming the ``figures`` extra when
it is missing (`require_mujoco` is that check, for code outside this package
that calls MuJoCo directly).
"""

from __future__ import annotations

from sinews.figures._mujoco import require_mujoco
from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid import HumanoidShape, humanoid, humanoid_mjcf
from sinews.figures.luxo import LuxoShape, luxo, luxo_mjcf
from sinews.figures.rollout import Observer, RolloutResult, rollout
from sinews.figures.sensors import sensor_columns
from sinews.figures.snake import SnakeShape, snake, snake_mjcf

__all__ = [
    "Figure",
    "FigureError",
    "HumanoidShape",
    "LuxoShape",
    "Observer",
    "RolloutResult",
    "SnakeShape",
    "humanoid",
    "humanoid_mjcf",
    "luxo",
    "luxo_mjcf",
    "require_mujoco",
    "rollout",
    "sensor_columns",
    "snake",
    "snake_mjcf",
]
