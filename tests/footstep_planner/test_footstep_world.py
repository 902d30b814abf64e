"""Geometry and world collision queries, checked against brute-force sampling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from footstep_planner.errors import FootstepPlannerError
from footstep_planner.geometry import convex_hull, rectangle_corners, wrap_angle
from footstep_planner.obstacles import Obstacle
from footstep_planner.world import World


def _inside_convex(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Points inside (or on) a CCW convex polygon: left of (or on) every edge."""
    edges = np.roll(vertices, -1, axis=0) - vertices
    relative = points[:, None, :] - vertices[None]
    cross = edges[None, :, 0] * relative[..., 1] - edges[None, :, 1] * relative[..., 0]
    return np.all(cross >= -1e-12, axis=1)


def _sampled_overlap(rectangle: np.ndarray, polygon: np.ndarray) -> bool:
    """Brute force: does a fine grid over both shapes' bounding box have a point in both?"""
    low = np.minimum(rectangle.min(axis=0), polygon.min(axis=0))
    high = np.maximum(rectangle.max(axis=0), polygon.max(axis=0))
    u, v = np.meshgrid(np.linspace(low[0], high[0], 160), np.linspace(low[1], high[1], 160))
    points = np.column_stack((u.ravel(), v.ravel()))
    return bool(np.any(_inside_convex(points, rectangle) & _inside_convex(points, polygon)))


