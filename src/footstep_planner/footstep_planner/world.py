"""The planar world the planner walks in: a set of convex obstacles and collision queries."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from footstep_planner.geometry import (
    BoolArray,
    FloatArray,
    PackedPolygons,
    edge_normals,
    interior_angles,
    rectangle_axes,
    rectangles_overlap_polygons,
    rectangles_touch_any,
)
from footstep_planner.obstacles import Obstacle

if TYPE_CHECKING:
    from footstep_planner.door import DoorGeometry

__all__ = ["BoundingRectangles", "World"]


@dataclass(frozen=True, eq=False)
class BoundingRectangles:
    """An oriented bounding rectangle per obstacle (exact for rectangular obstacles).

    Used for the cheap test "is anything within r of this point?": the
    distance to a bounding rectangle never exceeds the distance to its
    obstacle, so a point far from every rectangle is far from every obstacle.
    """

    centres: FloatArray
    axes: FloatArray
    half_extents: FloatArray

    @classmethod
    def of(cls, polygons: list[FloatArray]) -> BoundingRectangles:
        """Bounding rectangles aligned with each polygon's longest edge."""
        centres, axes, extents = [], [], []
        for vertices in polygons:
            edges = np.roll(vertices, -1, axis=0) - vertices
            longest = edges[np.argmax(np.hypot(edges[:, 0], edges[:, 1]))]
            along = longest / np.hypot(*longest)
            frame = np.array([along, [-along[1], along[0]]])
            local = vertices @ frame.T
            low, high = local.min(axis=0), local.max(axis=0)
            centres.append(frame.T @ ((low + high) / 2.0))
            axes.append(frame)
            extents.append((high - low) / 2.0)
        return cls(np.array(centres).reshape(-1, 2), np.array(axes).reshape(-1, 2, 2),
                   np.array(extents).reshape(-1, 2))

    def distance(self, x: float, y: float) -> float:
        """Distance from (x, y) to the nearest rectangle (0 inside one, inf if none)."""
        if len(self.centres) == 0:
            return float("inf")
        local = np.abs(np.einsum("mij,mj->mi", self.axes, np.array([x, y]) - self.centres))
        outside = np.maximum(local - self.half_extents, 0.0)
        return float(np.min(np.hypot(outside[:, 0], outside[:, 1])))


