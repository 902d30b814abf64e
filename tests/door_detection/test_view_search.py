"""Active perception: the neck from the URDF, the view plan, when to move on, and the
search on the sim core reaching a confirmed door that started partly out of view."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers_detection import angle_deg, handle_error

from door_contract.vocabulary import DetectionMode
from door_detection.errors import DetectionError
from door_detection.view_search import (
    Neck,
    NeckAxis,
    SearchStep,
    View,
    ViewSearch,
    ViewSearchOptions,
    head_move_time,
    pan_step_for,
    plan_views,
)

TALOS_LIKE = Neck(NeckAxis("pan", -1.309, 1.309, 1.0), NeckAxis("tilt", -0.262, 0.785, 1.0))


@pytest.fixture(scope="module")
def talos_kinematics():
    from door_robot.kinematics import RobotKinematics
    from door_robot.profile import load_profile

    return RobotKinematics(load_profile("talos"))


def test_the_talos_neck_is_found_in_the_urdf_and_its_signs_look_left_and_down(talos_kinematics) -> None:
    from door_detection.neck import neck_of

    neck = neck_of(talos_kinematics)
    assert (neck.pan.joint, neck.tilt.joint) == ("head_2_joint", "head_1_joint")
    assert (neck.pan.lower, neck.pan.upper) == pytest.approx((-1.309, 1.309), abs=1e-3)
    assert (neck.tilt.lower, neck.tilt.upper) == pytest.approx((-0.2618, 0.7854), abs=1e-3)
    assert neck.pan.velocity == neck.tilt.velocity == 1.0
    assert head_move_time(neck, View(0.0, 0.3), View(-0.9, 0.6)) == pytest.approx(0.9)
    frame = talos_kinematics.profile.head_camera_frame
    q0 = talos_kinematics.walking_q
    forward = talos_kinematics.frame_pose(q0, frame)[:3, 2]                # optical z
    for axis, look, check in ((neck.pan, 0.3, lambda z: z[1] > forward[1] + 0.2),     # left: +y
                              (neck.tilt, 0.3, lambda z: z[2] < forward[2] - 0.2)):   # down: −z
        q = q0.copy()
        q[talos_kinematics.joint_indices([axis.joint])[0]] = axis.joint_angle(look)
        assert check(talos_kinematics.frame_pose(q, frame)[:3, 2]), axis.joint


def test_a_neck_without_pan_is_found_too(shared_data) -> None:
    from door_detection.neck import neck_of
    from door_robot.kinematics import RobotKinematics
    from door_robot.profile import load_profile

    neck = neck_of(RobotKinematics(load_profile("atlas_v4")))
    assert neck.pan is None and neck.tilt.joint == "neck_ry"


def test_views_sweep_the_pan_alternately_then_tilt_then_turn_the_body() -> None:
    options = ViewSearchOptions(pan_step=0.45, max_pan=1.2, tilt_offsets=(0.3,), body_turn_step=0.8, max_body_turns=1)
    views = plan_views(TALOS_LIKE, View(0.0, 0.3), options)
    pans = [0.0, 0.45, -0.45, 0.9, -0.9]
    assert [v.pan for v in views[:5]] == pytest.approx(pans) and all(v.tilt == 0.3 for v in views[:5])
    assert [v.pan for v in views[5:10]] == pytest.approx(pans) and all(v.tilt == pytest.approx(0.6) for v in views[5:10])
    assert [v.body_yaw for v in views[10:]] == [0.8] * 5 + [-0.8] * 5
    assert len(views) == 20
    targets = views[3].joint_targets(TALOS_LIKE)
    assert targets == pytest.approx({"pan": 0.9, "tilt": 0.3})


def test_limits_clip_the_plan_and_a_missing_pan_leaves_body_turns() -> None:
    narrow = Neck(NeckAxis("pan", -0.5, 0.5, -1.0), NeckAxis("tilt", -0.2, 0.4, 1.0))
    views = plan_views(narrow, View(0.0, 0.3), ViewSearchOptions(pan_step=0.45, max_body_turns=0))
    assert [v.pan for v in views] == pytest.approx([0.0, 0.45, -0.45] * 2)
    assert views[3].tilt == pytest.approx(0.4)                            # 0.3 + 0.3 clipped to the limit
    assert View(0.45, 0.3).joint_targets(narrow) == pytest.approx({"pan": -0.45, "tilt": 0.3})
    assert View(0.9, 0.3).joint_targets(narrow)["pan"] == pytest.approx(-0.5)
    headless = plan_views(Neck(None, None), View(0.0, 0.0), ViewSearchOptions(max_body_turns=2, body_turn_step=0.7))
    assert [v.body_yaw for v in headless] == pytest.approx([0.0, 0.7, -0.7, 1.4, -1.4])


def test_a_view_is_left_after_empty_frames_or_unconfirmed_ones_and_the_search_ends() -> None:
    search = ViewSearch((View(0.0, 0.3), View(0.45, 0.3)), ViewSearchOptions(empty_frames_per_view=2,
                                                                               frames_per_view=4))
    assert search.after_frame(detected=False, confirmed=False) is SearchStep.STAY
    assert search.after_frame(detected=False, confirmed=False) is SearchStep.MOVE
    assert search.view == View(0.45, 0.3)
    steps = [search.after_frame(detected=True, confirmed=False) for _ in range(4)]   # estimates, no vote
    assert steps == [SearchStep.STAY] * 3 + [SearchStep.EXHAUSTED] and search.view is None
    fresh = ViewSearch((View(0.0, 0.3),))
    assert fresh.after_frame(detected=True, confirmed=True) is SearchStep.CONFIRMED


def test_bad_search_options_are_refused() -> None:
    with pytest.raises(DetectionError, match="empty_frames_per_view = 0"):
        ViewSearchOptions(empty_frames_per_view=0)
    with pytest.raises(DetectionError, match="pan_step"):
        ViewSearchOptions(pan_step=0.0)
    with pytest.raises(DetectionError, match="needs at least one view"):
        ViewSearch(())
    with pytest.raises(DetectionError, match="never fits"):
        pan_step_for(1.31, 1.4)
    assert pan_step_for(1.31, 0.86) == pytest.approx(0.45)


@pytest.mark.parametrize("distance, yaw, lateral", [(3.6, 0.55, 0.0), (1.1, -0.45, 0.0), (1.0, 0.0, -0.4)])
def test_a_door_edge_out_of_view_at_the_start_is_found_by_the_search(talos_kinematics, distance, yaw,
                                                                     lateral) -> None:
    """Issue 13's three starts (the graph's 640×480 camera): the first frame cannot see the
    door whole; the search turns the head and confirms it within 2 cm / 2° in odom."""
    from door_detection.automatic import detect_automatic
    from door_detection.neck import neck_of
    from door_evaluation.detection.search_trial import run_search
    from door_evaluation.detection.trial_scenes import TrialScene, world_config
    from door_sim_bridge.world import DoorWorld

    neck = neck_of(talos_kinematics)
    with DoorWorld(world_config(TrialScene(distance, yaw, lateral))) as world:
        first = world.render()
        assert not detect_automatic(first.rgb, first.depth, first.intrinsics).ok
        outcome = run_search(world, neck, DetectionMode.AUTOMATIC)
        grasp, truth = world.handle_grasp_pose(), world.door_ground_truth()
        head = world.joint_positions()[neck.pan.joint]
    assert outcome.estimate is not None and outcome.views > 1
    assert abs(head) >= 0.3 - 1e-3                                          # the head did turn
    assert handle_error(outcome.estimate.handle_position, grasp[:3, 3]) < 0.02
    assert angle_deg(outcome.estimate.normal, truth.normal) < 2.0
    assert abs(outcome.estimate.width - truth.width) < 0.01
    assert outcome.sim_time < 10.0 and math.isfinite(outcome.sim_time)


def test_a_door_in_view_is_confirmed_from_two_frames_half_a_second_apart(talos_kinematics) -> None:
    from door_detection.neck import neck_of
    from door_evaluation.detection.search_trial import SearchSettings, run_search
    from door_evaluation.detection.trial_scenes import TrialScene, world_config
    from door_sim_bridge.world import DoorWorld

    with DoorWorld(world_config(TrialScene(2.5, 0.1, 0.1))) as world:
        outcome = run_search(world, neck_of(talos_kinematics), DetectionMode.OPERATOR,
                             settings=SearchSettings(camera_rate=2.0))
        grasp = world.handle_grasp_pose()
    assert (outcome.frames, outcome.views) == (2, 1) and outcome.sim_time == pytest.approx(0.5)
    assert outcome.estimate.mode is DetectionMode.OPERATOR
    assert handle_error(outcome.estimate.handle_position, grasp[:3, 3]) < 0.02
    assert np.isnan(outcome.estimate.width)


def test_without_a_pan_joint_the_body_turns_in_place(talos_kinematics) -> None:
    """A neck that only tilts (Atlas v4's): the search turns the body, left first, then right,
    and confirms the door 0.9 rad to the right."""
    from door_detection.neck import neck_of
    from door_evaluation.detection.search_trial import run_search
    from door_evaluation.detection.trial_scenes import TrialScene, world_config
    from door_sim_bridge.world import DoorWorld

    tilt_only = Neck(None, neck_of(talos_kinematics).tilt)
    with DoorWorld(world_config(TrialScene(2.5, 0.9))) as world:
        outcome = run_search(world, tilt_only, search_options=ViewSearchOptions(body_turn_step=0.6))
        base, grasp = world.base_pose(), world.handle_grasp_pose()
    assert outcome.estimate is not None and outcome.views == 4          # home, tilted, left, right
    assert math.atan2(base[1, 0], base[0, 0]) == pytest.approx(0.3)
    assert handle_error(outcome.estimate.handle_position, grasp[:3, 3]) < 0.02
