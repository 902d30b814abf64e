"""A jamb taken for the leaf, found by depth and cut off (beyond the paper).

When the leaf and its frame have one colour (a white leaf in a white frame), the boundary
between them may not show at all: the jamb's face is flush with the leaf's in colour and
its side face is a sub-pixel sliver. The pair of lines is then one leaf edge and the far
side of a jamb — a door 6 cm too wide, its hinge (which the door motions turn about) 6 cm
off; 4 of 490 Table II starts had that. Depth still tells them apart: the frame stands
proud of the leaf (1 cm in the sim, the casing's depth on real doors).

For each edge, the points of every row's strip up to ``frame_width_max`` inside it get
their distance w from the edge along the door (from the pixels' rays cut with the door
plane, so noise moves them along the ray only) and their stand-off d above the plane. A
jamb is a step: for each candidate width c (every ``JAMB_STEP`` from ``JAMB_MIN_WIDTH``),
the medians of d over w < c and over c ≤ w < c + ``JAMB_REFERENCE`` differ by Δ(c) with
standard error σ_Δ = √(σ₁² + σ₂²), σᵢ = 1.2533·1.4826·MAD/√n (medians: robust to the
handle's rows). The c of largest Δ/σ_Δ is the jamb when Δ ≥ ``JAMB_MIN_STEP``,
Δ/σ_Δ ≥ ``JAMB_MIN_SCORE`` and the reference part lies on the plane (|median| < Δ/2); the
edge then moves inward by c.
"""

from __future__ import annotations

import math

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_detection.door_pairs import DoorCandidate
from door_detection.lines import VerticalLines
from door_detection.plane import Plane, pixel_rays

__all__ = ["trim_jambs"]

JAMB_STEP = 0.005
"""Spacing of the candidate jamb widths (m)."""
JAMB_MIN_WIDTH = 0.02
"""Narrowest jamb (m): a 4 mm gap or a mixed pixel is none."""
JAMB_REFERENCE = 0.04
"""Width of the leaf strip a jamb is compared with (m)."""
JAMB_MIN_STEP = 0.004
"""Smallest stand-off of a jamb above the leaf (m)."""
JAMB_MIN_SCORE = 5.0
"""Smallest step, in standard errors."""
JAMB_MIN_DEPTH = 0.1
"""m: an edge nearer the camera than this is not measured."""
JAMB_MAX_ROWS = 600
"""Rows sampled along each edge, at most: every row (at 3.5 m and σ = 4 cm, a 1 cm step over
a 6.7 cm jamb is ~7 standard errors over 260 rows, < 1 over 40)."""


def trim_jambs(lines: VerticalLines, candidate: DoorCandidate, plane: Plane, depth: np.ndarray,
               intrinsics: CameraIntrinsics, frame_width: float) -> VerticalLines:
    """``lines`` with the candidate's edges moved inward past any jamb found beside them."""
    segments = lines.segments.copy()
    count = int(min(candidate.bottom - candidate.top + 1, JAMB_MAX_ROWS))
    rows = np.linspace(candidate.top, candidate.bottom, max(count, 2))
    xs = lines.x_at(np.tile(rows, (len(lines), 1)))
    for index, other, inward in ((candidate.left, candidate.right, 1), (candidate.right, candidate.left, -1)):
        edge = plane.intersect_rays(pixel_rays(intrinsics, xs[index], rows))
        across = plane.intersect_rays(pixel_rays(intrinsics, xs[other], rows)) - edge
        if not (np.all(np.isfinite(edge)) and np.all(np.isfinite(across))):
            continue
        axis = across.mean(axis=0) / np.linalg.norm(across.mean(axis=0))
        inset = _jamb_width(edge, axis, rows, xs[index], inward, plane, depth, intrinsics, frame_width)
        if inset > 0.0:
            segments[index] = _moved(segments[index], edge, axis * inset, rows, intrinsics)
    return VerticalLines(segments)


def _jamb_width(edge: np.ndarray, axis: np.ndarray, rows: np.ndarray, edge_x: np.ndarray, inward: int,
                plane: Plane, depth: np.ndarray, intrinsics: CameraIntrinsics, frame_width: float) -> float:
    """Width (m) of the jamb beside the edge (see the module docstring), 0 when there is none.

    An edge whose rays meet the plane behind or at the camera (a plane seen edge-on) has no
    jamb to measure; the strip searched is at most the image's width (unbounded, a ray that
    grazed the plane asked for a 62-million-pixel strip and the detector ran out of memory)."""
    if not np.all(edge[:, 2] > JAMB_MIN_DEPTH):
        return 0.0
    span = np.minimum(np.ceil(frame_width * intrinsics.fx / edge[:, 2]), depth.shape[1]).astype(int)
    offsets = np.arange(int(span.max()) + 1)[None, :]
    cols = np.rint(edge_x)[:, None] + inward * offsets
    which = np.broadcast_to(np.arange(rows.size)[:, None], cols.shape)     # the sampled row of each pixel
    pixel_rows = np.rint(rows)[which]
    keep = (offsets <= span[:, None]) & (cols >= 0) & (cols < depth.shape[1]) & \
        (pixel_rows >= 0) & (pixel_rows < depth.shape[0])
    cols, pixel_rows, which = cols[keep].astype(int), pixel_rows[keep].astype(int), which[keep]
    z = depth[pixel_rows, cols]
    valid = np.isfinite(z)
    cols, pixel_rows, which, z = cols[valid], pixel_rows[valid], which[valid], z[valid]
    points = intrinsics.back_project(cols.astype(float), pixel_rows.astype(float), z)
    on_plane = plane.intersect_rays(pixel_rays(intrinsics, cols, pixel_rows))
    position = np.einsum("ij,j->i", on_plane - edge[which], axis)
    proud = plane.signed_distance(points)
    best, width = 0.0, 0.0
    for candidate in np.arange(JAMB_MIN_WIDTH, frame_width - JAMB_REFERENCE + 1e-9, JAMB_STEP):
        inner, outer = proud[position < candidate], proud[(position >= candidate) & (position < candidate + JAMB_REFERENCE)]
        if inner.size < 8 or outer.size < 8:
            continue
        step = float(np.median(inner) - np.median(outer))
        score = step / math.hypot(_median_error(inner), _median_error(outer))
        if step >= JAMB_MIN_STEP and abs(float(np.median(outer))) < step / 2 and score > max(best, JAMB_MIN_SCORE):
            best, width = score, float(candidate)
    return width


def _median_error(values: np.ndarray) -> float:
    """Standard error of a sample's median, 1.2533·σ̂/√n with σ̂ = 1.4826·MAD (floor 0.1 mm)."""
    spread = 1.4826 * float(np.median(np.abs(values - np.median(values))))
    return max(1.2533 * spread / math.sqrt(values.size), 1e-4)


def _moved(segment: np.ndarray, edge: np.ndarray, shift: np.ndarray, rows: np.ndarray,
           intrinsics: CameraIntrinsics) -> np.ndarray:
    """The segment refitted through the edge points moved by ``shift`` (projected)."""
    pixels = intrinsics.project(edge + shift)
    slope, offset = np.polyfit(pixels[:, 1], pixels[:, 0], 1)
    top, bottom = segment[1], segment[3]
    return np.array([slope * top + offset, top, slope * bottom + offset, bottom])
