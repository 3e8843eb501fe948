"""The evaluator seam: run a function over chunks of a population, here or elsewhere.

The unit of work is a *chunk*: a slice of the population simulated in one
batched rollout, never one individual per task. Three evaluators share one
interface:

* ``serial`` — in this process, one chunk for the whole population;
* ``processes`` — a local `ProcessPoolExecutor` (spawned workers; the default);
* ``dask`` — `dask.distributed` (the ``[dask]`` extra): a scheduler address,
  or a local cluster of two single-threaded worker processes.

The function and its context must be picklable (module-level functions and
plain data). A chunk's result may depend only on the chunk and the context,
so all three give identical results.
"""

from __future__ import annotations

import ctypes
import math
import os
import signal
import sys
import threading
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from multiprocessing import get_context
from types import TracebackType
from typing import Any, ClassVar, TypeVar

from sinews.errors import SinewsError, missing_extra

__all__ = [
    "EVALUATORS",
    "DaskEvaluator",
    "Evaluator",
    "ProcessEvaluator",
    "SerialEvaluator",
    "chunk_slices",
    "make_evaluator",
]

C = TypeVar("C")
T = TypeVar("T")
R = TypeVar("R")

EVALUATORS = ("serial", "processes", "dask")
_PR_SET_PDEATHSIG = 1


def chunk_slices(count: int, n_chunks: int) -> list[slice]:
    """Split ``range(count)`` into at most ``n_chunks`` contiguous, near-equal slices."""
    n_chunks = max(1, min(n_chunks, count))
    size = math.ceil(count / n_chunks)
    return [slice(start, min(start + size, count)) for start in range(0, count, size)]


def _die_with_parent(parent: int) -> None:
    """Worker initializer: end this worker when the process that started it dies.

    A pool worker blocks on its call queue, so after a SIGKILL of the parent it
    would live on, reparented to init. On Linux the kernel sends the worker
    SIGTERM when its parent dies (``PR_SET_PDEATHSIG``); elsewhere, and if the
    parent is gone already, a daemon thread polling the parent's pid ends it.
    """
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    if os.getppid() != parent:
        os._exit(1)
    if not sys.platform.startswith("linux"):
        threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()


def _watch_parent(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(1.0)
    os._exit(1)


def _in_one_thread(fn: Callable[[C, T], R], context: C, chunk: T) -> R:
    """Run ``fn`` with numba limited to one thread (workers already fill the cores)."""
    import numba

    numba.set_num_threads(1)
    return fn(context, chunk)


class Evaluator(ABC):
    """Runs ``fn(context, chunk)`` for each chunk and returns the results in order.

    Attributes:
        name: ``"serial"``, ``"processes"`` or ``"dask"``.
        n_workers: how many chunks run at once (the population is split in as many).
    """

    name: ClassVar[str]
    n_workers: int = 1

    @abstractmethod
    def map(self, fn: Callable[[C, T], R], context: C, chunks: Sequence[T]) -> list[R]:
        """``[fn(context, chunk) for chunk in chunks]``, computed by the workers."""

    def close(self) -> None:  # noqa: B027 - optional hook
        """Release the workers (nothing to release by default)."""

    def __enter__(self) -> Evaluator:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


class SerialEvaluator(Evaluator):
    """Everything in this process, in one chunk (numba uses every core)."""

    name = "serial"

    def map(self, fn: Callable[[C, T], R], context: C, chunks: Sequence[T]) -> list[R]:
        return [fn(context, chunk) for chunk in chunks]


class ProcessEvaluator(Evaluator):
    """A pool of spawned local processes, one single-threaded chunk each at a time.

    Workers end with the process that made the pool, even when it is killed.

    Args:
        workers: number of processes (default: the number of CPUs).
    """

    name = "processes"

    def __init__(self, *, workers: int | None = None) -> None:
        self.n_workers = workers or os.cpu_count() or 1
        self._pool = ProcessPoolExecutor(
            max_workers=self.n_workers,
            mp_context=get_context("spawn"),
            initializer=_die_with_parent,
            initargs=(os.getpid(),),
        )

    def map(self, fn: Callable[[C, T], R], context: C, chunks: Sequence[T]) -> list[R]:
        futures = [self._pool.submit(_in_one_thread, fn, context, chunk) for chunk in chunks]
        try:
            return [future.result() for future in futures]
        except BrokenProcessPool:
            raise SinewsError("a worker process died (out of memory, or killed)") from None

    def close(self) -> None:
        self._pool.shutdown(cancel_futures=True)


class DaskEvaluator(Evaluator):
    """Chunks as Dask tasks; the context is scattered to every worker once per call.

    Args:
        scheduler: address of a running scheduler (``tcp://host:8786``); None
            starts a local cluster of ``workers`` single-threaded processes.
        workers: workers of the local cluster.

    Raises:
        SinewsError: dask is not installed, or the scheduler cannot be reached.
    """

    name = "dask"

    def __init__(self, *, scheduler: str | None = None, workers: int = 2) -> None:
        try:
            from dask.distributed import Client, LocalCluster
        except ImportError:
            raise missing_extra("dask.distributed", "dask") from None
        self._cluster: Any = None
        try:
            if scheduler is None:
                self._cluster = LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=True,
                    host="127.0.0.1",
                    dashboard_address=None,
                )
                self._client = Client(self._cluster)
            else:
                self._client = Client(scheduler, timeout=10)
        except OSError as exc:
            self.close()
            raise SinewsError(f"cannot reach the Dask scheduler {scheduler}: {exc}") from None
        self.n_workers = max(1, len(self._client.scheduler_info()["workers"]))

    @property
    def address(self) -> str:
        """The scheduler's address (e.g. of the local cluster, for other clients)."""
        return str(self._client.scheduler_info()["address"])

    def map(self, fn: Callable[[C, T], R], context: C, chunks: Sequence[T]) -> list[R]:
        shared = self._client.scatter(context, broadcast=True, hash=False)
        futures = [
            self._client.submit(_in_one_thread, fn, shared, chunk, pure=False) for chunk in chunks
        ]
        return list(self._client.gather(futures))

    def close(self) -> None:
        client = getattr(self, "_client", None)
        if client is not None:
            client.close()
        if self._cluster is not None:
            self._cluster.close()


def make_evaluator(
    name: str, *, workers: int | None = None, scheduler: str | None = None
) -> Evaluator:
    """The evaluator called ``name`` (see `EVALUATORS`).

    Args:
        name: ``"serial"``, ``"processes"`` or ``"dask"``.
        workers: worker processes (processes: default all CPUs; dask local cluster: default 2).
        scheduler: Dask scheduler address (dask only).

    Raises:
        SinewsError: unknown name, a scheduler given to a non-Dask evaluator,
            or the evaluator cannot start.
    """
    if scheduler is not None and name != "dask":
        raise SinewsError("--scheduler needs --executor dask")
    if name == "serial":
        return SerialEvaluator()
    if name == "processes":
        return ProcessEvaluator(workers=workers)
    if name == "dask":
        return DaskEvaluator(scheduler=scheduler, workers=workers or 2)
    raise SinewsError(f"no executor called {name!r}; choose from {', '.join(EVALUATORS)}")
