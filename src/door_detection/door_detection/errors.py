"""Errors of the door detector's ROS-free core.

``DetectionError`` is the package's one base error; its message names the offending field
(or input) and, for ranges, the allowed interval, so a node can log it verbatim. It is not a
:class:`ValueError`: bad input is :class:`InputError`, and any other ``DetectionError`` or
``ValueError`` raised inside the pipeline is a bug, reported as INTERNAL_ERROR.
"""

__all__ = ["DetectionError", "InputError"]


class DetectionError(Exception):
    """An option out of range, or a misuse of the detector; the message names the field."""


class InputError(DetectionError):
    """A frame the detector cannot use: empty image, size mismatch, no valid depth,
    intrinsics that disagree with the image, a scribble outside the image."""
