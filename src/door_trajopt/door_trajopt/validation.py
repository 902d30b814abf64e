"""Range checks for option dataclasses: raise :class:`TrajoptError` naming the field (the
contract's one check, :func:`door_contract.ranges.check_in_range`)."""

from __future__ import annotations

import math

from door_contract.ranges import FieldRange, check_in_range
from door_trajopt.problem import TrajoptError


def require_in_range(
    owner: str,
    field_name: str,
    value: float,
    low: float,
    high: float,
    *,
    low_open: bool = False,
    high_open: bool = False,
) -> None:
    """Raise unless ``value`` lies in the interval (``open`` ends excluded)."""
    check_in_range(f"{owner}.{field_name}", value, FieldRange(low, high, "", low_open, high_open), TrajoptError)


def require_int_at_least(owner: str, field_name: str, value: int, low: int) -> None:
    """Raise unless ``value`` is an ``int`` (not ``bool``) and ``>= low``."""
    check_in_range(f"{owner}.{field_name}", value, FieldRange(low, math.inf, ""), TrajoptError, integer=True)
