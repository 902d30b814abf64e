"""Errors of the door detector's ROS-free core.

``DetectionError`` is a :class:`ValueError` so callers that only know the standard
library still catch it; its message names the offending field (or input) and, for
ranges, the allowed interval, so a node can log it verbatim.
"""


class DetectionError(ValueError):
    """An option out of range, or a misuse of the detector; the message names the field."""


class InputError(DetectionError):
    """A frame the detector cannot use: empty image, size mismatch, no valid depth,
    intrinsics that disagree with the image, a scribble outside the image."""
