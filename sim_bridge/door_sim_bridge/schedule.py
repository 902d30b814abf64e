"""Periodic publications of the sim bridge in simulated time, without ROS."""

from __future__ import annotations

import math

__all__ = ["FrameSchedule", "Schedule"]


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


class FrameSchedule:
    """The head camera's frames in simulated time (s): every 1/``walking_hz`` while the robot
    walks, every 1/``standing_hz`` otherwise. Rendering is the simulation's dearest work
    (~0.14 s of CPU per VGA frame against ~0.2 s per simulated second of walking physics), and
    the detector works while the robot stands: DETECT_DOOR confirms a door from 2-4 agreeing
    frames, so its latency is a few frame periods (issue #15). Frames fall on whole multiples
    of the period of the robot's current activity (the next one after the last frame), as
    :class:`Schedule`'s do: a camera pose then shares its stamp with a /tf message (a listener
    composing the camera frame from /tf found none when the frames ran one physics step off)."""

    def __init__(self, walking_hz: float, standing_hz: float) -> None:
        if not (walking_hz > 0 and standing_hz > 0):
            raise ValueError(f"frame rates must be positive, got {walking_hz} and {standing_hz} Hz")
        self.walking_period, self.standing_period = 1.0 / walking_hz, 1.0 / standing_hz
        self.last_time = -1.0  # s: the first frame is due at 0

    def due(self, now: float, walking: bool) -> bool:
        """Whether a frame is due at ``now``; if so, it is counted as taken."""
        period = self.walking_period if walking else self.standing_period
        if now + 1e-9 < (math.floor(self.last_time / period + 1e-9) + 1.0) * period:
            return False
        self.last_time = now
        return True
