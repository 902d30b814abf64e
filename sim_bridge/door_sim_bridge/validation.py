"""Range checks of the sim bridge's validated options: one idiom, one error type.

A value outside its interval raises :class:`~door_sim_bridge.errors.SimulationError` naming
the option's owner, field, interval and unit, so a node can log it verbatim and refuse to
start.
"""

from __future__ import annotations

import math

from door_sim_bridge.errors import SimulationError


def require(owner: str, name: str, value: object, low: float, high: float, unit: str = "") -> None:
    """Raise :class:`SimulationError` unless ``value`` is a finite real number in [low, high]."""
    suffix = f" {unit}" if unit else ""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SimulationError(f"{owner}.{name} must be a number in [{low:.10g}, {high:.10g}]{suffix}, "
                              f"got {value!r}")
    if not math.isfinite(value) or not low <= value <= high:
        raise SimulationError(f"{owner}.{name} = {value!r} is outside the allowed range "
                              f"[{low:.10g}, {high:.10g}]{suffix}")


def check_ranges(owner: object, ranges: dict[str, tuple[float, float, str]]) -> None:
    name = type(owner).__name__
    for key, (low, high, unit) in ranges.items():
        require(name, key, getattr(owner, key), low, high, unit)
