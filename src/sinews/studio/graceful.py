"""uvicorn's server, stopped by Ctrl+C as the rest of `sinews` is.

The first Ctrl+C (or SIGTERM) stops the studio gracefully: open connections are closed, then
the app's shutdown waits for the generation in progress and closes the store. uvicorn's own
handling differs in two ways that printed tracebacks: a second Ctrl+C "force quits", skipping
the app's shutdown, and after stopping it raises every signal it caught again, interrupting
the event loop while the app's lifespan task still waits. Here a second Ctrl+C quits at once,
as `sinews` does while it starts (exit 130, "interrupted"; the store is SQLite's, whole after
any exit), and the signal that stopped the server is left to the caller (`stopped_by`).
"""

from __future__ import annotations

from types import FrameType

import uvicorn

from sinews.interrupted import exit_interrupted

__all__ = ["GracefulServer"]


class GracefulServer(uvicorn.Server):
    """A `uvicorn.Server` that stops gracefully on the first signal and at once on the next.

    Attributes:
        stopped_by: the signal that stopped it, or None.
    """

    stopped_by: int | None = None

    def handle_exit(self, sig: int, frame: FrameType | None) -> None:
        """Signal handler (uvicorn installs it while serving; install it before, too)."""
        if self.should_exit:
            exit_interrupted(sig, frame)
        self.stopped_by = sig
        self.should_exit = True
