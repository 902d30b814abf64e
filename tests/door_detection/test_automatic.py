"""Automatic detection ([Banerjee 2015] Sec. III-A) on rendered scenes."""

from __future__ import annotations

import numpy as np
import pytest
from helpers_detection import angle_deg, handle_error

from door_contract.vocabulary import DetectionMode, DoorOpening, HingeSide, Side
from door_detection.automatic import detect_automatic
from door_detection.estimate import DetectionOutcome
from door_detection.options import DetectionOptions


def test_sim_door_at_two_metres_straight_on(straight_on) -> None:
    result = detect_automatic(straight_on.rgb, straight_on.depth, straight_on.intrinsics)
    assert result.outcome is DetectionOutcome.DETECTED, result.reason
    estimate = result.estimate
    assert handle_error(estimate.handle_position, straight_on.handle_position) < 0.02
    assert angle_deg(estimate.normal, straight_on.normal) < 2.0
    assert estimate.hinge_side is Side.LEFT
    assert estimate.mode is DetectionMode.AUTOMATIC
    assert 0.80 <= estimate.width <= 1.00
    assert 0.0 < estimate.confidence <= 1.0


def test_estimate_geometry_is_consistent(straight_on) -> None:
    estimate = detect_automatic(straight_on.rgb, straight_on.depth, straight_on.intrinsics).estimate
    assert estimate.normal @ -estimate.handle_position > 0          # faces the camera
    corners = estimate.corners
    assert corners[0, 0] < corners[1, 0] and corners[3, 0] < corners[2, 0]   # left before right
    assert corners[0, 1] > corners[3, 1]                             # bottom below top (y down)
    assert np.allclose((corners - corners.mean(axis=0)) @ estimate.normal, 0.0, atol=1e-6)
    pose = estimate.handle_pose()
    assert np.allclose(pose[:3, :3].T @ pose[:3, :3], np.eye(3), atol=1e-9)
    assert np.isclose(np.linalg.det(pose[:3, :3]), 1.0)
    assert angle_deg(pose[:3, 2], -straight_on.up) > 170             # z is the world's up …
    assert angle_deg(pose[:3, 2], straight_on.up) < 1.0              # … from the door's edges


def test_right_hinged_oblique_noisy_door(sim_scene) -> None:
    scene = sim_scene(3.0, -0.4, 0.003, Side.RIGHT)
    result = detect_automatic(scene.rgb, scene.depth, scene.intrinsics)
    assert result.ok, result.reason
    assert result.estimate.hinge_side is Side.RIGHT
    assert handle_error(result.estimate.handle_position, scene.handle_position) < 0.02
    assert angle_deg(result.estimate.normal, scene.normal) < 2.0


def test_hinge_side_prior_restricts_the_search(straight_on) -> None:
    wrong = detect_automatic(straight_on.rgb, straight_on.depth, straight_on.intrinsics,
                             hinge_side=Side.RIGHT)
    assert wrong.outcome is DetectionOutcome.NO_HANDLE
    right = detect_automatic(straight_on.rgb, straight_on.depth, straight_on.intrinsics,
                             hinge_side=Side.LEFT)
    assert right.ok


def test_independent_pybullet_scene(fixture_scene) -> None:
    result = detect_automatic(fixture_scene.rgb, fixture_scene.depth, fixture_scene.intrinsics)
    assert result.ok, result.reason
    assert handle_error(result.estimate.handle_position, fixture_scene.handle_position) < 0.02
    assert angle_deg(result.estimate.normal, fixture_scene.normal) < 2.0


def test_width_outside_the_range_is_no_door_pair(straight_on) -> None:
    narrow = DetectionOptions(door_width_min=0.3, door_width_max=0.6)
    result = detect_automatic(straight_on.rgb, straight_on.depth, straight_on.intrinsics, narrow)
    assert result.outcome is DetectionOutcome.NO_DOOR_PAIR
    assert "0.3–0.6 m" in result.reason


def test_a_blank_wall_has_no_lines(straight_on) -> None:
    wall = np.full_like(straight_on.rgb, 120)
    result = detect_automatic(wall, straight_on.depth, straight_on.intrinsics)
    assert result.outcome is DetectionOutcome.NO_VERTICAL_LINES


def test_a_flat_painted_door_without_depth_step_still_needs_a_plane(straight_on) -> None:
    """Scrambling the depth inside the door breaks the diagonal plane check."""
    depth = straight_on.depth.copy()
    rng = np.random.default_rng(1)
    depth[:, 380:640] = rng.uniform(1.0, 6.0, size=depth[:, 380:640].shape).astype(np.float32)
    result = detect_automatic(straight_on.rgb, depth, straight_on.intrinsics)
    assert result.outcome in (DetectionOutcome.NO_DOOR_PLANE, DetectionOutcome.NO_DOOR_PAIR)


def test_width_is_the_leafs_not_the_frames(sim_scene) -> None:
    """The leaf (0.914 m in a 0.922 m opening) sits inside 6 cm jambs: the pairs of the
    jambs' outer edges (1.04 m) and mixtures (0.98 m) are also door-like, and the
    innermost pair must win; the width comes from the ray-plane corners, not from the
    depth read a few pixels inside each edge."""
    for distance in (2.0, 2.5, 3.0):
        frame = sim_scene(distance, 0.0)
        result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
        assert result.outcome is DetectionOutcome.DETECTED, result.reason
        assert abs(result.estimate.width - 0.918) < 0.015, (distance, result.estimate.width)
        bottom_width = np.linalg.norm(result.estimate.corners[1] - result.estimate.corners[0])
        assert abs(bottom_width - result.estimate.width) < 0.02


