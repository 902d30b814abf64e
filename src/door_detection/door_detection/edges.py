"""Sub-pixel door edges from the colour profile across each edge (beyond the paper).

The Hough line of a door edge lies on a Canny edge pixel, and the strongest colour step near
a leaf is often the frame's inner edge, not the leaf's: the DRC-size leaf sits in its
opening with a 4 mm gap, which a 640-px camera sees as one mixed pixel. Measured on the sim
door, the lines lay 0.4–1.7 px outside the leaf, so the leaf came out 3–11 mm wide at
1.5–3.5 m. The door motions turn about the hinge edge, so the leaf's own edge is wanted.

For each sampled row along an edge, the profile d(u) = ‖rgb(u) − c_leaf‖ runs from inside
the leaf (c_leaf: the median colour a few pixels inside, that row) outwards across the line.
With D the largest contrast on the outer side, the leaf ends where d first exceeds D/2; the
crossing is interpolated linearly between the two pixels around it (for an unblurred
renderer, which samples each pixel at one point, that is the midpoint between the last leaf
sample and the first other one, unbiased; for a blurred camera, the half-contrast point).
Rows with too little contrast (a white leaf in a white frame) are skipped. The edge is the
least-squares line x = a·y + b through the rows' crossings after dropping those more than
``EDGE_FIT_RESIDUAL`` px off a first fit; too few good rows keep the Hough line.

:func:`edge_width` is the door's width between two edges cut with its plane.
"""

from __future__ import annotations

import numpy as np

from door_detection.lines import VerticalLines

__all__ = ["edge_width", "refine_door_edges", "refine_edge"]

PROFILE_INSIDE = 4
"""Pixels of the profile on the leaf side of the Hough line."""
PROFILE_OUTSIDE = 4
"""Pixels of the profile on the outer side of the Hough line."""
REFERENCE_PIXELS = (6, 7, 8)
"""Offsets inside the line whose median colour is the leaf's, per row."""
MIN_CONTRAST = 12.0
"""Smallest outer contrast D (RGB distance, 0..441) for a row to locate the edge."""
MAX_ROWS = 120
"""Rows sampled per edge."""
MIN_ROW_FRACTION = 0.3
"""Fraction of the sampled rows that must locate the edge for the refined line to be used."""
EDGE_FIT_RESIDUAL = 1.0
"""Rows farther than this from the first fit (px) are dropped before the final fit."""


def refine_door_edges(rgb: np.ndarray, lines: VerticalLines, left: int, right: int) -> VerticalLines:
    """``lines`` with lines ``left`` (a door's left edge, leaf to its right) and ``right`` (leaf
    to its left) moved onto the leaf's sub-pixel edges; other lines are unchanged."""
    segments = lines.segments.copy()
    for index, inside in ((left, 1), (right, -1)):
        refined = refine_edge(rgb, lines, index, inside)
        if refined is not None:
            segments[index] = refined
    return VerticalLines(segments)


def refine_edge(rgb: np.ndarray, lines: VerticalLines, index: int, inside: int) -> np.ndarray | None:
    """The segment (x_top, y_top, x_bottom, y_bottom) of line ``index`` moved onto the leaf
    edge whose leaf lies on side ``inside`` (+1: right, −1: left), or None when too few rows
    show the edge."""
    x_top, y_top, _, y_bottom = lines.segments[index]
    count = int(min(MAX_ROWS, max(y_bottom - y_top, 2)))
    rows = np.rint(np.linspace(y_top, y_bottom, count)).astype(np.intp)
    rows = rows[(rows >= 0) & (rows < rgb.shape[0])]
    if rows.size < 2:
        return None
    centre = lines.x_at(np.tile(rows.astype(float), (len(lines), 1)))[index]
    crossings = _crossings(rgb, rows, np.rint(centre).astype(np.intp), inside)
    good = np.isfinite(crossings)
    if good.sum() < max(MIN_ROW_FRACTION * rows.size, 2):
        return None
    slope, offset = _robust_line(rows[good].astype(float), crossings[good])
    return np.array([slope * y_top + offset, y_top, slope * y_bottom + offset, y_bottom])


