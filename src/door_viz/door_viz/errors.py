"""Errors of the visualisation package.

:class:`DoorVizError` is the package's one base error; it is not a :class:`ValueError`, so a
bug's ``ValueError`` is never taken for a client's bad message.
"""

__all__ = ["DoorVizError"]


class DoorVizError(Exception):
    """Something the visualisation refuses; the message says what."""
