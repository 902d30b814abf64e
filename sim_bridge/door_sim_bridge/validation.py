"""Range checks of the sim bridge's validated options: the contract's one check
(:func:`door_contract.ranges.check_in_range`), one error type.

A value outside its interval raises :class:`~door_sim_bridge.errors.SimulationError` naming
the option's owner, field, interval and unit, so a node can log it verbatim and refuse to
start.
"""

from __future__ import annotations

from door_contract.ranges import FieldRange, check_in_range
from door_sim_bridge.errors import SimulationError


def require(owner: str, name: str, value: object, low: float, high: float, unit: str = "") -> None:
    """Raise :class:`SimulationError` unless ``value`` is a finite real number in [low, high]."""
    check_in_range(f"{owner}.{name}", value, FieldRange(low, high, unit), SimulationError)


def check_ranges(owner: object, ranges: dict[str, tuple[float, float, str]]) -> None:
    """:func:`require` for each field of ``owner`` named in ``ranges`` (low, high, unit)."""
    name = type(owner).__name__
    for key, (low, high, unit) in ranges.items():
        require(name, key, getattr(owner, key), low, high, unit)
