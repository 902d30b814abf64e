"""The door estimates a planner has heard, so a request can name the one the operator approved."""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from door_contract.payloads import DoorEstimate, decode
from door_contract.ranges import FieldRange

__all__ = ["DOOR_ANGLE_RANGE", "DOOR_NORMAL_MAX_UP", "DOOR_WIDTH_RANGE", "DoorEstimateHistory", "door_angle_problem",
           "door_estimate_problem", "normal_is_horizontal", "requested_estimate_problem"]

DOOR_WIDTH_RANGE = FieldRange(0.3, 2.5, "m")
"""Door widths a planner accepts (the detector's width parameters stay inside it)."""

DOOR_NORMAL_MAX_UP = 0.5
"""Largest |n_z| / |n| of a door normal in odom (z up): a door is a vertical plane (the normal
60° from vertical at most, far beyond any real door's tilt or depth noise)."""

DOOR_ANGLE_RANGE = FieldRange(-0.1, 2.0, "rad")
"""Hinge angles a request may carry: closed (0) to beyond a right angle, with 0.1 rad of slack
below for a door resting on its stop (the footstep planner's passage angle tops at 2.0)."""


def normal_is_horizontal(normal: Sequence[float] | npt.NDArray[np.float64]) -> bool:
    """Whether a door normal (odom, z up) is horizontal enough for a door, a vertical plane:
    nonzero and |n_z| ≤ :data:`DOOR_NORMAL_MAX_UP` |n|. The FSM's estimates and the detector's
    frames are judged by it."""
    norm = math.sqrt(sum(float(v) * float(v) for v in normal))
    return norm > 0.0 and abs(float(normal[2])) <= DOOR_NORMAL_MAX_UP * norm


def door_estimate_problem(estimate: DoorEstimate) -> str | None:
    """Why a (finite, decoded) estimate cannot be planned with, or None.

    The normal must be a direction (|n| ≈ 1, to 10 %) and mostly horizontal (a door is a
    vertical plane: |n_z| ≤ :data:`DOOR_NORMAL_MAX_UP`); a zero normal made the optimiser's outcome NaN (issue #12).
    """
    norm = math.sqrt(sum(v * v for v in estimate.normal))
    if not 0.9 <= norm <= 1.1:
        return f"door normal {estimate.normal} is not a unit vector (|n| = {norm:.3g})"
    if not normal_is_horizontal(estimate.normal):
        return f"door normal {estimate.normal} is not horizontal: a door is a vertical plane"
    if not DOOR_WIDTH_RANGE.admits(estimate.width):
        return f"door width {estimate.width:g} m is outside {DOOR_WIDTH_RANGE.describe()}"
    if estimate.corners and (len(estimate.corners) != 4 or any(len(c) != 3 for c in estimate.corners)):
        return "door corners must be four (x, y, z) points"
    if not 0.0 <= estimate.confidence <= 1.0:
        return f"door confidence {estimate.confidence:g} is outside [0, 1]"
    return None


def requested_estimate_problem(estimate: DoorEstimate | None, door_stamp: float) -> str | None:
    """Why a planner cannot plan a request with the estimate it picked for ``door_stamp`` (s;
    < 0: the latest), or None: none has arrived, the one asked for was not received, or it is
    unusable (:func:`door_estimate_problem`)."""
    if estimate is None:
        return ("no door estimate yet" if door_stamp < 0 else
                f"door estimate of stamp {door_stamp:.3f} s was not received")
    return door_estimate_problem(estimate)


def door_angle_problem(angle: float) -> str | None:
    """Why a requested hinge angle is refused, or None (the optimiser spent 80 s on 1e6 rad)."""
    if DOOR_ANGLE_RANGE.admits(angle):
        return None
    return f"door_angle {angle:g} rad is outside {DOOR_ANGLE_RANGE.describe()}"


class DoorEstimateHistory:
    """The last ``size`` estimates by stamp; :meth:`pick` finds the approved one."""

    def __init__(self, size: int = 200) -> None:
        self._by_stamp: OrderedDict[float, DoorEstimate] = OrderedDict()
        self._size = size

    def add(self, estimate: DoorEstimate) -> None:
        self._by_stamp[estimate.stamp] = estimate
        while len(self._by_stamp) > self._size:
            self._by_stamp.popitem(last=False)

    @property
    def latest(self) -> DoorEstimate | None:
        return next(reversed(self._by_stamp.values()), None)

    def pick(self, stamp: float, carried: str = "") -> DoorEstimate | None:
        """The estimate a request names: the one it carries (JSON), else the one with
        ``stamp`` (within 1 µs), else — for ``stamp`` < 0 — the latest one."""
        if carried:
            return decode(DoorEstimate, carried)
        if stamp < 0:
            return self.latest
        return next((e for s, e in self._by_stamp.items() if abs(s - stamp) < 1e-6), None)