@dataclass(frozen=True)
class World:
    """Obstacles in ``odom``; answers "does this rectangle touch anything?" in batches."""

    obstacles: tuple[Obstacle, ...] = ()
    _polygons: PackedPolygons = field(init=False, repr=False, compare=False)
    _bounds: BoundingRectangles = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        arrays = [obstacle.array for obstacle in self.obstacles]
        object.__setattr__(self, "_polygons", PackedPolygons.pack(arrays))
        object.__setattr__(self, "_bounds", BoundingRectangles.of(arrays))

    @classmethod
    def from_door(cls, door: DoorGeometry,
                  sweep: tuple[float, float] | None = None) -> World:
        """Wall, door posts and door leaf of ``door``; plus the leaf's sweep between the two
        door angles of ``sweep`` (rad) when given, for "keep out of the door's swing"."""
        from footstep_planner.door import door_obstacles  # door.py builds on this module
        return cls(door_obstacles(door, sweep))

    def rectangles_collide(self, x: FloatArray, y: FloatArray, yaw: FloatArray,
                           length: float | FloatArray, width: float | FloatArray,
                           margin: float | FloatArray = 0.0) -> BoolArray:
        """For N oriented rectangles, does each touch any obstacle?  Shape (N,).

        A rectangle is centred on (x, y) with ``length`` along ``yaw`` and
        ``width`` across (m), grown by ``margin`` on every side (m); sizes are
        scalars or one per rectangle.  Exact separating-axis test (touching
        counts as a collision).
        """
        x, y, yaw = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (x, y, yaw))
        if not self.obstacles:
            return np.zeros(len(x), dtype=bool)
        half_length = np.broadcast_to(np.asarray(length) / 2.0 + margin, x.shape).astype(float)
        half_width = np.broadcast_to(np.asarray(width) / 2.0 + margin, x.shape).astype(float)
        return rectangles_touch_any(x, y, yaw, half_length, half_width, self._polygons)

    def rectangles_touch(self, x: FloatArray, y: FloatArray, yaw: FloatArray, half_length: FloatArray,
                         half_width: FloatArray) -> BoolArray:
        """:meth:`rectangles_collide` for 1-D arrays of half extents (margins included), without
        any conversion: the planner's inner loop."""
        if not self.obstacles:
            return np.zeros(len(x), dtype=bool)
        return rectangles_touch_any(x, y, yaw, half_length, half_width, self._polygons)

    def rectangle_hits(self, x: FloatArray, y: FloatArray, yaw: FloatArray,
                       length: float | FloatArray, width: float | FloatArray,
                       margin: float | FloatArray = 0.0) -> BoolArray:
        """Like :meth:`rectangles_collide`, per obstacle: shape (N, M)."""
        if not self.obstacles:
            return np.zeros((len(x), 0), dtype=bool)
        half_extents = np.empty((len(x), 2))
        half_extents[:, 0] = np.asarray(length) / 2.0 + margin
        half_extents[:, 1] = np.asarray(width) / 2.0 + margin
        centres = np.stack((x, y), axis=1)
        boxes = _boxes_overlap(centres, np.hypot(half_extents[:, 0], half_extents[:, 1]),
                               self._polygons)
        rows = np.asarray(boxes.any(axis=1), dtype=bool)
        columns = np.asarray(boxes.any(axis=0), dtype=bool)
        hits = np.zeros_like(boxes)
        if rows.any():
            exact = rectangles_overlap_polygons(centres[rows], rectangle_axes(yaw[rows]),
                                                half_extents[rows],
                                                self._polygons.subset(columns))
            hits[np.ix_(rows, columns)] = exact & boxes[np.ix_(rows, columns)]
        return hits

    def colliding_obstacles(self, x: float, y: float, yaw: float, length: float, width: float,
                            margin: float = 0.0) -> tuple[str, ...]:
        """Names of the obstacles one rectangle touches (see :meth:`rectangles_collide`)."""
        hits = self.rectangle_hits(np.array([x]), np.array([y]), np.array([yaw]),
                                   length, width, margin)[0]
        return tuple(obstacle.name for obstacle, hit in zip(self.obstacles, hits) if hit)

    def distance_lower_bound(self, x: float, y: float) -> float:
        """A lower bound of the distance from (x, y) to the nearest obstacle (m)."""
        return self._bounds.distance(x, y)

    def near_obstacles(self, points: FloatArray, distance: float) -> BoolArray:
        """Which points (P, 2) lie within ``distance`` (m) of an obstacle.  Shape (P,).

        Each polygon ``{p : n_k . p <= o_k}`` is grown to
        ``{p : n_k . p <= o_k + distance * sin(alpha_min / 2)}``; a point of
        the grown polygon is at most ``distance`` from the original (the worst
        point is at the sharpest corner, of interior angle alpha_min).  So a
        True here always means "within distance"; points within ``distance``
        of a corner may still read False.  Only the points inside a polygon's
        grown bounding box are tested against it.
        """
        near = np.zeros(len(points), dtype=bool)
        for obstacle in self.obstacles:
            vertices = obstacle.array
            low, high = vertices.min(axis=0) - distance, vertices.max(axis=0) + distance
            candidates = np.flatnonzero(np.all((points >= low) & (points <= high), axis=1))
            if len(candidates) == 0:
                continue
            normals = edge_normals(vertices)
            grown = (np.sum(normals * vertices, axis=1)
                     + distance * math.sin(float(np.min(interior_angles(vertices))) / 2.0))
            inside = np.all(points[candidates] @ normals.T <= grown, axis=1)
            near[candidates[inside]] = True
        return near


def _boxes_overlap(centres: FloatArray, radii: FloatArray, polygons: PackedPolygons) -> BoolArray:
    """(N, M): does the square of half side ``radius`` about each centre (it holds the
    rectangle) overlap each polygon's bounding box?  A cheap filter before the exact test."""
    low, high = centres - radii[:, None], centres + radii[:, None]
    overlap: BoolArray = np.all((low[:, None, :] <= polygons.box_max[None]) &
                                (high[:, None, :] >= polygons.box_min[None]), axis=2)
    return overlap
