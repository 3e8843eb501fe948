"""Fitness over generations as a small matplotlib figure (Agg, no GUI)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.render._output import atomic_output, suffix_of
from sinews.render.errors import RenderError

__all__ = ["plot_fitness"]

_HEADLINE = ("best", "mean", "median", "worst", "best at full weight")


def plot_fitness(
    generations: npt.ArrayLike,
    series: Mapping[str, npt.ArrayLike],
    path: str | os.PathLike[str],
    title: str = "",
    *,
    marks: Mapping[str, float] | None = None,
) -> Path:
    """Plot fitness curves per generation to a PNG, SVG or PDF and return its path.

    Series named best/mean/median/worst go on the top panel; any others
    (the fitness terms) on a panel below, since their scales differ.
    Missing values may be NaN.

    Args:
        generations: (G,) generation numbers.
        series: name → (G,) values.
        path: ``.png``, ``.svg`` or ``.pdf`` file.
        title: figure title.
        marks: label → generation, drawn as dotted vertical lines on every
            panel (e.g. where style starts and where it is full).
    """
    suffix = suffix_of(path, (".png", ".svg", ".pdf"))
    x = np.asarray(generations, dtype=np.float64).reshape(-1)
    if not series:
        raise RenderError("plot_fitness needs at least one series")
    curves = {name: np.asarray(values, dtype=np.float64) for name, values in series.items()}
    for name, values in curves.items():
        if values.shape != x.shape:
            raise RenderError(f"series {name!r} has shape {values.shape}, expected {x.shape}")
    headline = {k: v for k, v in curves.items() if k.lower() in _HEADLINE}
    terms = {k: v for k, v in curves.items() if k.lower() not in _HEADLINE}
    panels = [(group, label) for group, label in ((headline, "fitness"), (terms, "term")) if group]

    # Imported here: matplotlib is slow to load and only plots need it.
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    fig = Figure(figsize=(6.4, 0.8 + 2.4 * len(panels)), dpi=100, layout="constrained")
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (group, label) in zip(axes, panels, strict=True):
        for name, values in group.items():
            ax.plot(
                x,
                values,
                label=name,
                linewidth=2.0 if group is headline else 1.2,
                marker="o" if len(x) == 1 else None,
            )  # one generation: a dot, not nothing
        for k, (name, generation) in enumerate((marks or {}).items()):
            ax.axvline(generation, color="0.45", linestyle=":", linewidth=1.0)
            if ax is axes[0]:
                where = (generation, 1.0 - 0.08 * (k + 1))
                ax.annotate(
                    name, where, xycoords=("data", "axes fraction"), fontsize="x-small",
                    color="0.35", xytext=(3, 0), textcoords="offset points",
                )  # fmt: skip
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize="small", loc="best")
    axes[-1].set_xlabel("generation")
    axes[-1].xaxis.set_major_locator(MaxNLocator(integer=True))
    if title:
        fig.suptitle(title)
    with atomic_output(path) as tmp:
        fig.savefig(tmp, format=suffix[1:])
    return Path(path)
