"""Near-vertical image lines: probabilistic Hough, tilt filter, merging (Sec. III-A).

A line is stored as its two end points in full-resolution pixels, top end first:
``(x_top, y_top, x_bottom, y_bottom)`` with ``y_top < y_bottom``.  Being near-vertical,
it is parametrised by the row: x(y) = x_top + s·(y − y_top), s = Δx/Δy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from door_detection.options import DetectionOptions
from door_detection.preprocessing import edge_image

__all__ = ["VerticalLines", "detect_vertical_lines", "merge_collinear"]


@dataclass(frozen=True)
class VerticalLines:
    """n near-vertical segments, ``segments`` (n, 4) = x_top, y_top, x_bottom, y_bottom (px)."""

    segments: np.ndarray

    def __len__(self) -> int:
        return int(self.segments.shape[0])

    @property
    def slopes(self) -> np.ndarray:
        """dx/dy of every line (n,)."""
        s = self.segments
        slopes: np.ndarray = (s[:, 2] - s[:, 0]) / np.maximum(s[:, 3] - s[:, 1], 1e-9)
        return slopes

    @property
    def lengths(self) -> np.ndarray:
        s = self.segments
        lengths: np.ndarray = np.hypot(s[:, 2] - s[:, 0], s[:, 3] - s[:, 1])
        return lengths

    def x_at(self, rows: np.ndarray) -> np.ndarray:
        """x of every line at ``rows``; rows broadcast against (n,) (e.g. (n, k))."""
        s = self.segments
        rows = np.asarray(rows, dtype=float)
        extra = (slice(None),) + (None,) * max(rows.ndim - 1, 0)
        xs: np.ndarray = s[:, 0][extra] + self.slopes[extra] * (rows - s[:, 1][extra])
        return xs


def detect_vertical_lines(rgb: np.ndarray, options: DetectionOptions) -> VerticalLines:
    """Hough segments of the edge image of ``rgb`` (H×W×3 uint8), kept when
    near-vertical, merged, and long enough.

    Hough runs on the image scaled by ``line_scale``; it is asked for segments of half
    the minimum length so that fragments of one edge (broken by texture or the handle's
    shadow) can be merged before the length test of Sec. III-A is applied.  The edges
    are first widened to 3 px horizontally: a slightly tilted edge is a staircase whose
    1-px steps would otherwise break the Hough segment every few tens of pixels.
    """
    edges = cv2.dilate(edge_image(rgb, options), np.ones((1, 3), np.uint8))
    scale = options.line_scale
    raw = cv2.HoughLinesP(edges, options.hough_rho, math.radians(options.hough_theta_deg),
                          options.hough_threshold, minLineLength=0.5 * options.min_line_length * scale,
                          maxLineGap=options.hough_max_gap * scale)
    if raw is None:
        return VerticalLines(np.zeros((0, 4)))
    segments = _top_first((raw.reshape(-1, 4).astype(float) + 0.5) / scale - 0.5)
    segments = segments[_is_near_vertical(segments, options.max_line_tilt_deg)]
    merged = merge_collinear(VerticalLines(segments), options)
    keep = merged.lengths >= options.min_line_length
    kept = merged.segments[keep]
    order = np.argsort(-np.hypot(kept[:, 2] - kept[:, 0], kept[:, 3] - kept[:, 1]))
    return VerticalLines(kept[order[: options.max_lines]])


def _top_first(segments: np.ndarray) -> np.ndarray:
    flip = segments[:, 1] > segments[:, 3]
    out = segments.copy()
    out[flip] = segments[flip][:, [2, 3, 0, 1]]
    return out


def _is_near_vertical(segments: np.ndarray, max_tilt_deg: float) -> np.ndarray:
    dx = np.abs(segments[:, 2] - segments[:, 0])
    dy = segments[:, 3] - segments[:, 1]
    upright: np.ndarray = dx <= math.tan(math.radians(max_tilt_deg)) * dy
    return upright


def merge_collinear(lines: VerticalLines, options: DetectionOptions) -> VerticalLines:
    """Merge fragments of one edge.

    Segments i and j belong together when both end points of the shorter one lie within
    ``line_merge_distance`` px (horizontally) of the longer one's extension (the longer
    segment's slope is the better estimate) and the rows between them are no more than
    ``min_line_length`` px: a short fragment's slope, extended far, would otherwise
    bridge a door's edge and its frame's outer edge ~10 px beside it.  Groups are the connected components of
    that relation; each group becomes the least-squares line x = a·y + b through its
    members' end points (weighted by member length), spanning the group's rows.
    """
    n = len(lines)
    if n < 2:
        return lines
    seg, lengths = lines.segments, lines.lengths
    x_at_tops = lines.x_at(np.broadcast_to(seg[:, 1], (n, n)))      # [i, j] = x_i(top_j)
    x_at_bottoms = lines.x_at(np.broadcast_to(seg[:, 3], (n, n)))
    gap = np.maximum(seg[:, 1][:, None], seg[:, 1][None, :]) - np.minimum(seg[:, 3][:, None], seg[:, 3][None, :])
    near = (np.abs(x_at_tops - seg[:, 0][None, :]) <= options.line_merge_distance) & \
           (np.abs(x_at_bottoms - seg[:, 2][None, :]) <= options.line_merge_distance) & \
           (gap <= options.min_line_length)
    i_longer = lengths[:, None] >= lengths[None, :]
    adjacency = np.where(i_longer, near, near.T)
    count, labels = connected_components(csr_matrix(adjacency), directed=False)
    if count == n:
        return lines
    return VerticalLines(np.array([_fit_group(seg[labels == k], lengths[labels == k])
                                   for k in range(count)]))


def _fit_group(members: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    if len(members) == 1:
        line: np.ndarray = members[0]
        return line
    ys = np.concatenate([members[:, 1], members[:, 3]])
    xs = np.concatenate([members[:, 0], members[:, 2]])
    w = np.concatenate([lengths, lengths])
    a, b = np.polyfit(ys, xs, 1, w=np.sqrt(w))
    top, bottom = float(ys.min()), float(ys.max())
    return np.array([a * top + b, top, a * bottom + b, bottom])
