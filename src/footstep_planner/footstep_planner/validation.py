"""Range checks that raise :class:`FootstepPlannerError` naming the field and its allowed range."""

from __future__ import annotations

import math
from dataclasses import dataclass

from footstep_planner.errors import FootstepPlannerError


@dataclass(frozen=True)
class FieldRange:
    """The allowed interval of one value: [low, high], ends open when flagged."""

    low: float
    high: float
    unit: str
    low_open: bool = False
    high_open: bool = False

    def admits(self, value: float) -> bool:
        """True when ``value`` lies in the interval."""
        above = value > self.low if self.low_open else value >= self.low
        below = value < self.high if self.high_open else value <= self.high
        return above and below

    def describe(self) -> str:
        """The interval in words, e.g. ``(0, 1] m``."""
        if math.isinf(self.low) and math.isinf(self.high):
            return f"any finite value {self.unit}".rstrip()
        opening = "(" if self.low_open else "["
        closing = ")" if self.high_open else "]"
        return f"{opening}{self.low:g}, {self.high:g}{closing} {self.unit}".rstrip()


def check_range(name: str, value: object, allowed: FieldRange, owner: str = "") -> None:
    """Raise unless ``value`` is a finite real number (not a bool) within ``allowed``.

    ``owner`` prefixes the message ("door angle = ...").
    """
    label = f"{owner} {name}".strip()
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise FootstepPlannerError(
            f"{label} must be a number in {allowed.describe()}, got {value!r}", field=name)
    if not math.isfinite(value) or not allowed.admits(value):
        raise FootstepPlannerError(
            f"{label} = {value!r} is outside the allowed range {allowed.describe()}", field=name)
