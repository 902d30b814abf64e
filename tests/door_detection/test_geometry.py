"""The geometric building blocks: RANSAC line, plane refinement, noise, line merging, pairing."""

from __future__ import annotations

import numpy as np

from door_detection.door_pairs import pair_lines
from door_detection.lines import VerticalLines, merge_collinear
from door_detection.options import DetectionOptions
from door_detection.plane import Plane, depth_noise, fit_plane, ransac_line, refine_plane


def test_ransac_line_ignores_outliers() -> None:
    rng = np.random.default_rng(0)
    t = np.linspace(-1.0, 1.0, 120)[:, None]
    points = np.array([0.4, 0.0, 2.5]) + t * np.array([0.0, 1.0, 0.05]) / np.linalg.norm([0, 1, 0.05])
    points += rng.normal(scale=0.005, size=points.shape)
    points[::6] += rng.uniform(-1.0, 1.0, size=points[::6].shape)        # 17 % outliers
    line = ransac_line(points, 0.02, 40, np.random.default_rng(1))
    assert line is not None and line.inlier_fraction > 0.8
    assert abs(abs(line.direction @ np.array([0.0, 1.0, 0.05]) / np.linalg.norm([0, 1, 0.05])) - 1) < 1e-3


def test_refine_plane_is_robust_and_keeps_orientation() -> None:
    rng = np.random.default_rng(2)
    uv = rng.uniform(-0.45, 0.45, size=(2000, 2))
    points = np.column_stack([uv[:, 0], uv[:, 1], 3.0 + 0.2 * uv[:, 0]])
    points[:, 2] += rng.normal(scale=0.04, size=len(points))               # 4 cm stereo noise
    points[:100, 2] -= 0.3                                                 # a handle in front
    truth = np.array([-0.2, 0.0, 1.0]) / np.linalg.norm([-0.2, 0.0, 1.0])
    start = Plane(np.array([0.0, 0.0, 3.0]), np.array([0.0, 0.0, -1.0]))
    plane, fraction = refine_plane(points, start, 0.05)
    assert plane.normal[2] < 0                                              # orientation kept
    assert np.degrees(np.arccos(abs(plane.normal @ truth))) < 0.5
    assert 0.6 < fraction < 0.95
    assert abs(fit_plane(points[100:]).normal @ truth) > 0.999


def test_depth_noise_ignores_a_slant_and_measures_the_noise() -> None:
    rng = np.random.default_rng(3)
    z = np.linspace(2.0, 3.0, 400) + rng.normal(scale=0.03, size=400)
    points = np.column_stack([np.zeros(400), np.zeros(400), z])
    assert 0.025 < depth_noise(points) < 0.035


def test_ray_plane_intersection() -> None:
    plane = Plane(np.array([0.0, 0.0, 2.0]), np.array([0.0, 0.0, -1.0]))
    hits = plane.intersect_rays(np.array([[0.1, 0.2, 1.0], [1.0, 0.0, 0.0]]))
    assert np.allclose(hits[0], [0.2, 0.4, 2.0]) and np.isnan(hits[1]).all()


def test_fragments_of_an_edge_are_merged() -> None:
    lines = VerticalLines(np.array([[100.0, 0.0, 105.0, 200.0], [105.5, 220.0, 110.0, 400.0],
                                    [300.0, 0.0, 300.0, 400.0]]))
    merged = merge_collinear(lines, DetectionOptions())
    assert len(merged) == 2
    longest = merged.segments[np.argmax(merged.lengths)]
    assert longest[1] == 0.0 and longest[3] == 400.0


def test_pairs_closer_than_sixty_pixels_are_dropped() -> None:
    lines = VerticalLines(np.array([[100.0, 0.0, 100.0, 400.0], [150.0, 0.0, 150.0, 400.0],
                                    [400.0, 0.0, 400.0, 400.0], [700.0, 350.0, 700.0, 500.0]]))
    pairs = {tuple(p) for p in pair_lines(lines, DetectionOptions()).tolist()}
    assert pairs == {(0, 2), (1, 2)}         # (0, 1) is 50 px apart; line 3 barely overlaps


def test_an_unresolved_bar_leans_on_the_stand_off_prior() -> None:
    """A bar two or three pixels high: its pixels' median (4 cm, precise) is pulled by the
    rose; the segmentation error moves the fused stand-off most of the way to the prior."""
    from door_detection.grasp import fused_standoff

    options = DetectionOptions()
    measured = np.full(40, 0.040) + np.linspace(-1e-3, 1e-3, 40)
    assert abs(fused_standoff(measured, options) - 0.040) < 1e-3
    leaned = fused_standoff(measured, options, segmentation_sigma=0.026)
    assert 0.055 < leaned < options.handle_standoff_prior
