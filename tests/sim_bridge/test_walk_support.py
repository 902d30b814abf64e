"""The soles' support polygon (door_sim_bridge.walking.support): where a walk starts from, and the
run summary's CoM margin. Pure geometry."""

from __future__ import annotations

import math

import numpy as np
import pytest

from door_sim_bridge.walking.support import into_polygon, signed_margin, support_polygon

LENGTH, WIDTH, MARGIN = 0.22, 0.14, 0.02


def sole(x: float, y: float, yaw: float = 0.0) -> np.ndarray:
    frame = np.eye(4)
    frame[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    frame[:2, 3] = (x, y)
    return frame


FEET = (sole(0.0, 0.1), sole(0.0, -0.1))


def test_the_polygon_is_the_shrunk_soles_hull():
    polygon = support_polygon(FEET, LENGTH, WIDTH, MARGIN)
    assert polygon[:, 0].max() == pytest.approx(LENGTH / 2 - MARGIN)
    assert polygon[:, 1].max() == pytest.approx(0.1 + WIDTH / 2 - MARGIN)
    edges = np.roll(polygon, -1, axis=0) - polygon
    following = np.roll(edges, -1, axis=0)
    turns = edges[:, 0] * following[:, 1] - edges[:, 1] * following[:, 0]
    assert np.all(turns > 0.0)  # convex, counter-clockwise


def test_a_point_inside_stays_where_it_is():
    polygon = support_polygon(FEET, LENGTH, WIDTH, MARGIN)
    assert np.array_equal(into_polygon(np.array([0.03, -0.05]), polygon), [0.03, -0.05])


@pytest.mark.parametrize("point, expected", [
    ((0.104, 0.017), (LENGTH / 2 - MARGIN, 0.017)),  # the Monte-Carlo's leaning CoM: onto the front edge
    ((-0.3, 0.0), (-(LENGTH / 2 - MARGIN), 0.0)),
    ((0.0, 0.5), (0.0, 0.1 + WIDTH / 2 - MARGIN)),
])
def test_a_point_outside_goes_to_the_nearest_point_of_the_boundary(point, expected):
    polygon = support_polygon(FEET, LENGTH, WIDTH, MARGIN)
    assert into_polygon(np.array(point), polygon) == pytest.approx(expected)


def test_staggered_turned_soles():
    """One sole ahead and turned: the hull takes both rectangles' corners as they stand."""
    feet = (sole(0.15, 0.1, math.radians(30.0)), sole(0.0, -0.1))
    polygon = support_polygon(feet, LENGTH, WIDTH, MARGIN)
    front = into_polygon(np.array([1.0, 0.1]), polygon)
    assert front[0] > 0.15 + 0.5 * (LENGTH / 2 - MARGIN)  # reaches out to the leading sole's toe
    assert np.allclose(into_polygon(front, polygon), front)  # on the boundary: stays


def test_signed_margin_is_the_distance_to_the_edge_positive_inside():
    feet = (sole(-1.0, 0.085), sole(-1.0, -0.085))
    polygon = support_polygon(feet, 0.22, 0.13)
    assert sorted(polygon[:, 0]) == pytest.approx([-1.11, -1.11, -0.89, -0.89])
    assert signed_margin(np.array([-1.0, 0.0]), polygon) == pytest.approx(0.11)  # 11 cm to the toe and heel
    assert signed_margin(np.array([-1.0, 0.25]), polygon) == pytest.approx(-(0.25 - 0.15))
    assert signed_margin(np.array([-0.79, 0.25]), polygon) == pytest.approx(-math.hypot(0.1, 0.1))
