"""Matching the camera's streams into frames by stamp, without ROS.

A frame is one message of each stream (colour, depth, CameraInfo, the camera's pose in
``odom``) whose stamps agree within ``tolerance`` (s). Incomplete frames wait; beyond
``max_pending`` the oldest are dropped, each with the streams it lacked, so the node can say
which stream never came (e.g. no CameraInfo).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from door_detection.errors import DetectionError

__all__ = ["STREAMS", "STREAM_NAMES", "DroppedFrame", "FrameSync"]

STREAMS = ("color", "depth", "info", "pose")
"""The streams of a frame, by the names :class:`FrameSync` keys them with."""
STREAM_NAMES = {"color": "colour image", "depth": "depth image", "info": "CameraInfo", "pose": "camera pose"}
"""What each stream is, for a log line."""


@dataclass(frozen=True)
class DroppedFrame:
    """An incomplete frame given up: its stamp (s) and the streams it lacked, in stream order."""

    stamp: float
    missing: tuple[str, ...]

    def describe(self) -> str:
        """``colour image, CameraInfo``: the missing streams for a log line."""
        return ", ".join(STREAM_NAMES.get(s, s) for s in self.missing)


@dataclass
class FrameSync:
    """Collects messages per stamp; :meth:`add` returns a frame once every stream has one."""

    tolerance: float
    streams: Sequence[str] = STREAMS
    max_pending: int = 20
    _pending: OrderedDict[float, dict[str, Any]] = field(default_factory=OrderedDict)

    def __post_init__(self) -> None:
        if not self.tolerance >= 0.0:
            raise DetectionError(f"sync tolerance must be ≥ 0 s, got {self.tolerance}")
        if self.max_pending < 1:
            raise DetectionError(f"max_pending must be ≥ 1, got {self.max_pending}")

    def add(self, stream: str, stamp: float, message: Any) -> tuple[tuple[float, dict[str, Any]] | None,
                                                                     list[DroppedFrame]]:
        """File ``message`` of ``stream`` under the pending frame within ``tolerance`` of
        ``stamp`` (or a new one). Returns the frame it completed, as (its stamp, {stream:
        message}), or None; and the frames dropped to keep at most ``max_pending`` waiting."""
        if stream not in self.streams:
            raise DetectionError(f"unknown stream {stream!r}; expected one of {', '.join(self.streams)}")
        key = next((k for k in self._pending if abs(k - stamp) <= self.tolerance), stamp)
        frame = self._pending.setdefault(key, {})
        frame[stream] = message
        complete = None
        if len(frame) == len(self.streams):
            del self._pending[key]
            complete = (key, frame)
        dropped = []
        while len(self._pending) > self.max_pending:
            old_stamp, parts = self._pending.popitem(last=False)
            dropped.append(DroppedFrame(old_stamp, tuple(s for s in self.streams if s not in parts)))
        return complete, dropped

    @property
    def pending(self) -> int:
        """How many incomplete frames wait."""
        return len(self._pending)
