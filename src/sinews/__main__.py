"""The ``sinews`` script (and ``python -m sinews``): Ctrl-C exits 130 quietly at once.

Importing the command line takes a few tenths of a second (typer, numpy);
a SIGINT in that window must not print a traceback, so this module, which
imports nothing heavy, installs a handler before anything else is imported.
`sinews.cli.main` then hands SIGINT back to Python's KeyboardInterrupt.
"""

from __future__ import annotations

import signal
import sys

from sinews.interrupted import exit_interrupted


def run() -> None:
    """Entry point of the ``sinews`` console script."""
    signal.signal(signal.SIGINT, exit_interrupted)
    from sinews.cli import main

    sys.exit(main())


if __name__ == "__main__":
    run()
