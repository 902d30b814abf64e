"""Range checks for option dataclasses: raise :class:`TrajoptError` naming the field (the
contract's one check, :func:`door_contract.ranges.check_in_range`, over the options'
:class:`~door_contract.ranges.FieldRange` tables)."""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping

from door_contract.ranges import FieldRange, check_fields
from door_trajopt.problem import TrajoptError

__all__ = ["FieldRange", "at_least", "check_ranges"]


def at_least(low: int) -> FieldRange:
    """The range of a count of at least ``low`` (no upper bound)."""
    return FieldRange(low, math.inf, "")


def check_ranges(owner: object, ranges: Mapping[str, FieldRange], integers: Collection[str] = ()) -> None:
    """Raise :class:`TrajoptError` naming ``<type>.<field>`` unless every field of ``owner`` named
    in ``ranges`` lies in its range (those in ``integers`` as ``int``)."""
    check_fields(owner, ranges, TrajoptError, type(owner).__name__, integers)
