"""Automatic door and handle detection ([Banerjee 2015] Sec. III-A).

Pipeline, one frame:

1. check the inputs (:mod:`~door_detection.preprocessing`);
2. scale → histogram equalisation (luma) → bilateral filter → Canny → probabilistic
   Hough; near-vertical lines longer than a threshold (:mod:`~door_detection.lines`);
3. pairs ≥ 60 px apart; RANSAC 3-D line per edge from the registered depth; width
   80–100 cm; duplicates merged; the plane between the edges validated on the two
   diagonals; normal = (line joining the edges) × (edge) (:mod:`~door_detection.door_pairs`);
4. handle by colour statistics on the handle side (:mod:`~door_detection.handle`), on
   the best candidates in turn until one has a handle (on the rows both edges span, then,
   when one edge's line is shorter — a faint edge — on the rows either spans) that does not
   touch the image border (a lever cut by it would be measured short: 2.8 cm off);
5. the plane refined by robust least squares in inverse-depth space over ~3000 points of
   the door's surface (beyond the paper: the cross-product normal only seeds it; under
   stereo noise the fit is ~10× more precise, see :func:`~door_detection.plane.refine_plane`);
   the grasp point (:mod:`~door_detection.grasp`) and the corners (the image corners' rays
   cut with the plane) lie on that plane; the door's "up" is its 3-D edges' direction.

Never raises on bad frames: every failure is a :class:`DetectionResult` whose outcome
names the stage and whose reason says why.

The vote over frames is :class:`~door_detection.voting.Voter`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cv2
import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.vocabulary import DetectionMode, Side
from door_detection.door_pairs import DoorCandidate, corners_3d, door_surface_points, find_doors
from door_detection.edges import edge_width, refine_door_edges
from door_detection.errors import DetectionError, InputError
from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.grasp import locate_grasp
from door_detection.handle import HandleBlob, find_handle, touches_border
from door_detection.jambs import trim_jambs
from door_detection.lines import VerticalLines, detect_vertical_lines
from door_detection.options import DetectionOptions
from door_detection.plane import refine_plane
from door_detection.preprocessing import DepthError, RgbdFrame, validate_frame

__all__ = ["UNEXPECTED_ERRORS", "StageClock", "StageFailure", "detect_automatic"]

UNEXPECTED_ERRORS = (DetectionError, ArithmeticError, IndexError, ValueError, np.linalg.LinAlgError, cv2.error)
"""Failures inside the pipeline that no input check foresaw: reported (INTERNAL_ERROR), never
raised. Caught after :class:`InputError` (bad input); a :class:`DetectionError` that gets this
far (e.g. a non-finite estimate built from a valid frame) is a bug of the pipeline."""


class StageFailure(Exception):
    """A pipeline stage found nothing; carries the outcome and a reason for the caller."""

    def __init__(self, outcome: DetectionOutcome, reason: str, candidates: int = 0) -> None:
        super().__init__(reason)
        self.outcome = outcome
        self.reason = reason
        self.candidates = candidates


@dataclass(frozen=True)
class _Found:
    candidate: DoorCandidate
    blob: HandleBlob
    lines: VerticalLines
    candidates: int


class StageClock:
    """Wall time of named stages (diagnostics and the benchmark)."""

    def __init__(self) -> None:
        self._start = time.perf_counter()
        self._last = self._start
        self._stages: list[tuple[str, float]] = []

    def mark(self, name: str) -> None:
        now = time.perf_counter()
        self._stages.append((name, now - self._last))
        self._last = now

    @property
    def stages(self) -> tuple[tuple[str, float], ...]:
        return tuple(self._stages)

    @property
    def elapsed(self) -> float:
        return time.perf_counter() - self._start


def detect_automatic(rgb: np.ndarray, depth: np.ndarray, intrinsics: CameraIntrinsics,
                     options: DetectionOptions | None = None,
                     hinge_side: Side | None = None) -> DetectionResult:
    """Detect the door and its handle in one RGB-D frame; never raises on bad frames.

    ``rgb``: H×W×3 uint8; ``depth``: H×W float metres registered to ``rgb`` (NaN, ≤ 0 or
    out of range = invalid); ``intrinsics`` of that image; ``hinge_side``: optional prior
    knowledge of the hinge side (image left/right).  Returns a :class:`DetectionResult`
    whose ``estimate`` is set when ``outcome`` is DETECTED.
    """
    opts = options if options is not None else DetectionOptions()
    clock = StageClock()
    try:
        frame = validate_frame(rgb, depth, intrinsics, opts)
        clock.mark("validate")
        estimate, candidates = _detect(frame, opts, hinge_side, clock)
    except DepthError as error:
        return DetectionResult(DetectionOutcome.NO_VALID_DEPTH, None, str(error), clock.elapsed)
    except InputError as error:
        return DetectionResult(DetectionOutcome.BAD_INPUT, None, str(error), clock.elapsed)
    except StageFailure as failure:
        return DetectionResult(failure.outcome, None, failure.reason, clock.elapsed,
                               failure.candidates, clock.stages)
    except UNEXPECTED_ERRORS as error:  # a bug must not take the node down (DESIGN.md)
        return DetectionResult(DetectionOutcome.INTERNAL_ERROR, None,
                               f"{type(error).__name__}: {error}", clock.elapsed)
    return DetectionResult(DetectionOutcome.DETECTED, estimate, "", clock.elapsed, candidates,
                           clock.stages)


def _detect(frame: RgbdFrame, options: DetectionOptions, hinge_side: Side | None,
            clock: StageClock) -> tuple[DetectedDoor, int]:
    found = _find_door_and_handle(frame, options, hinge_side, clock)
    candidate = found.candidate
    lines = refine_door_edges(frame.rgb, found.lines, candidate.left, candidate.right)
    surface = door_surface_points(candidate, lines, frame.depth, frame.intrinsics, options)
    plane, fraction = refine_plane(surface, candidate.plane, options.plane_inlier_distance) \
        if len(surface) >= options.min_region_points else (candidate.plane, candidate.plane_fraction)
    plane = plane.facing(np.zeros(3))
    lines = trim_jambs(lines, candidate, plane, frame.depth, frame.intrinsics, options.frame_width_max)
    up = _door_up(candidate)
    hinge = found.blob.side.other
    handle = locate_grasp(found.blob.cols, found.blob.rows, frame.depth, frame.intrinsics, plane, up,
                          hinge, options)
    if handle is None:
        raise StageFailure(DetectionOutcome.NO_HANDLE, "the handle's rays miss the door plane",
                           found.candidates)
    corners = corners_3d(candidate, lines, plane, frame.intrinsics)
    clock.mark("plane+grasp")
    confidence = float(np.clip(min(candidate.plane_fraction, fraction), 0.0, 1.0))
    estimate = DetectedDoor(handle, plane.normal, hinge, edge_width(corners), corners, confidence,
                            DetectionMode.AUTOMATIC, 1, up)
    return estimate, found.candidates


def _door_up(candidate: DoorCandidate) -> np.ndarray:
    """The door's vertical: the mean 3-D edge direction, oriented towards image up (−y)."""
    left, right = candidate.left_edge.direction, candidate.right_edge.direction
    mean = left + (right if float(left @ right) >= 0 else -right)
    normal: np.ndarray = -mean / np.linalg.norm(mean) if mean[1] > 0 else mean / np.linalg.norm(mean)
    return normal


