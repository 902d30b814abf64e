"""The allowed interval of one option or value, shared by the packages' validated options.

Each package raises its own error type when a value is outside (the rosbags layout: per-package
errors); the interval and its wording are the same everywhere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


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
