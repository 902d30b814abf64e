"""The allowed interval of one option or value, and the one check of it, shared by the
packages' validated options.

Each package raises its own error type when a value is outside (the rosbags layout: per-package
errors), through :func:`check_in_range`; the interval and its wording are the same everywhere:
``<owner>.<field> = <value> is outside the allowed range [low, high] <unit>``. A package states
its options' intervals once, as a table of :class:`FieldRange` by field name checked by
:func:`check_fields`; a node parameter configuring an option takes the option's interval.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass

__all__ = ["FieldRange", "check_fields", "check_in_range"]


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
        return f"{opening}{self.low:.10g}, {self.high:.10g}{closing} {self.unit}".rstrip()


def check_in_range(label: str, value: object, allowed: FieldRange, error: Callable[[str], Exception],
                   integer: bool = False) -> None:
    """Raise ``error(message)`` unless ``value`` is a finite real number (not a bool; an ``int``
    when ``integer``) within ``allowed``; ``label`` names it (``"MotionOptions.push_angle"``)."""
    kind = "an integer" if integer else "a number"
    if isinstance(value, bool) or not isinstance(value, int if integer else (int, float)):
        raise error(f"{label} must be {kind} in {allowed.describe()}, got {value!r}")
    if not math.isfinite(value) or not allowed.admits(value):
        raise error(f"{label} = {value!r} is outside the allowed range {allowed.describe()}")


def check_fields(owner: object, ranges: Mapping[str, FieldRange], error: Callable[[str], Exception],
                 label: str = "", integers: Collection[str] = ()) -> None:
    """:func:`check_in_range` for each attribute of ``owner`` named in ``ranges``, in order; the
    names in ``integers`` must be ``int``. Each is labelled ``<label>.<name>`` (``name`` alone
    without a label)."""
    for name, allowed in ranges.items():
        check_in_range(f"{label}.{name}" if label else name, getattr(owner, name), allowed, error,
                       integer=name in integers)
