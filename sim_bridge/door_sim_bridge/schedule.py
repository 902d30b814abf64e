"""Periodic publications of the sim bridge in simulated time, without ROS."""

from __future__ import annotations

__all__ = ["Schedule"]


class Schedule:
    """Due times of a periodic publication in simulated time (s). Periods missed in a stall are
    not made up one by one: the schedule catches up with ``now``. A rate of 0 is due once, at
    the start, and never again (the node skips publications whose rate is 0)."""

    def __init__(self, rate_hz: float) -> None:
        self.period = 1.0 / rate_hz if rate_hz > 0 else float("inf")
        self.next_time = 0.0

    def due(self, now: float) -> bool:
        """Whether the publication is due at ``now``; if so, the next one is scheduled."""
        if now + 1e-9 < self.next_time:
            return False
        self.next_time = max(self.next_time + self.period, now)
        return True
