"""Range checks that raise :class:`FootstepPlannerError` naming the field and its allowed range."""

from __future__ import annotations

import math

from door_contract.ranges import FieldRange
from footstep_planner.errors import FootstepPlannerError

__all__ = ["FieldRange", "check_range"]


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