def test_wrap_angle_range() -> None:
    assert wrap_angle(3.0 * math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(-0.5) == pytest.approx(-0.5)
    assert wrap_angle(2.0 * math.pi + 0.25) == pytest.approx(0.25)


def test_convex_hull_drops_inner_and_collinear_points() -> None:
    points = np.array([[0, 0], [1, 0], [2, 0], [2, 2], [0, 2], [1, 1], [1, 2]], dtype=float)
    hull = convex_hull(points)
    assert len(hull) == 4
    assert {tuple(p) for p in hull} == {(0, 0), (2, 0), (2, 2), (0, 2)}


def test_separating_axis_test_agrees_with_sampling() -> None:
    rng = np.random.default_rng(7)
    disagreements = 0
    for _ in range(100):
        obstacle = Obstacle.hull("random", rng.uniform(-0.5, 0.5, size=(7, 2)))
        x, y = rng.uniform(-0.8, 0.8, size=2)
        yaw = rng.uniform(-math.pi, math.pi)
        length, width = rng.uniform(0.05, 0.6, size=2)
        world = World((obstacle,))
        exact = bool(world.rectangles_collide(np.array([x]), np.array([y]), np.array([yaw]),
                                              length, width)[0])
        corners = rectangle_corners(np.array([x]), np.array([y]), np.array([yaw]),
                                    length / 2.0, width / 2.0)[0]
        sampled = _sampled_overlap(corners, obstacle.array)
        disagreements += exact != sampled
    # Sampling can miss a sliver of overlap thinner than its spacing: allow very few.
    assert disagreements <= 3


def test_batched_collisions_match_single_queries() -> None:
    wall = Obstacle.rectangle("wall", (1.0, 0.0), 0.3, 2.0, 0.1)
    post = Obstacle.rectangle("post", (-1.0, 0.5), 0.0, 0.1, 0.1)
    world = World((wall, post))
    rng = np.random.default_rng(3)
    x, y = rng.uniform(-2, 2, size=(2, 200))
    yaw = rng.uniform(-math.pi, math.pi, size=200)
    batch = world.rectangles_collide(x, y, yaw, 0.22, 0.13, 0.02)
    single = [bool(world.rectangles_collide(np.array([a]), np.array([b]), np.array([c]),
                                            0.22, 0.13, 0.02)[0]) for a, b, c in zip(x, y, yaw)]
    assert batch.tolist() == single
    assert batch.any() and not batch.all()


def test_touching_counts_as_collision_and_margin_grows_the_rectangle() -> None:
    world = World((Obstacle.rectangle("box", (0.0, 0.0), 0.0, 1.0, 1.0),))
    touching = world.rectangles_collide(np.array([1.0]), np.array([0.0]), np.array([0.0]),
                                        1.0, 1.0)
    apart = world.rectangles_collide(np.array([1.05]), np.array([0.0]), np.array([0.0]),
                                     1.0, 1.0)
    grown = world.rectangles_collide(np.array([1.05]), np.array([0.0]), np.array([0.0]),
                                     1.0, 1.0, margin=0.06)
    assert touching[0] and not apart[0] and grown[0]


def test_colliding_obstacles_are_named() -> None:
    world = World((Obstacle.rectangle("wall", (0.0, 0.0), 0.0, 1.0, 0.1),
                   Obstacle.rectangle("post", (5.0, 0.0), 0.0, 0.1, 0.1)))
    assert world.colliding_obstacles(0.2, 0.0, 0.0, 0.22, 0.13) == ("wall",)
    assert world.colliding_obstacles(3.0, 0.0, 0.0, 0.22, 0.13) == ()


def test_near_obstacles_never_claims_a_far_point() -> None:
    triangle = Obstacle("triangle", ((0.0, 0.0), (1.0, 0.0), (0.0, 0.3)))  # sharp corner
    world = World((triangle,))
    rng = np.random.default_rng(11)
    points = rng.uniform(-0.5, 1.5, size=(4000, 2))
    near = world.near_obstacles(points, 0.1)
    distance = _distance_to_polygon(points, triangle.array)
    assert np.all(distance[near] <= 0.1 + 1e-9)
    assert np.all(near[distance == 0.0])


def _distance_to_polygon(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Brute-force Euclidean distance from points to a convex polygon (0 inside)."""
    inside = _inside_convex(points, vertices)
    start, end = vertices, np.roll(vertices, -1, axis=0)
    edge = end - start
    t = np.clip(np.einsum("pki,ki->pk", points[:, None] - start, edge)
                / np.sum(edge * edge, axis=1), 0.0, 1.0)
    closest = start + t[..., None] * edge
    distance = np.min(np.hypot(*(points[:, None] - closest).transpose(2, 0, 1)), axis=1)
    return np.where(inside, 0.0, distance)


def test_distance_lower_bound_never_exceeds_the_distance() -> None:
    obstacle = Obstacle.hull("blob", np.array([[0, 0], [1, 0.2], [0.8, 1.0], [0.1, 0.7]]))
    world = World((obstacle,))
    rng = np.random.default_rng(5)
    points = rng.uniform(-2, 3, size=(300, 2))
    exact = _distance_to_polygon(points, obstacle.array)
    bounds = np.array([world.distance_lower_bound(x, y) for x, y in points])
    assert np.all(bounds <= exact + 1e-9)


def test_empty_world_collides_with_nothing() -> None:
    world = World()
    assert not world.rectangles_collide(np.zeros(3), np.zeros(3), np.zeros(3), 1.0, 1.0).any()
    assert world.distance_lower_bound(0.0, 0.0) == math.inf


@pytest.mark.parametrize("vertices", [
    ((0.0, 0.0), (1.0, 0.0)),                         # too few
    ((0.0, 0.0), (0.0, 1.0), (1.0, 0.0)),             # clockwise
    ((0.0, 0.0), (1.0, 0.0), (2.0, 0.0)),             # degenerate
    ((0.0, 0.0), (math.nan, 0.0), (0.0, 1.0)),        # not finite
])
def test_malformed_obstacles_are_rejected(vertices: tuple[tuple[float, float], ...]) -> None:
    with pytest.raises(FootstepPlannerError):
        Obstacle("bad", vertices)


def test_segment_obstacle_is_a_thin_rectangle() -> None:
    segment = Obstacle.segment("leaf", (0.0, 0.0), (1.0, 0.0), thickness=0.02)
    assert segment.array[:, 1].max() == pytest.approx(0.01)
    assert segment.array[:, 0].max() == pytest.approx(1.0)
