"""Motion recorded while scoring, so a replay need not simulate it again.

A figure's rollout is deterministic and does not depend on the batch, so the
motion a scorer simulated is the motion `RunKind.replay` would simulate. When
a scorer is given a `MotionLog`, its chunks record the motion at the log's
rate and the log keeps it by genome key; `RunKind.replay` with the same log
rebuilds those replays from it and simulates only the rest. The studio keeps
one log per figure run, so the generation it just bred is drawn at once.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = ["MotionLog", "recall"]


@dataclass(eq=False)
class MotionLog:
    """The last ``capacity`` genomes' recorded motion, by genome key (oldest dropped first).

    Safe to share between threads: the studio's background job writes while its worker
    thread reads.

    Attributes:
        hz: frames per second of the recorded motion.
        capacity: genomes kept.
    """

    hz: float
    capacity: int = 256
    _motion: OrderedDict[Hashable, Any] = field(default_factory=OrderedDict, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def put(self, key: Hashable, motion: Any) -> None:
        """Keep ``motion`` (a kind's own record of one genome's rollout) under ``key``."""
        with self._lock:
            self._motion[key] = motion
            self._motion.move_to_end(key)
            while len(self._motion) > self.capacity:
                self._motion.popitem(last=False)

    def get(self, key: Hashable) -> Any | None:
        """The motion kept under ``key``, or None."""
        with self._lock:
            return self._motion.get(key)


def recall(
    log: MotionLog | None,
    hz: float,
    keys: Sequence[Hashable],
    simulate: Callable[[list[int]], Sequence[Any]],
) -> list[Any]:
    """Each genome's motion at ``hz``: the log's where it kept that genome at that rate, else
    what ``simulate(rows)`` records for the rows it lacks (in their order)."""
    kept = log if log is not None and log.hz == hz else None
    motion = [None if kept is None else kept.get(key) for key in keys]
    missing = [row for row, found in enumerate(motion) if found is None]
    if missing:
        for row, found in zip(missing, simulate(missing), strict=True):
            motion[row] = found
    return motion