def _crossings(rgb: np.ndarray, rows: np.ndarray, centres: np.ndarray, inside: int) -> np.ndarray:
    """Per row, the image x where the colour leaves the leaf's (NaN: no clear edge)."""
    offsets = np.arange(PROFILE_INSIDE, -PROFILE_OUTSIDE - 1, -1)          # inside → outside
    columns = centres[:, None] + inside * offsets[None, :]
    reference_columns = centres[:, None] + inside * np.array(REFERENCE_PIXELS)[None, :]
    width = rgb.shape[1]
    valid = (columns.min(axis=1) >= 0) & (columns.max(axis=1) < width) & \
        (reference_columns.min(axis=1) >= 0) & (reference_columns.max(axis=1) < width)
    result = np.full(rows.size, np.nan)
    if not valid.any():
        return result
    rows, columns, reference_columns = rows[valid], columns[valid], reference_columns[valid]
    profile = rgb[rows[:, None], columns].astype(np.float32)                # (n, k, 3)
    leaf = np.median(rgb[rows[:, None], reference_columns].astype(np.float32), axis=1)
    distance = np.linalg.norm(profile - leaf[:, None, :], axis=2)          # (n, k)
    contrast = distance[:, PROFILE_INSIDE + 1:].max(axis=1)
    threshold = 0.5 * contrast
    beyond = distance > threshold[:, None]
    first = np.argmax(beyond, axis=1)
    ok = (contrast >= MIN_CONTRAST) & beyond.any(axis=1) & (first > 0)
    k = np.clip(first, 1, offsets.size - 1)
    n = np.arange(rows.size)
    before, after = distance[n, k - 1], distance[n, k]
    fraction = np.clip((threshold - before) / np.maximum(after - before, 1e-6), 0.0, 1.0)
    position = offsets[k - 1] - fraction                                     # offset from the centre
    result[np.flatnonzero(valid)[ok]] = (columns[:, PROFILE_INSIDE] + inside * position)[ok]
    return result


def _robust_line(rows: np.ndarray, xs: np.ndarray) -> tuple[float, float]:
    """Least-squares x = a·y + b, refitted without rows off the first fit by more than
    ``EDGE_FIT_RESIDUAL`` px (when enough remain)."""
    slope, offset = np.polyfit(rows, xs, 1)
    keep = np.abs(xs - (slope * rows + offset)) <= EDGE_FIT_RESIDUAL
    if keep.sum() >= max(2, rows.size // 2):
        slope, offset = np.polyfit(rows[keep], xs[keep], 1)
    return float(slope), float(offset)


def edge_width(corners: np.ndarray) -> float:
    """Door width (m): the distance between the door's two edges, the lines through the corners
    bottom-left → top-left and bottom-right → top-right (the image edges' rays cut with the
    door plane; corners ordered bottom-left, bottom-right, top-right, top-left).

    With u the mean edge direction, w = ½ Σ ‖(r − l) − ((r − l)·u) u‖ over the bottom and top
    corner pairs (l, r): the component across the edges only.  A corner pair lies on one
    image *row*, which a pitched and yawed camera does not see as level: at 1.5 m and
    0.3 rad the bottom corners were 0.30 m apart in height, and their plain distance made a
    0.914 m leaf 0.939 m wide.  The edges' own RANSAC lines are no measure either: they are
    fitted to depth read ``edge_depth_offset`` px *inside* the door, 2·offset·z/f short
    (5.8 cm at 3 m with f = 415 px; a 0.84 m leaf failed the 0.80 m gate there, and the pair
    of one leaf edge and the far jamb's outer edge, 0.91 m, was taken instead).
    """
    left, right = corners[3] - corners[0], corners[2] - corners[1]
    up = left / np.linalg.norm(left) + np.sign(float(left @ right)) * right / np.linalg.norm(right)
    up /= np.linalg.norm(up)
    across = np.stack([corners[1] - corners[0], corners[2] - corners[3]])
    across -= np.outer(across @ up, up)
    return float(np.linalg.norm(across, axis=1).mean())
