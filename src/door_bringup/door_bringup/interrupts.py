"""A SIGTERM ends the main job and the Monte-Carlo as a Ctrl-C does.

Python's default SIGTERM kills the process where it stands: no ``finally`` runs, so the
graph's node processes (each in its own session, out of reach of the terminal) and a
Monte-Carlo's worker processes were left running. Raising :class:`KeyboardInterrupt`
instead unwinds through :func:`door_bringup.door_task.run_task`, which stops the graph.
"""

from __future__ import annotations

import signal
from types import FrameType

__all__ = ["INTERRUPTED", "interrupt_on_sigterm"]

INTERRUPTED = 130
"""The exit code of a run ended by Ctrl-C or SIGTERM (128 + SIGINT, as shells report it)."""


def interrupt_on_sigterm() -> None:
    """From now on a SIGTERM raises :class:`KeyboardInterrupt` in the main thread."""
    signal.signal(signal.SIGTERM, _interrupt)


def _interrupt(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt(signal.Signals(signum).name)
