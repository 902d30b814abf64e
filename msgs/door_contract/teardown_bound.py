"""A node's teardown that cannot outlive its bound.

Destroying a node's publishers or the node itself inside Fast DDS deadlocks now and then
(seen three times: ``Publisher.destroy`` in the main job's operator node, stop 38; the sim
bridge's ``destroy_node`` → ``destroy_when_not_in_use`` in a Monte-Carlo trial and in CI, stop
42 — about one sim-bridge shutdown in 40; eProsima/Fast-DDS#6193 reports the same on
simultaneous start/stop). The lock is never released: the node ran on after its work was done
until the graph's supervisor SIGKILLed it, and a ``ros2 run`` stopped with Ctrl-C would hang
for good.

A hung middleware call holds the GIL (rclpy's ``destroy_when_not_in_use`` does not release it),
so no Python timer or waiting thread can end it. The bound is kept by the
kernel instead: :func:`bounded_teardown` arms ``ITIMER_REAL`` with SIGALRM's *default* action
(terminate the process), and faulthandler's own C thread dumps every thread's stack to stderr
(the node's log) first. A process ended so reports ``-SIGALRM`` to :mod:`subprocess`
(:data:`TEARDOWN_ABANDONED`); its work was done, its sockets and memory go with the process,
and its peers see it leave when its participant lease ends (2 s, params/fastdds_profile.xml).
"""

from __future__ import annotations

import faulthandler
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

__all__ = ["TEARDOWN_ABANDONED", "TeardownBound", "bounded_teardown"]

TEARDOWN_ABANDONED = signal.SIGALRM
"""The signal that ends a process whose teardown outlived its bound."""


@dataclass(frozen=True)
class TeardownBound:
    """When a teardown is reported slow and when it is abandoned (s, wall clock from its start).

    A node's teardown takes milliseconds, even with four graphs on two cores. ``limit_s`` stays
    below the graph supervisor's SIGINT grace (5 s, :class:`door_bringup.processes.ProcessSupervisor`),
    so a hung node ends itself before the supervisor's SIGTERM and SIGKILL.
    """

    stacks_after_s: float = 2.0
    limit_s: float = 4.0

    def __post_init__(self) -> None:
        if not 0.0 < self.stacks_after_s < self.limit_s:
            raise ValueError(f"teardown bound: need 0 < stacks_after_s < limit_s, got "
                             f"{self.stacks_after_s} and {self.limit_s}")


@contextmanager
def bounded_teardown(bound: TeardownBound) -> Iterator[None]:
    """Run the block under ``bound``: stacks dumped after ``stacks_after_s``, the process
    ended by SIGALRM after ``limit_s``. Call from the main thread (Python's signal rule)."""
    faulthandler.dump_traceback_later(bound.stacks_after_s, exit=False)
    previous = signal.signal(TEARDOWN_ABANDONED, signal.SIG_DFL)
    signal.setitimer(signal.ITIMER_REAL, bound.limit_s)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(TEARDOWN_ABANDONED, previous)
        faulthandler.cancel_dump_traceback_later()
