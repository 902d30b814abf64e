"""The vote over frames (seed 001 Sec. III-A, last paragraph).

"The entire algorithm is repeated over a window of 10 frames. Detections from every frame
is recorded. At the end of ten iterations, the detection with the maximum occurrence is
selected as the door."

:class:`Voter` keeps the last N results (failed frames count as votes for nothing).
Two estimates *agree* when their handles are within ``vote_handle_distance``, their
normals within ``vote_normal_angle_deg`` and their hinge sides equal.  The estimate with
the most agreeing ones (itself included; the newest on ties) is the "maximum
occurrence"; when at least ⌊N/2⌋ + 1 agree, the consensus is published at once (no
need to wait for the N-th frame): the component-wise median of the agreeing estimates
(the normal and up renormalised), confidence = agreeing / N.

Estimates are compared in whatever frame they are given in: vote on optical-frame
estimates only while the head is still, otherwise transform them to ``odom`` first
(:meth:`~door_detection.estimate.DoorEstimate.transformed`).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from door_detection.estimate import DetectionOutcome, DetectionResult, DoorEstimate
from door_detection.options import DetectionOptions


@dataclass(frozen=True)
class VoteResult:
    """DETECTED with the consensus ``estimate``, VOTING (too few frames yet) or
    NO_CONSENSUS (a full window without a majority); ``agreeing`` of ``window`` frames."""

    outcome: DetectionOutcome
    estimate: DoorEstimate | None
    agreeing: int
    window: int

    @property
    def ok(self) -> bool:
        return self.outcome is DetectionOutcome.DETECTED and self.estimate is not None


class Voter:
    """Majority vote over the last ``vote_frames`` detections."""

    def __init__(self, options: DetectionOptions | None = None) -> None:
        self._options = options if options is not None else DetectionOptions()
        self._window: deque[DoorEstimate | None] = deque(maxlen=self._options.vote_frames)

    @property
    def size(self) -> int:
        """N, the window length."""
        return self._options.vote_frames

    def __len__(self) -> int:
        return len(self._window)

    def reset(self) -> None:
        """Forget every frame (e.g. after the robot moved, for optical-frame votes)."""
        self._window.clear()

    def add(self, detection: DoorEstimate | DetectionResult | None) -> VoteResult:
        """Record one frame's estimate (a failed result or None is a vote for nothing)
        and return the current decision."""
        estimate = detection.estimate if isinstance(detection, DetectionResult) else detection
        self._window.append(estimate)
        return self.decide()

    def decide(self) -> VoteResult:
        """The decision on the current window (see the module docstring)."""
        estimates = [e for e in self._window if e is not None]
        best: list[DoorEstimate] = []
        for pivot in reversed(estimates):
            group = [e for e in estimates if self._agree(pivot, e)]
            if len(group) > len(best):
                best = group
        if len(best) >= self._options.vote_majority:
            return VoteResult(DetectionOutcome.DETECTED, self._consensus(best), len(best), len(self._window))
        outcome = DetectionOutcome.VOTING if len(self._window) < self.size else DetectionOutcome.NO_CONSENSUS
        return VoteResult(outcome, None, len(best), len(self._window))

    def _agree(self, a: DoorEstimate, b: DoorEstimate) -> bool:
        distance = float(np.linalg.norm(a.handle_position - b.handle_position))
        angle = math.degrees(math.acos(float(np.clip(a.normal @ b.normal, -1.0, 1.0))))
        return (distance <= self._options.vote_handle_distance and
                angle <= self._options.vote_normal_angle_deg and a.hinge_side is b.hinge_side)

    def _consensus(self, group: list[DoorEstimate]) -> DoorEstimate:
        """Component-wise median of the agreeing estimates; confidence = |group| / N."""
        def median(name: str) -> np.ndarray:
            return np.median(np.stack([getattr(e, name) for e in group]), axis=0)

        def unit(vector: np.ndarray) -> np.ndarray:
            return vector / np.linalg.norm(vector)

        with np.errstate(all="ignore"):
            corners = np.nanmedian(np.stack([e.corners for e in group]), axis=0) \
                if any(np.isfinite(e.corners).all() for e in group) else group[-1].corners
            width = float(np.nanmedian([e.width for e in group])) \
                if any(math.isfinite(e.width) for e in group) else float("nan")
        newest = group[-1]
        return DoorEstimate(median("handle_position"), unit(median("normal")), newest.hinge_side, width,
                            corners, len(group) / self.size, newest.mode, len(group), unit(median("up")))
