"""Planar geometry: angles, rectangles, convex hulls, separating-axis tests.

Everything is vectorised over a leading batch dimension where it matters for
the planner's speed.  Polygons are convex, counter-clockwise, shape (K, 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["BoolArray", "Bounds", "FloatArray", "PackedPolygons", "convex_hull", "edge_normals", "interior_angles",
           "rectangle_axes", "rectangle_corners", "rectangles_overlap_polygons", "rectangles_touch_any", "wrap_angle",
           "wrap_angles"]

FloatArray = NDArray[np.floating[Any]]
BoolArray = NDArray[np.bool_]


def wrap_angle(angle: float) -> float:
    """``angle`` wrapped to [-pi, pi) (rad)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def wrap_angles(angles: FloatArray) -> FloatArray:
    """Element-wise :func:`wrap_angle`."""
    wrapped: FloatArray = np.remainder(angles + np.pi, 2.0 * np.pi) - np.pi
    return wrapped


def rectangle_corners(centre_x: FloatArray, centre_y: FloatArray, yaw: FloatArray,
                      half_length: float | FloatArray, half_width: float | FloatArray
                      ) -> FloatArray:
    """Corners of N oriented rectangles, counter-clockwise, shape (N, 4, 2).

    A rectangle's length lies along its yaw; corner k is
    ``centre + R(yaw) @ (sx_k * half_length, sy_k * half_width)`` with
    (sx, sy) = (+,+), (-,+), (-,-), (+,-).
    """
    cos_yaw, sin_yaw = np.cos(yaw), np.sin(yaw)
    local_x = np.multiply.outer(np.broadcast_to(half_length, np.shape(yaw)), _SIGNS_X)
    local_y = np.multiply.outer(np.broadcast_to(half_width, np.shape(yaw)), _SIGNS_Y)
    world_x = centre_x[:, None] + cos_yaw[:, None] * local_x - sin_yaw[:, None] * local_y
    world_y = centre_y[:, None] + sin_yaw[:, None] * local_x + cos_yaw[:, None] * local_y
    return np.stack((world_x, world_y), axis=-1)


_SIGNS_X = np.array([1.0, -1.0, -1.0, 1.0])
_SIGNS_Y = np.array([1.0, 1.0, -1.0, -1.0])


def convex_hull(points: FloatArray) -> FloatArray:
    """Convex hull of 2-D points, counter-clockwise without collinear points (Andrew's chain)."""
    unique = np.unique(np.asarray(points, dtype=float), axis=0)
    if len(unique) < 3:
        return unique
    ordered = [tuple(p) for p in unique]  # np.unique sorts by x then y
    lower = _half_hull(ordered)
    upper = _half_hull(ordered[::-1])
    return np.array(lower[:-1] + upper[:-1], dtype=float)


_COLLINEAR = 1e-9
"""Cross products (m^2) at or below this count as collinear: such hull points are dropped."""


def _half_hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """One monotone chain of Andrew's algorithm (keeps left turns only)."""
    chain: list[tuple[float, float]] = []
    for point in points:
        while len(chain) >= 2 and _cross(chain[-2], chain[-1], point) <= _COLLINEAR:
            chain.pop()
        chain.append(point)
    return chain


