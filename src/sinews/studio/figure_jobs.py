"""Figure runs evolved in the background while the page watches: start, progress, pause.

One job at a time (the machine's cores are the job's), on a thread of its
own with its own `RunStore` connection to the studio's database. A job
extends its run one generation at a time through the run kind
(`RunKind.run` with ``generations`` = one more), so every generation is stored
as it is made, a pause takes effect between generations, and a run paused,
or a studio killed mid-job, is continued by ``sinews runs resume RUN`` or by
the page exactly as an uninterrupted run would have gone on. The motion a job
simulates while scoring goes into the run's motion log, so the page draws the
generations it made without simulating them again.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sinews.errors import SinewsError
from sinews.evolve import SerialEvaluator
from sinews.experiments.kinds import kind_of
from sinews.experiments.motion_log import MotionLog
from sinews.store import RunStore

__all__ = ["FigureJobs", "Job"]

_log = logging.getLogger(__name__)


@dataclass
class Job:
    """One background run's progress (read by the page, written by the job's thread).

    Attributes:
        run_id: the run.
        target: the generation count it runs to.
        done: generations stored so far.
        pausing: asked to stop after the generation it is making.
        running: its thread has not ended.
        error: why it stopped early, or None.
    """

    run_id: int
    target: int
    done: int
    pausing: bool = False
    running: bool = True
    error: str | None = None

    def to_json(self) -> dict[str, Any]:
        """What the page's progress bar shows."""
        return {"target": self.target, "done": self.done, "running": self.running,
                "pausing": self.pausing, "error": self.error}  # fmt: skip


class FigureJobs:
    """Background evolution of figure runs in one database.

    Args:
        db: the run database.
        logs: the motion log of a run (`FigureRuns.motion_log`).
    """

    def __init__(self, db: Path, logs: Callable[[int], MotionLog]) -> None:
        self.db = db
        self._logs = logs
        self._lock = threading.Lock()
        self._jobs: dict[int, Job] = {}
        self._thread: threading.Thread | None = None

    def start(self, run_id: int, done: int, more: int) -> Job:
        """Evolve ``more`` generations of a run that has ``done`` in the background.

        Raises:
            SinewsError: another run is evolving (one job at a time).
        """
        with self._lock:
            if self._thread is not None and self._thread.is_alive():
                busy = next(j.run_id for j in self._jobs.values() if j.running)
                raise SinewsError(f"run {busy} is evolving; pause it first")
            job = Job(run_id=run_id, target=done + more, done=done)
            self._jobs[run_id] = job
            self._thread = threading.Thread(
                target=self._evolve, args=(job,), name=f"sinews-figure-run-{run_id}", daemon=True
            )
            self._thread.start()
        return job

    def pause(self, run_id: int) -> None:
        """Ask a run's job to stop after the generation it is making (nothing if none runs)."""
        with self._lock:
            job = self._jobs.get(run_id)
            if job is not None and job.running:
                job.pausing = True

    def job(self, run_id: int) -> Job | None:
        """The run's latest job, if this studio ran one."""
        with self._lock:
            return self._jobs.get(run_id)

    def busy(self, run_id: int) -> bool:
        """Whether a job of this studio is evolving the run now."""
        job = self.job(run_id)
        return job is not None and job.running

    def close(self) -> None:
        """Pause every job and wait for it (at most one generation)."""
        with self._lock:
            for job in self._jobs.values():
                job.pausing = True
            thread = self._thread
        if thread is not None:
            thread.join()

    def _evolve(self, job: Job) -> None:
        try:
            with RunStore(self.db) as store:
                kind = kind_of(store.run(job.run_id))
                evaluator = SerialEvaluator()
                log = self._logs(job.run_id)
                while not job.pausing and job.done < job.target:
                    kind.run(store, job.run_id, evaluator=evaluator, generations=job.done + 1,
                             log=log)  # fmt: skip
                    done = store.last_generation(job.run_id) + 1
                    if done == job.done:  # the run's own rule ended it (GP's --until)
                        break
                    job.done = done
        except SinewsError as exc:
            job.error = str(exc).splitlines()[0]
        except Exception as exc:  # reported to the page; the run is marked failed
            _log.exception("figure run %d failed", job.run_id)
            job.error = f"internal error ({type(exc).__name__})"
        finally:
            job.running = False