def _find_door_and_handle(frame: RgbdFrame, options: DetectionOptions, hinge_side: Side | None,
                          clock: StageClock) -> _Found:
    """Lines → door candidates → the first (best-scored) candidate with a handle."""
    lines = detect_vertical_lines(frame.rgb, options)
    clock.mark("lines")
    if len(lines) < 2:
        raise StageFailure(DetectionOutcome.NO_VERTICAL_LINES,
                           f"found {len(lines)} vertical line(s) longer than {options.min_line_length:g} px")
    doors, sized = find_doors(lines, frame.depth, frame.intrinsics, options)
    clock.mark("pairs")
    if sized == 0:
        raise StageFailure(DetectionOutcome.NO_DOOR_PAIR,
                           f"no pair of {len(lines)} vertical lines is {options.door_width_min:g}–"
                           f"{options.door_width_max:g} m apart in 3-D")
    if not doors:
        raise StageFailure(DetectionOutcome.NO_DOOR_PLANE,
                           f"{sized} door-width pair(s) but none holds a plane between its edges", sized)
    cut = False
    for candidate in doors[: options.max_candidates]:
        ratio = float(candidate.left_edge.point[2] / candidate.right_edge.point[2])
        for outer in (False, True) if candidate.partly_seen else (False,):
            blob = find_handle(frame.rgb, candidate.image_corners(lines, outer), options, hinge_side, ratio)
            if blob is not None and touches_border(blob, frame.rgb.shape):
                cut = True                   # a lever cut by the border would be measured short
            elif blob is not None:
                clock.mark("handle")
                return _Found(candidate, blob, lines, len(doors))
    clock.mark("handle")
    raise StageFailure(DetectionOutcome.NO_HANDLE,
                       f"{len(doors)} door(s) found but " + ("the handle is cut by the image border" if cut else
                       f"no handle blob on the {'handle' if hinge_side else 'left or right'} side"), len(doors))
