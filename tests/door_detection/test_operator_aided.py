"""Operator-aided detection from a scribble (seed 001 Sec. III-B)."""

from __future__ import annotations

import numpy as np

from door_detection.estimate import DetectionMode, DetectionOutcome, Side
from door_detection.operator_aided import detect_from_scribble
from helpers_detection import angle_deg, handle_error


def test_scribble_at_three_and_a_half_metres(sim_scene) -> None:
    scene = sim_scene(3.5, 0.2, 0.003)
    result = detect_from_scribble(scene.rgb, scene.depth, scene.intrinsics, scene.scribble,
                                  hinge_side=Side.LEFT, up=scene.up)
    assert result.outcome is DetectionOutcome.DETECTED, result.reason
    estimate = result.estimate
    assert handle_error(estimate.handle_position, scene.handle_position) < 0.02
    assert angle_deg(estimate.normal, scene.normal) < 2.0
    assert estimate.mode is DetectionMode.OPERATOR
    assert np.isnan(estimate.width) and np.isnan(estimate.corners).all()


def test_hinge_side_is_guessed_from_colour(sim_scene) -> None:
    scene = sim_scene(2.0, 0.0, 0.0, Side.RIGHT)
    result = detect_from_scribble(scene.rgb, scene.depth, scene.intrinsics, scene.scribble, up=scene.up)
    assert result.ok, result.reason
    assert result.estimate.hinge_side is Side.RIGHT
    assert handle_error(result.estimate.handle_position, scene.handle_position) < 0.02


def test_a_rough_polyline_scribble(straight_on) -> None:
    """An operator's drag along the lever (two points) instead of a polygon."""
    centre = straight_on.scribble.mean(axis=0)
    line = np.array([centre - [8.0, 0.0], centre + [8.0, 0.0]])
    result = detect_from_scribble(straight_on.rgb, straight_on.depth, straight_on.intrinsics, line,
                                  hinge_side=Side.LEFT, up=straight_on.up)
    assert result.ok, result.reason
    assert handle_error(result.estimate.handle_position, straight_on.handle_position) < 0.03
    assert angle_deg(result.estimate.normal, straight_on.normal) < 2.0


def test_independent_pybullet_scene(fixture_scene) -> None:
    result = detect_from_scribble(fixture_scene.rgb, fixture_scene.depth, fixture_scene.intrinsics,
                                  fixture_scene.handle_polygon, hinge_side=Side.LEFT)
    assert result.ok, result.reason
    assert handle_error(result.estimate.handle_position, fixture_scene.handle_position) < 0.02
    assert angle_deg(result.estimate.normal, fixture_scene.normal) < 2.0
