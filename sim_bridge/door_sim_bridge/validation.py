"""Range checks of the sim bridge's validated options: the contract's one check
(:func:`door_contract.ranges.check_in_range`) over :class:`~door_contract.ranges.FieldRange`
tables, one error type.

A value outside its interval raises :class:`~door_sim_bridge.errors.SimulationError` naming
the option's owner, field, interval and unit, so a node can log it verbatim and refuse to
start.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

from door_contract.ranges import FieldRange, check_fields, check_in_range
from door_sim_bridge.errors import SimulationError

__all__ = ["FieldRange", "check_ranges", "require"]

def require(owner: str, name: str, value: object, allowed: FieldRange, integer: bool = False) -> None:
    """Raise :class:`SimulationError` naming ``<owner>.<name>`` unless ``value`` is a finite real
    number (an ``int`` when ``integer``) within ``allowed``."""
    check_in_range(f"{owner}.{name}", value, allowed, SimulationError, integer)


def check_ranges(owner: object, ranges: Mapping[str, FieldRange], integers: Collection[str] = ()) -> None:
    """:func:`require` for each field of ``owner`` named in ``ranges`` (those in ``integers`` as
    ``int``), labelled by the owner's type."""
    check_fields(owner, ranges, SimulationError, type(owner).__name__, integers)