def _cross(o: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
    """z of (a - o) x (b - o): positive for a left turn."""
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def edge_normals(vertices: FloatArray) -> FloatArray:
    """Outward unit normals of a counter-clockwise polygon's edges, shape (K, 2).

    Edge k runs from vertex k to vertex k+1; for a CCW polygon its outward
    normal is the edge direction turned clockwise: (dy, -dx) / |edge|.
    """
    edges = np.roll(vertices, -1, axis=0) - vertices
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    normals: FloatArray = np.stack((edges[:, 1], -edges[:, 0]), axis=1) / lengths[:, None]
    return normals


def interior_angles(vertices: FloatArray) -> FloatArray:
    """Interior angle (rad) at each vertex of a convex CCW polygon."""
    to_previous = np.roll(vertices, 1, axis=0) - vertices
    to_next = np.roll(vertices, -1, axis=0) - vertices
    cosine = np.sum(to_previous * to_next, axis=1) / (
        np.hypot(*to_previous.T) * np.hypot(*to_next.T))
    angles: FloatArray = np.arccos(np.clip(cosine, -1.0, 1.0))
    return angles


@dataclass(frozen=True, eq=False)
class PackedPolygons:
    """M convex polygons padded to a common vertex count K for batched tests.

    Padding repeats a polygon's first vertex and first normal, which changes
    neither its projections nor its half-plane description.

    Attributes:
        vertices: (M, K, 2) vertices.
        normals: (M, K, 2) outward unit edge normals.
        normal_ranges: (M, K, 2) min and max projection of the polygon on each
            of its own normals.
        box_min, box_max: (M, 2) axis-aligned bounding box of each polygon.
    """

    vertices: FloatArray
    normals: FloatArray
    normal_ranges: FloatArray
    box_min: FloatArray
    box_max: FloatArray
    flat_normals: FloatArray = field(init=False, repr=False)
    """(2, M K) the normals as columns, for one matrix product per batch."""
    flat_vertices: FloatArray = field(init=False, repr=False)
    """(2, M K) the vertices as columns."""

    def __post_init__(self) -> None:
        object.__setattr__(self, "flat_normals", np.ascontiguousarray(self.normals.reshape(-1, 2).T))
        object.__setattr__(self, "flat_vertices", np.ascontiguousarray(self.vertices.reshape(-1, 2).T))

    @classmethod
    def pack(cls, polygons: list[FloatArray]) -> PackedPolygons:
        """Pad and stack CCW convex polygons (each (K_i, 2), K_i >= 3)."""
        width = max((len(p) for p in polygons), default=3)
        vertices = np.zeros((len(polygons), width, 2))
        normals = np.zeros((len(polygons), width, 2))
        for index, polygon in enumerate(polygons):
            count = len(polygon)
            vertices[index, :count], vertices[index, count:] = polygon, polygon[0]
            own_normals = edge_normals(polygon)
            normals[index, :count], normals[index, count:] = own_normals, own_normals[0]
        projections = np.einsum("mki,mji->mkj", normals, vertices)
        ranges = np.stack((projections.min(axis=2), projections.max(axis=2)), axis=-1)
        return cls(vertices, normals, ranges, vertices.min(axis=1), vertices.max(axis=1))

    def subset(self, keep: BoolArray) -> PackedPolygons:
        """The polygons selected by the (M,) mask ``keep``."""
        return PackedPolygons(self.vertices[keep], self.normals[keep], self.normal_ranges[keep],
                              self.box_min[keep], self.box_max[keep])

    @property
    def count(self) -> int:
        """Number of polygons M."""
        return int(self.vertices.shape[0])


def rectangles_overlap_polygons(centres: FloatArray, axes: FloatArray, half_extents: FloatArray,
                                polygons: PackedPolygons) -> BoolArray:
    """Separating-axis test of N rectangles against M convex polygons, shape (N, M).

    Two convex shapes are disjoint iff their projections on some edge normal
    of either shape are disjoint (separating axis theorem).  The candidate
    axes are the rectangle's two axes and the polygon's K normals.  On a unit
    axis n a rectangle of centre c, unit axes (a, b) and half extents (l, w)
    projects to ``c.n -+ (l |a.n| + w |b.n|)``; on its own axes it projects to
    ``c.a -+ l`` and ``c.b -+ w``.  Touching shapes count as overlapping.

    Args:
        centres: (N, 2) rectangle centres.
        axes: (N, 2, 2) the rectangles' unit length and width axes.
        half_extents: (N, 2) half length and half width along those axes.
        polygons: the obstacles.
    """
    count, shape = len(centres), (len(centres), polygons.count, -1)
    normals = polygons.normals.reshape(-1, 2).T
    centre_on_normals = centres @ normals
    reach = (half_extents[:, :1] * np.abs(axes[:, 0] @ normals)
             + half_extents[:, 1:] * np.abs(axes[:, 1] @ normals))
    ranges = polygons.normal_ranges.reshape(-1, 2)
    separated = np.any(((centre_on_normals + reach < ranges[:, 0])
                        | (centre_on_normals - reach > ranges[:, 1])).reshape(shape), axis=2)
    vertices = polygons.vertices.reshape(-1, 2).T
    for axis in range(2):
        on_axis = (axes[:, axis] @ vertices).reshape(shape)
        centre = np.sum(centres * axes[:, axis], axis=1)[:, None]
        extent = half_extents[:, axis:axis + 1]
        separated |= ((on_axis.max(axis=2) < centre - extent)
                      | (on_axis.min(axis=2) > centre + extent))
    overlapping: BoolArray = ~separated[:count]
    return overlapping


def rectangles_touch_any(x: FloatArray, y: FloatArray, yaw: FloatArray, half_length: FloatArray,
                         half_width: FloatArray, polygons: PackedPolygons) -> BoolArray:
    """Does each of N rectangles overlap (or touch) any of the polygons?  Shape (N,).

    The test of :func:`rectangles_overlap_polygons` written for the planner's inner loop:
    the rectangles' two axes a = (cos, sin), b = (-sin, cos) meet all M K polygon normals
    and vertices in four matrix products, with no per-call packing of axes or subsets.
    """
    count, shape = len(x), (len(x), polygons.count, -1)
    cos_yaw, sin_yaw = np.cos(yaw), np.sin(yaw)
    along = np.column_stack((cos_yaw, sin_yaw))
    across = np.column_stack((-sin_yaw, cos_yaw))
    normals, vertices = polygons.flat_normals, polygons.flat_vertices
    centre_on_normals = np.column_stack((x, y)) @ normals
    reach = np.abs(along @ normals) * half_length[:, None] + np.abs(across @ normals) * half_width[:, None]
    ranges = polygons.normal_ranges.reshape(-1, 2)
    separated = ((centre_on_normals + reach < ranges[:, 0]) | (centre_on_normals - reach > ranges[:, 1]))
    separated = np.asarray(separated.reshape(shape).any(axis=2))
    for axis, half, centre in ((along, half_length, x * cos_yaw + y * sin_yaw),
                               (across, half_width, y * cos_yaw - x * sin_yaw)):
        on_axis = (axis @ vertices).reshape(shape)
        separated |= ((on_axis.max(axis=2) < (centre - half)[:, None])
                      | (on_axis.min(axis=2) > (centre + half)[:, None]))
    return np.asarray(~separated.all(axis=1)) if count else np.zeros(0, dtype=bool)


def rectangle_axes(yaw: FloatArray) -> FloatArray:
    """Unit length and width axes of rectangles with the given yaws, shape (N, 2, 2)."""
    cos_yaw, sin_yaw = np.cos(yaw), np.sin(yaw)
    return np.stack((np.stack((cos_yaw, sin_yaw), axis=-1),
                     np.stack((-sin_yaw, cos_yaw), axis=-1)), axis=1)


@dataclass(frozen=True)
class Bounds:
    """An axis-aligned rectangle of the plane (m): the planner's search region."""

    x_min: float
    x_max: float
    y_min: float
    y_max: float

    @classmethod
    def around(cls, points: list[tuple[float, float]], margin: float) -> Bounds:
        """The bounding box of ``points`` grown by ``margin`` on every side."""
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        return cls(min(xs) - margin, max(xs) + margin, min(ys) - margin, max(ys) + margin)

    def contains(self, x: FloatArray, y: FloatArray) -> BoolArray:
        """Element-wise: is (x, y) inside the bounds?"""
        return (x >= self.x_min) & (x <= self.x_max) & (y >= self.y_min) & (y <= self.y_max)
