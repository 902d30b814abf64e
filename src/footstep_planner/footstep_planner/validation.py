"""Range checks that raise :class:`FootstepPlannerError` naming the field and its allowed range
(the contract's one check, :func:`door_contract.ranges.check_in_range`)."""

from __future__ import annotations

from door_contract.ranges import FieldRange, check_in_range
from footstep_planner.errors import FootstepPlannerError

__all__ = ["FieldRange", "check_range"]


def check_range(name: str, value: object, allowed: FieldRange, owner: str = "", integer: bool = False) -> None:
    """Raise unless ``value`` is a finite real number (not a bool; an ``int`` when ``integer``)
    within ``allowed``.

    ``owner`` prefixes the message ("door angle = ...").
    """
    check_in_range(f"{owner} {name}".strip(), value, allowed,
                   lambda message: FootstepPlannerError(message, field=name), integer)
