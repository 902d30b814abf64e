"""Range checks for option dataclasses: raise :class:`TrajoptError` naming the field."""

from __future__ import annotations

import math

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
    below = value <= low if low_open else value < low
    above = value >= high if high_open else value > high
    if isinstance(value, bool) or not math.isfinite(value) or below or above:
        left = "(" if low_open else "["
        right = ")" if high_open else "]"
        raise TrajoptError(
            f"{owner}.{field_name} must be in {left}{low}, {high}{right}, got {value!r}"
        )


def require_int_at_least(owner: str, field_name: str, value: int, low: int) -> None:
    """Raise unless ``value`` is an ``int`` (not ``bool``) and ``>= low``."""
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise TrajoptError(f"{owner}.{field_name} must be an integer >= {low}, got {value!r}")
