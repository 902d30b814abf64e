"""A SIGTERM ends the main job and the Monte-Carlo as a Ctrl-C does.

Python's default SIGTERM kills the process where it stands: no ``finally`` runs, so the
graph's node processes (each in its own session, out of reach of the terminal) and a
Monte-Carlo's worker processes were left running. Raising :class:`KeyboardInterrupt`
instead unwinds through :func:`door_bringup.door_task.run_task`, which stops the graph.
:func:`signals_deferred` holds a stop back while a node process is being started, until the
supervisor can stop it (:mod:`door_bringup.processes`).
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

__all__ = ["DEFERRED_SIGNALS", "INTERRUPTED", "interrupt_on_sigterm", "signals_deferred"]

INTERRUPTED = 130
"""The exit code of a run ended by Ctrl-C or SIGTERM (128 + SIGINT, as shells report it)."""


def interrupt_on_sigterm() -> None:
    """From now on a SIGTERM raises :class:`KeyboardInterrupt` in the main thread."""
    signal.signal(signal.SIGTERM, _interrupt)


def _interrupt(signum: int, frame: FrameType | None) -> None:
    raise KeyboardInterrupt(signal.Signals(signum).name)


DEFERRED_SIGNALS = (signal.SIGINT, signal.SIGTERM)


@contextmanager
def signals_deferred() -> Iterator[None]:
    """SIGINT and SIGTERM arriving inside the block are re-raised when it ends, to the handlers
    in place before it (the first one only: a stop is a stop). Python handles signals in the
    main thread alone; elsewhere, or with a handler not set from Python, nothing is deferred."""
    handlers = {sig: signal.getsignal(sig) for sig in DEFERRED_SIGNALS}
    if threading.current_thread() is not threading.main_thread() or None in handlers.values():
        yield
        return
    caught: list[int] = []
    for sig in DEFERRED_SIGNALS:
        signal.signal(sig, lambda number, _frame: caught.append(number))
    try:
        yield
    finally:
        for sig, handler in handlers.items():
            signal.signal(sig, handler)
        if caught:
            signal.raise_signal(caught[0])
