"""Sub-pixel door edges from the colour profile across them (door_detection.edges)."""

from __future__ import annotations

import numpy as np

from door_detection.edges import refine_edge
from door_detection.lines import VerticalLines

LEAF, FRAME = (110, 65, 35), (200, 200, 190)


def _image(last_leaf_column: int, leaf_on_right: bool = False) -> np.ndarray:
    """A leaf up to ``last_leaf_column`` (inclusive) and frame beyond it, or mirrored."""
    image = np.empty((200, 300, 3), np.uint8)
    image[:] = FRAME
    if leaf_on_right:
        image[:, last_leaf_column:] = LEAF
    else:
        image[:, : last_leaf_column + 1] = LEAF
    return image


def test_the_edge_moves_from_the_hough_line_to_between_the_leaf_and_the_frame() -> None:
    lines = VerticalLines(np.array([[152.0, 20.0, 152.0, 180.0]]))     # 2 px outside the leaf
    refined = refine_edge(_image(150), lines, 0, inside=-1)            # leaf on the line's left
    assert refined is not None
    np.testing.assert_allclose(refined[[0, 2]], 150.5, atol=1e-6)      # between columns 150 and 151
    np.testing.assert_allclose(refined[[1, 3]], [20.0, 180.0])
    mirrored = refine_edge(_image(120, leaf_on_right=True), VerticalLines(np.array([[118.0, 20.0, 118.0, 180.0]])),
                           0, inside=1)
    np.testing.assert_allclose(mirrored[[0, 2]], 119.5, atol=1e-6)


def test_a_tilted_edge_keeps_its_slope() -> None:
    image = np.empty((200, 300, 3), np.uint8)
    image[:] = FRAME
    rows = np.arange(200)
    edge = 100.0 + 0.1 * rows                                            # x of the leaf's end per row
    image[np.arange(300)[None, :] <= edge[:, None]] = LEAF
    lines = VerticalLines(np.array([[102.0, 0.0, 122.0, 199.0]]))
    refined = refine_edge(image, lines, 0, inside=-1)
    slope = (refined[2] - refined[0]) / (refined[3] - refined[1])
    assert abs(slope - 0.1) < 0.01
    assert abs(refined[0] - 100.5) < 0.6 and abs(refined[2] - (100.5 + 19.9)) < 0.6


def test_without_contrast_the_hough_line_is_kept() -> None:
    flat = np.full((200, 300, 3), 180, np.uint8)
    assert refine_edge(flat, VerticalLines(np.array([[150.0, 20.0, 150.0, 180.0]])), 0, inside=1) is None


def test_contrast_limited_equalisation_keeps_a_small_step_next_to_a_dominant_grey() -> None:
    """A white scene (one grey, 179, almost everywhere) with a lit jamb face (190): plain
    equalisation sends both to the top (254, 255); the contrast-limited one keeps a step."""
    from door_detection.options import DetectionOptions
    from door_detection.preprocessing import equalise_luma

    luma = np.full((200, 300), 179, np.uint8)
    luma[:, 150] = 190
    luma[:, 200] = 153
    plain = equalise_luma(luma, 0.0)
    assert int(plain[0, 150]) - int(plain[0, 0]) <= 1
    limited = equalise_luma(luma, DetectionOptions().histogram_clip_limit)
    assert int(limited[0, 150]) - int(limited[0, 0]) >= 10
    assert int(limited[0, 0]) - int(limited[0, 200]) >= 20


def test_a_jamb_is_not_measured_where_the_rays_miss_the_plane_and_the_strip_stays_in_the_image():
    """Seen edge-on, the edge's rays meet the plane behind the camera, or so far away that the
    strip would have been millions of pixels wide (the detector once ran out of memory)."""
    from door_contract.converters.camera_info import CameraIntrinsics
    from door_detection.jambs import _jamb_width
    from door_detection.plane import Plane

    intrinsics = CameraIntrinsics(640, 480, 500.0, 500.0, 320.0, 240.0)
    depth = np.full((480, 640), 2.0)
    rows = np.linspace(100.0, 300.0, 50)
    axis = np.array([1.0, 0.0, 0.0])
    behind = np.column_stack([np.zeros(50), np.zeros(50), np.full(50, -1.0)])
    plane = Plane(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]))
    assert _jamb_width(behind, axis, rows, np.full(50, 320.0), 1, plane, depth, intrinsics, 0.1) == 0.0
    grazing = np.column_stack([np.zeros(50), np.zeros(50), np.full(50, 0.1 + 1e-7)])
    plane = Plane(np.array([0.0, 0.0, 2.0]), np.array([0.0, 0.0, 1.0]))
    assert _jamb_width(grazing, axis, rows, np.full(50, 320.0), 1, plane, depth, intrinsics, 0.1) == 0.0
