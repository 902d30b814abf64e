"""Door and handle proposals from a colour image alone (the 2-D stage of Sec. III-A).

Without depth there is no width or plane check; a pair of vertical lines is a door
*proposal* when its pixel geometry is door-like:

* the two lines are ≥ ``min_pair_separation`` px apart (the paper's 60 px) and overlap
  vertically (:func:`~door_detection.door_pairs.pair_lines`);
* height / width between ``MIN_ASPECT`` and ``MAX_ASPECT`` (a 2.08 × 0.91 m door is 2.3;
  perspective and cropping widen the range), at least ``MIN_WIDTH_FRACTION`` of the image
  wide.

Proposals are ranked by score = edge coverage (how much of the pair's height the two
lines cover) + uniformity (1 − σ_inside/σ_image, a door is one colour) + ``SIZE_WEIGHT``
× width fraction + ``HANDLE_BONUS`` if a handle blob is found
(:func:`~door_detection.handle.find_handle`), then thinned by non-maximum suppression.
Used on the real photographs by
:mod:`~door_evaluation.detection.evaluate_photos`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_detection.door_pairs import pair_lines
from door_detection.handle import find_handle
from door_detection.lines import VerticalLines, detect_vertical_lines
from door_detection.options import DetectionOptions

__all__ = ["Box", "DoorProposal", "iou", "non_maximum_suppression", "propose_doors"]

Box = tuple[float, float, float, float]
"""x0, y0, x1, y1 in pixels."""

MIN_ASPECT = 1.3
MAX_ASPECT = 4.5
MIN_WIDTH_FRACTION = 0.08
HANDLE_BONUS = 0.5
SIZE_WEIGHT = 2.0
"""Score per image width the door spans: a door within the robot's working range (≤ 4 m)
spans ≥ 13 % of a 80°-wide image, so wide pairs are favoured over panels and planks."""
NMS_IOU = 0.5
HANDLE_CHECKS = 3


@dataclass(frozen=True)
class DoorProposal:
    """A door hypothesis: its box, corner pixels (BL, BR, TR, TL), score and handle box."""

    box: Box
    corners: np.ndarray
    score: float
    handle_box: Box | None


def propose_doors(rgb: np.ndarray, options: DetectionOptions, max_proposals: int = 5) -> list[DoorProposal]:
    """The best ``max_proposals`` door proposals of an rgb8 image, best first.

    Pairs are first ranked without the handle term; only the best ``HANDLE_CHECKS`` ×
    ``max_proposals`` (after suppression) are searched for a handle, then re-ranked.
    """
    lines = detect_vertical_lines(rgb, options)
    height, width = rgb.shape[:2]
    spread = float(rgb.reshape(-1, 3)[:: max(rgb.size // 60000, 1)].std(axis=0).mean()) + 1e-6
    candidates = []
    for left, right in pair_lines(lines, options):
        proposal = _proposal(rgb, lines, int(left), int(right), spread)
        if proposal is not None and proposal.box[2] - proposal.box[0] >= MIN_WIDTH_FRACTION * width:
            candidates.append(proposal)
    shortlist = non_maximum_suppression(sorted(candidates, key=lambda p: -p.score),
                                        HANDLE_CHECKS * max_proposals)
    with_handles = [_with_handle(rgb, proposal, options) for proposal in shortlist]
    return non_maximum_suppression(sorted(with_handles, key=lambda p: -p.score), max_proposals)


def _proposal(rgb: np.ndarray, lines: VerticalLines, left: int, right: int,
              spread: float) -> DoorProposal | None:
    """A pair's box, corners and score without the handle term (None: not door-shaped)."""
    s = lines.segments
    top, bottom = max(s[left, 1], s[right, 1]), min(s[left, 3], s[right, 3])
    xs = lines.x_at(np.array([[bottom, top]] * len(lines)))
    corners = np.array([[xs[left, 0], bottom], [xs[right, 0], bottom], [xs[right, 1], top], [xs[left, 1], top]])
    box = (float(corners[:, 0].min()), float(top), float(corners[:, 0].max()), float(bottom))
    door_height, door_width = box[3] - box[1], box[2] - box[0]
    if door_width <= 0 or not MIN_ASPECT <= door_height / door_width <= MAX_ASPECT:
        return None
    coverage = 0.5 * ((s[left, 3] - s[left, 1]) + (s[right, 3] - s[right, 1])) / max(door_height, 1.0)
    inside = rgb[int(top):int(bottom):2, int(box[0]) + 1:int(box[2]):2]
    uniformity = 1.0 - float(inside.reshape(-1, 3).std(axis=0).mean()) / spread if inside.size else 0.0
    size = SIZE_WEIGHT * door_width / rgb.shape[1]
    return DoorProposal(box, corners, min(coverage, 1.0) + uniformity + size, None)


def _with_handle(rgb: np.ndarray, proposal: DoorProposal, options: DetectionOptions) -> DoorProposal:
    """The proposal with its handle box (if a blob is found) and the handle bonus."""
    blob = find_handle(rgb, proposal.corners, options)
    if blob is None:
        return proposal
    handle_box = (float(blob.cols.min()), float(blob.rows.min()), float(blob.cols.max() + 1),
                  float(blob.rows.max() + 1))
    return DoorProposal(proposal.box, proposal.corners, proposal.score + HANDLE_BONUS, handle_box)


def iou(a: Box, b: Box) -> float:
    """Intersection over union of two boxes."""
    ix = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = ix * iy
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0


def non_maximum_suppression(ranked: list[DoorProposal], keep: int) -> list[DoorProposal]:
    """Greedy NMS: drop proposals overlapping a better one by IoU > ``NMS_IOU``."""
    kept: list[DoorProposal] = []
    for proposal in ranked:
        if all(iou(proposal.box, other.box) <= NMS_IOU for other in kept):
            kept.append(proposal)
        if len(kept) == keep:
            break
    return kept
