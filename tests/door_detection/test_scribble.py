"""A scribble is checked once, on arrival, against the image size."""

import numpy as np
import pytest

from door_detection.scribble import MAX_SCRIBBLE_POINTS, scribble_problem


@pytest.mark.parametrize("points, size, why", [
    ([[1e6, 1e6]], (640, 480), "outside the 640×480 image"),
    ([[-1.0, 10.0], [10.0, 10.0]], (640, 480), "1 of its 2 points"),
    ([[np.nan, 1.0]], (640, 480), "NaN"),
    ([[np.inf, 1.0]], (640, 480), "NaN or infinity"),
    (np.zeros((0, 2)), (640, 480), "0 point(s)"),
    (np.ones((MAX_SCRIBBLE_POINTS + 1, 2)), (640, 480), "at most"),
    ([[10.0, 10.0]], (None, None), "no camera image"),
])
def test_bad_scribbles_are_named(points, size, why):
    assert why in scribble_problem(np.asarray(points, dtype=float).reshape(-1, 2), *size)


def test_a_scribble_on_the_image_is_accepted():
    assert scribble_problem(np.array([[0.0, 0.0], [639.0, 479.0], [320.5, 240.2]]), 640, 480) is None