@pytest.mark.parametrize("frame_colour", [(0.92, 0.92, 0.88), (1.0, 1.0, 1.0)])
def test_a_white_leaf_on_a_white_wall_renders_and_is_detected(frame_colour) -> None:
    """Issue 13's scene the sim used to refuse: a white leaf in a white wall (and a white or
    off-white frame), a dark-grey handle over a grey floor; the graph's 640×480 head camera
    at 2.5 m, 0.2 rad. Only the frame's side faces, the 4 mm gaps and depth show the door."""
    from door_sim_bridge.world import DoorConfig, DoorWorld, StanceConfig, WorldConfig

    white = (1.0, 1.0, 1.0)
    door = DoorConfig(door_colour=white, wall_colour=white, frame_colour=frame_colour,
                      handle_colour=(0.25, 0.25, 0.25), floor_colour=(0.3, 0.3, 0.3))
    with DoorWorld(WorldConfig(door=door, stance=StanceConfig(distance=2.5, yaw=0.2))) as world:
        frame, grasp, truth = world.render(), world.handle_grasp_pose(), world.door_ground_truth()
    leaf_and_wall = np.array([[0.0, 0.1, 1.6], [0.0, 0.9, 1.6]])           # odom, on the plane x = 0
    rotation, origin = frame.camera_pose[:3, :3], frame.camera_pose[:3, 3]
    pixels = np.rint(frame.intrinsics.project((leaf_and_wall - origin) @ rotation)).astype(int)
    leaf, wall = (frame.rgb[v, u].astype(int) for u, v in pixels)
    assert np.array_equal(leaf, wall) and leaf.min() > 150               # one light tone
    result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
    assert result.ok, result.reason
    in_odom = result.estimate.transformed(frame.camera_pose)
    assert handle_error(in_odom.handle_position, grasp[:3, 3]) < 0.02
    assert angle_deg(in_odom.normal, truth.normal) < 2.0
    assert abs(in_odom.width - door.width) < 0.01


@pytest.mark.parametrize("width", [0.80, 0.84, 1.00])
def test_narrow_and_wide_leaves_are_measured_within_a_centimetre(width) -> None:
    """Issue 13: 0.80 and 0.84 m leaves came out 0.865 and 0.908 m (a leaf edge paired with a
    jamb's outer edge, the leaf pair having failed the 0.80 m gate); the graph's camera from
    2–3 m, straight and at 0.3 rad, where the image rows are not level on the door."""
    from door_sim_bridge.world import DoorConfig, DoorWorld, StanceConfig, WorldConfig

    for distance, yaw in ((2.0, 0.0), (3.0, 0.0), (2.5, 0.3)):
        with DoorWorld(WorldConfig(door=DoorConfig(width=width),
                                   stance=StanceConfig(distance=distance, yaw=yaw))) as world:
            frame, grasp = world.render(), world.handle_grasp_pose()
        result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
        assert result.ok, (distance, yaw, result.reason)
        assert abs(result.estimate.width - width) < 0.01, (distance, yaw, result.estimate.width)
        in_odom = result.estimate.transformed(frame.camera_pose)
        assert handle_error(in_odom.handle_position, grasp[:3, 3]) < 0.02


def test_a_faint_edge_seen_in_part_still_bounds_the_handle_search() -> None:
    """Table II start 209 (white leaf, frame and wall, σ = 1.9 cm at 2 m), the head turned
    0.6 rad right: the far jamb's faint line is found only above the handle; the handle is
    searched again on the rows the other edge spans, and found."""
    from door_evaluation.detection.trial_scenes import Appearance, TrialScene, world_config
    from door_sim_bridge.world import DoorWorld

    white = (1.0, 1.0, 1.0)
    look = Appearance(white, white, (0.85, 0.7, 0.15), white, (0.15, 0.15, 0.15), (-0.2857, 0.3862, 0.8771))
    scene = TrialScene(2.0, 0.6, -0.2654, 0.9036, 0.8805, DoorOpening.PUSH, HingeSide.RIGHT, 0.00476, look, 209)
    with DoorWorld(world_config(scene)) as world:
        world.set_joint_targets({"head_2_joint": -0.6})
        world.step(480)
        frame, grasp = world.render(), world.handle_grasp_pose()
    result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
    assert result.ok, result.reason
    in_odom = result.estimate.transformed(frame.camera_pose)
    assert handle_error(in_odom.handle_position, grasp[:3, 3]) < 0.02


def test_a_jamb_the_colour_of_the_leaf_is_cut_off_by_depth() -> None:
    """Table II start 31: a white leaf in a white frame 1 m away; one leaf edge does not show,
    so the pair is a leaf edge and the far side of a jamb (6.8 cm too wide). The jamb stands
    1 cm proud of the leaf: the edge moves inward past it."""
    from door_evaluation.detection.trial_scenes import Appearance, TrialScene, world_config
    from door_sim_bridge.world import DoorWorld

    white = (1.0, 1.0, 1.0)
    look = Appearance(white, white, (0.85, 0.7, 0.15), (0.45, 0.58, 0.72), (0.6, 0.5, 0.38), (-0.4025, -0.4411, 0.8021))
    scene = TrialScene(1.0, 0.0, 0.1036, 0.8245, 1.0834, DoorOpening.PUSH, HingeSide.LEFT, 0.0041, look, 31)
    with DoorWorld(world_config(scene)) as world:
        frame, grasp = world.render(), world.handle_grasp_pose()
    result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
    assert result.ok, result.reason
    assert abs(result.estimate.width - scene.width) < 0.01, result.estimate.width
    assert handle_error(result.estimate.transformed(frame.camera_pose).handle_position, grasp[:3, 3]) < 0.02
