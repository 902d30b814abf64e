"""Door hypotheses from pairs of vertical lines, checked in 3-D ([Banerjee 2015] Sec. III-A).

For a pair of image lines (L left, R right) the paper's door D = (P1, P2, S_P) must
satisfy (eq. 2):

* 80 cm ≤ ‖P1 − P2‖ ≤ 100 cm: the image edges' rays, cut with the plane of the two edges'
  RANSAC 3-D lines, are a door's width apart (:func:`~door_detection.edges.edge_width`);
* every P in S_P lies on one plane, (a − P)·b = 0: points sampled on the two image
  diagonals of the door back-project to within 5 cm of the plane spanned by the edges.

Depth along an edge is read ``edge_depth_offset`` px *inside* the hypothesised door
(right of L, left of R) so the samples fall on the leaf, not on the frame or on the
background seen through the gap: each line therefore gets two fits, one per side.

Beyond the paper: the paper's fixed 5 cm (plane) and the line RANSAC threshold assume a
good disparity map; stereo noise grows as z² (σ ≈ 5 cm per pixel at 4 m for a
MultiSense-like head), so each threshold widens to ``NOISE_GATE``·σ̂, with σ̂ the depth
noise measured on the samples themselves (:func:`~door_detection.plane.depth_noise`);
samples noisier than ``max_depth_noise`` are no smooth surface and are rejected.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_detection.edges import edge_width
from door_detection.lines import VerticalLines
from door_detection.options import DetectionOptions
from door_detection.plane import Line3D, Plane, depth_noise, pixel_rays, ransac_line, sample_depth

__all__ = ["DoorCandidate", "corners_3d", "door_surface_points", "find_doors", "frame_pairs", "merge_duplicates",
           "pair_lines"]

INSIDE_RIGHT = 1
"""Sample to the right of a line: the line is a door's left edge."""
INSIDE_LEFT = -1
"""Sample to the left of a line: the line is a door's right edge."""
NOISE_GATE = 3.0
"""Inlier thresholds widen to this many σ of the measured depth noise (see below)."""


@dataclass(frozen=True)
class DoorCandidate:
    """A door hypothesis that passed the width and plane checks.

    ``left``/``right`` index the image lines; ``top``/``bottom`` are the rows both edges
    span, ``outer_top``/``outer_bottom`` the rows either spans (a faint edge's line may
    cover only part of the door); ``plane`` has its normal towards the camera (cross
    product of the line joining the edges and an edge, Sec. III-A); ``plane_fraction`` is
    the fraction of valid diagonal samples on it.
    """

    left: int
    right: int
    left_edge: Line3D
    right_edge: Line3D
    width: float
    plane: Plane
    plane_fraction: float
    top: float
    bottom: float
    score: float
    outer_top: float = math.nan
    outer_bottom: float = math.nan

    @property
    def partly_seen(self) -> bool:
        """One edge's line spans rows the other's does not."""
        return bool(self.outer_top < self.top or self.outer_bottom > self.bottom)

    def image_corners(self, lines: VerticalLines, outer: bool = False) -> np.ndarray:
        """(4, 2) pixels: bottom-left, bottom-right, top-right, top-left, on the rows both edges
        span (``outer``: either spans, the shorter line extended)."""
        top, bottom = (self.outer_top, self.outer_bottom) if outer else (self.top, self.bottom)
        xs = lines.x_at(np.array([[bottom, top]] * len(lines)))
        xl_bottom, xl_top = xs[self.left]
        xr_bottom, xr_top = xs[self.right]
        return np.array([[xl_bottom, bottom], [xr_bottom, bottom], [xr_top, top], [xl_top, top]])


def find_doors(lines: VerticalLines, depth: np.ndarray, intrinsics: CameraIntrinsics,
               options: DetectionOptions) -> tuple[list[DoorCandidate], int]:
    """Door candidates, best first, and how many pairs passed the width check.

    Steps: 2-D pairing → per-edge RANSAC lines → width and parallelism → duplicate
    merge → diagonal plane check.
    """
    rng = np.random.default_rng(options.random_seed)
    pairs = pair_lines(lines, options)
    fits: dict[tuple[int, int], Line3D | None] = {}
    sized: list[DoorCandidate] = []
    for left, right in pairs:
        candidate = _sized_candidate(lines, int(left), int(right), depth, intrinsics, options, rng, fits)
        if candidate is not None:
            sized.append(candidate)
    unique = merge_duplicates(sized, options.duplicate_distance)
    checked = [c for c in (_check_plane(c, lines, depth, intrinsics, options) for c in unique)
               if c is not None]
    frames = frame_pairs(checked, options.frame_width_max)
    return sorted(checked, key=lambda c: (id(c) in frames, -c.score)), len(unique)


