"""Errors of the door task's supervisor.

:class:`DoorFsmError` is the package's one base error; it is not a :class:`ValueError`, so a
bug's ``ValueError`` is never taken for an operator's unknown command or a bad option.
"""

__all__ = ["DoorFsmError"]


class DoorFsmError(Exception):
    """Something the supervisor refuses (its wiring, its options, an operator's text)."""
