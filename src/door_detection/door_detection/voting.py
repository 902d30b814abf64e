"""The vote over frames, sequential ([Banerjee 2015] Sec. III-A, last paragraph, made faster).

The paper: "The entire algorithm is repeated over a window of 10 frames ... the detection
with the maximum occurrence is selected as the door"; waiting for 6 of 10 frames at the
graph's 2 Hz camera took 1.75 s while each frame's work is ~20 ms. Here the vote stops as
soon as the evidence suffices:

* :class:`Voter` keeps the last N (``vote_frames``) results; failed frames are votes for
  nothing and, unlike in the paper, do not count against a door (while the head searches,
  most views do not hold the door at all);
* two estimates *agree* when their handles are within ``vote_handle_distance``, their
  normals within ``vote_normal_angle_deg`` and their hinge sides equal; the largest group
  of mutually-agreeing-with-its-pivot estimates (the newest on ties) is the candidate;
* it is **confirmed** when (1) it has at least ``vote_min_agreeing`` estimates, (2) they are
  more than half of the window's estimates, and (3) its fused handle is precise enough: the
  95 % confidence half-width of the mean, t₀.₉₇₅(n − 1)·‖s‖/√n with s the per-axis sample
  standard deviations and t Student's quantile, at most ``vote_handle_confidence``, and
  likewise for the normals (their RMS angle to the mean, over √(n − 1)) at most
  ``vote_normal_confidence_deg``. Noise-free frames agree exactly and confirm at n = 2;
  stereo noise at 4 m (σ ≈ 8 cm per pixel) needs several more;
* the consensus is the mean of the group (outliers are already out of it: agreement is
  within 3 cm): handle, normal and up renormalised, corners and width (NaN-aware);
  confidence = |group| / N.

Estimates are compared in whatever frame they are given in. Frames from different head or
body views are voted on together once transformed to ``odom``
(:meth:`~door_detection.estimate.DetectedDoor.transformed`), which is how the views of the
active search (:mod:`~door_detection.view_search`) are fused.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np
from scipy.special import stdtrit

from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.options import DetectionOptions

__all__ = ["VoteResult", "Voter", "precision"]


@dataclass(frozen=True)
class VoteResult:
    """DETECTED with the consensus ``estimate``, VOTING (not confirmed yet) or NO_CONSENSUS (a
    full window without a confirmed door); ``agreeing`` of ``window`` frames; the 95 %
    ``confidence`` half-width of the candidate's handle (m; 0 for one estimate, inf for none)."""

    outcome: DetectionOutcome
    estimate: DetectedDoor | None
    agreeing: int
    window: int
    confidence: float = math.inf

    @property
    def ok(self) -> bool:
        return self.outcome is DetectionOutcome.DETECTED and self.estimate is not None


class Voter:
    """Sequential vote over the last ``vote_frames`` detections (see the module docstring)."""

    def __init__(self, options: DetectionOptions | None = None) -> None:
        self._options = options if options is not None else DetectionOptions()
        self._window: deque[DetectedDoor | None] = deque(maxlen=self._options.vote_frames)

    @property
    def size(self) -> int:
        """N, the window length."""
        return self._options.vote_frames

    def __len__(self) -> int:
        return len(self._window)

    def reset(self) -> None:
        """Forget every frame (e.g. after the operator's scribble replaced the automatic mode)."""
        self._window.clear()

    def add(self, detection: DetectedDoor | DetectionResult | None) -> VoteResult:
        """Record one frame's estimate (a failed result or None is a vote for nothing)
        and return the current decision."""
        estimate = detection.estimate if isinstance(detection, DetectionResult) else detection
        self._window.append(estimate)
        return self.decide()

    def decide(self) -> VoteResult:
        """The decision on the current window (see the module docstring)."""
        estimates = [e for e in self._window if e is not None]
        best: list[DetectedDoor] = []
        for pivot in reversed(estimates):
            group = [e for e in estimates if self._agree(pivot, e)]
            if len(group) > len(best):
                best = group
        error, spread = precision(best)
        options = self._options
        if (len(best) >= options.vote_min_agreeing and 2 * len(best) > len(estimates)
                and error <= options.vote_handle_confidence
                and spread <= options.vote_normal_confidence_deg):
            return VoteResult(DetectionOutcome.DETECTED, self._consensus(best), len(best), len(self._window), error)
        outcome = DetectionOutcome.VOTING if len(self._window) < self.size else DetectionOutcome.NO_CONSENSUS
        return VoteResult(outcome, None, len(best), len(self._window), error)

    def _agree(self, a: DetectedDoor, b: DetectedDoor) -> bool:
        distance = float(np.linalg.norm(a.handle_position - b.handle_position))
        angle = math.degrees(math.acos(float(np.clip(a.normal @ b.normal, -1.0, 1.0))))
        return (distance <= self._options.vote_handle_distance and
                angle <= self._options.vote_normal_angle_deg and a.hinge_side is b.hinge_side)

    def _consensus(self, group: list[DetectedDoor]) -> DetectedDoor:
        """Mean of the agreeing estimates; confidence = |group| / N."""
        def mean(name: str) -> np.ndarray:
            average: np.ndarray = np.mean(np.stack([getattr(e, name) for e in group]), axis=0)
            return average

        def unit(vector: np.ndarray) -> np.ndarray:
            direction: np.ndarray = vector / np.linalg.norm(vector)
            return direction

        with np.errstate(all="ignore"):
            corners = np.nanmean(np.stack([e.corners for e in group]), axis=0) \
                if any(np.isfinite(e.corners).all() for e in group) else group[-1].corners
            width = float(np.nanmean([e.width for e in group])) \
                if any(math.isfinite(e.width) for e in group) else float("nan")
        newest = group[-1]
        return DetectedDoor(mean("handle_position"), unit(mean("normal")), newest.hinge_side, width,
                            corners, len(group) / self.size, newest.mode, len(group), unit(mean("up")))


def precision(group: list[DetectedDoor]) -> tuple[float, float]:
    """95 % confidence half-widths of a group's mean handle (m) and mean normal (deg).

    Handle: t·‖s‖/√n, s the per-axis sample standard deviations (n − 1). Normal: t × the RMS
    angle of the normals to their mean direction, over √(n − 1) (the same estimator on the
    sphere). t = t₀.₉₇₅(n − 1), Student's quantile. A lone estimate has no spread to measure
    (0, 0: whether one frame may confirm is ``vote_min_agreeing``'s to say); none, (inf, inf).
    """
    n = len(group)
    if n < 2:
        return (0.0, 0.0) if n == 1 else (math.inf, math.inf)
    handles = np.stack([e.handle_position for e in group])
    t = float(stdtrit(n - 1, 0.975))
    handle_error = t * float(np.linalg.norm(handles.std(axis=0, ddof=1)) / math.sqrt(n))
    normals = np.stack([e.normal for e in group])
    mean = normals.mean(axis=0)
    mean /= np.linalg.norm(mean)
    angles = np.degrees(np.arccos(np.clip(normals @ mean, -1.0, 1.0)))
    return handle_error, t * float(math.sqrt(float(np.mean(angles ** 2)) / (n - 1)))