def pair_lines(lines: VerticalLines, options: DetectionOptions) -> np.ndarray:
    """Index pairs (left, right) of lines that overlap vertically and are at least
    ``min_pair_separation`` px apart (Sec. III-A: pairs closer than 60 px are dropped)."""
    n = len(lines)
    if n < 2:
        return np.zeros((0, 2), dtype=int)
    s = lines.segments
    top = np.maximum(s[:, 1][:, None], s[:, 1][None, :])
    bottom = np.minimum(s[:, 3][:, None], s[:, 3][None, :])
    heights = s[:, 3] - s[:, 1]
    overlap = (bottom - top) / np.maximum(np.minimum(heights[:, None], heights[None, :]), 1e-9)
    mid = 0.5 * (top + bottom)
    x_mid = lines.x_at(mid)                                   # [i, j] = x_i at the pair's mid row
    separation = x_mid.T - x_mid                              # x_j − x_i
    ok = (overlap >= options.min_vertical_overlap) & (separation >= options.min_pair_separation)
    return np.argwhere(ok)


def _edge_fit(lines: VerticalLines, index: int, side: int, depth: np.ndarray,
              intrinsics: CameraIntrinsics, options: DetectionOptions,
              rng: np.random.Generator) -> Line3D | None:
    """RANSAC 3-D line of the depth samples beside image line ``index`` (on ``side``)."""
    x_top, y_top, _, y_bottom = lines.segments[index]
    count = int(min(options.line_max_points, max(y_bottom - y_top, 2)))
    rows = np.linspace(y_top, y_bottom, count)
    cols = lines.x_at(np.tile(rows, (len(lines), 1)))[index] + side * options.edge_depth_offset
    points = sample_depth(depth, intrinsics, cols, rows)
    if len(points) < min(options.min_region_points, count // 2):
        return None
    noise = depth_noise(points)
    if noise > options.max_depth_noise:
        return None
    threshold = max(options.line_ransac_threshold, NOISE_GATE * noise)
    line = ransac_line(points, threshold, options.line_ransac_iterations, rng)
    if line is None or line.inlier_fraction < options.min_line_inlier_fraction:
        return None
    return line


def _cached_fit(cache: dict[tuple[int, int], Line3D | None], lines: VerticalLines, index: int,
                side: int, depth: np.ndarray, intrinsics: CameraIntrinsics,
                options: DetectionOptions, rng: np.random.Generator) -> Line3D | None:
    key = (index, side)
    if key not in cache:
        cache[key] = _edge_fit(lines, index, side, depth, intrinsics, options, rng)
    return cache[key]


def _sized_candidate(lines: VerticalLines, left: int, right: int, depth: np.ndarray,
                     intrinsics: CameraIntrinsics, options: DetectionOptions,
                     rng: np.random.Generator,
                     cache: dict[tuple[int, int], Line3D | None]) -> DoorCandidate | None:
    """The pair as a candidate when its 3-D edges are parallel and a door-width apart."""
    left_edge = _cached_fit(cache, lines, left, INSIDE_RIGHT, depth, intrinsics, options, rng)
    if left_edge is None:
        return None
    right_edge = _cached_fit(cache, lines, right, INSIDE_LEFT, depth, intrinsics, options, rng)
    if right_edge is None:
        return None
    direction = _mean_direction(left_edge.direction, right_edge.direction)
    if abs(float(left_edge.direction @ right_edge.direction)) < math.cos(math.radians(options.max_edge_angle_deg)):
        return None
    across = right_edge.point - left_edge.point
    across_perp = across - float(across @ direction) * direction
    normal = np.cross(direction, across_perp)
    plane = Plane(0.5 * (left_edge.point + right_edge.point), normal / np.linalg.norm(normal))
    s = lines.segments
    top, bottom = max(s[left, 1], s[right, 1]), min(s[left, 3], s[right, 3])
    candidate = DoorCandidate(left, right, left_edge, right_edge, 0.0, plane.facing(np.zeros(3)),
                              0.0, float(top), float(bottom), 0.0, float(min(s[left, 1], s[right, 1])),
                              float(max(s[left, 3], s[right, 3])))
    width = edge_width(corners_3d(candidate, lines, candidate.plane, intrinsics))
    tolerance = options.door_width_tolerance
    if not options.door_width_min - tolerance <= width <= options.door_width_max + tolerance:
        return None
    return replace(candidate, width=width)


def _mean_direction(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    b = b if float(a @ b) >= 0 else -b
    mean = a + b
    direction: np.ndarray = mean / np.linalg.norm(mean)
    return direction


def merge_duplicates(candidates: list[DoorCandidate], distance: float) -> list[DoorCandidate]:
    """Keep one candidate per door (Sec. III-A: "door pairs that have the same line
    equations are merged"): a candidate whose two edges both lie within ``distance`` of
    an already kept one's edges is dropped; the kept one has the most edge inliers."""
    ordered = sorted(candidates, key=lambda c: -(c.left_edge.inliers + c.right_edge.inliers))
    kept: list[DoorCandidate] = []
    for candidate in ordered:
        if not any(_same_door(candidate, other, distance) for other in kept):
            kept.append(candidate)
    return kept


def frame_pairs(candidates: list[DoorCandidate], frame_width: float,
                tolerance: float = 0.01) -> set[int]:
    """ids of the pairs that hold another pair nested inside them by at most ``frame_width``
    on both sides. The leaf and its frame give two to four door-like pairs (leaf edges,
    the jambs' outer edges, and mixtures) on one plane; the door is the innermost, so
    these rank after it (they stay candidates in case the leaf pair shows no handle).
    Offsets are measured across the outer pair, perpendicular to its edges."""
    return {id(outer) for outer in candidates
            if any(_nested(inner, outer, frame_width, tolerance) for inner in candidates if inner is not outer)}


def _nested(inner: DoorCandidate, outer: DoorCandidate, frame_width: float, tolerance: float) -> bool:
    direction = _mean_direction(outer.left_edge.direction, outer.right_edge.direction)
    across = outer.right_edge.point - outer.left_edge.point
    across = across - float(across @ direction) * direction
    across /= np.linalg.norm(across)
    left_inset = float((inner.left_edge.point - outer.left_edge.point) @ across)
    right_inset = float((outer.right_edge.point - inner.right_edge.point) @ across)
    insets = (left_inset, right_inset)
    return all(-tolerance <= inset <= frame_width for inset in insets) and sum(insets) > tolerance


def _same_door(a: DoorCandidate, b: DoorCandidate, distance: float) -> bool:
    points = np.stack([a.left_edge.point, a.right_edge.point])
    return bool(b.left_edge.distance(points[:1])[0] <= distance and
                b.right_edge.distance(points[1:])[0] <= distance)


def _check_plane(candidate: DoorCandidate, lines: VerticalLines, depth: np.ndarray,
                 intrinsics: CameraIntrinsics, options: DetectionOptions) -> DoorCandidate | None:
    """Sample the two image diagonals; keep the door if their 3-D points lie on its plane.

    The plane is the edges' plane; the fraction of valid diagonal samples within
    ``plane_inlier_distance`` must reach ``min_plane_inlier_fraction``.  The score ranks
    survivors: plane fraction + mean edge inlier fraction + visible height fraction.
    """
    corners = candidate.image_corners(lines)
    inset = options.edge_depth_offset
    t = np.linspace(0.03, 0.97, options.diagonal_samples)
    diagonals = []
    for start, end in ((corners[0], corners[2]), (corners[3], corners[1])):
        sx, ex = start[0] + inset * np.sign(end[0] - start[0]), end[0] - inset * np.sign(end[0] - start[0])
        diagonals.append(np.stack([sx + t * (ex - sx), start[1] + t * (end[1] - start[1])], axis=1))
    samples = np.concatenate(diagonals)
    points = sample_depth(depth, intrinsics, samples[:, 0], samples[:, 1])
    if len(points) < max(4, len(samples) // 4):
        return None
    half = len(points) // 2
    noise = 0.5 * (depth_noise(points[:half]) + depth_noise(points[half:]))
    if noise > options.max_depth_noise:
        return None
    threshold = max(options.plane_inlier_distance, NOISE_GATE * noise)
    on_plane = np.abs(candidate.plane.signed_distance(points)) <= threshold
    fraction = float(on_plane.mean())
    if fraction < options.min_plane_inlier_fraction:
        return None
    edges = 0.5 * (candidate.left_edge.inlier_fraction + candidate.right_edge.inlier_fraction)
    height = (candidate.bottom - candidate.top) / depth.shape[0]
    return replace(candidate, plane_fraction=fraction, score=fraction + edges + height)


def door_surface_points(candidate: DoorCandidate, lines: VerticalLines, depth: np.ndarray,
                        intrinsics: CameraIntrinsics, options: DetectionOptions) -> np.ndarray:
    """Valid 3-D points on a grid inside the door's image quadrilateral (margin excluded),
    at most ``plane_max_points`` of them, to refine the plane by least squares."""
    rows_n = max(int(math.sqrt(options.plane_max_points * 2)), 2)
    cols_n = max(options.plane_max_points // rows_n, 2)
    margin = options.door_margin_fraction
    rows = np.linspace(candidate.top, candidate.bottom, rows_n)
    xs = lines.x_at(np.tile(rows, (len(lines), 1)))
    xl, xr = xs[candidate.left][:, None], xs[candidate.right][:, None]
    t = np.linspace(margin, 1.0 - margin, cols_n)[None, :]
    u = xl + t * (xr - xl)
    v = np.broadcast_to(rows[:, None], u.shape)
    return sample_depth(depth, intrinsics, u.ravel(), v.ravel())


def corners_3d(candidate: DoorCandidate, lines: VerticalLines, plane: Plane,
               intrinsics: CameraIntrinsics) -> np.ndarray:
    """The image corners' rays intersected with the door plane (4, 3)."""
    pixels = candidate.image_corners(lines)
    return plane.intersect_rays(pixel_rays(intrinsics, pixels[:, 0], pixels[:, 1]))
