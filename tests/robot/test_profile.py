"""Robot profiles: the head camera's optical axes (``head_camera_axes``) are read and checked."""

import numpy as np
import pytest
import yaml

from door_contract.vocabulary import DoorOpening, WalkGoal
from door_robot.crouch import CrouchRules, LowLeverCrouch, PassageCrouch, walking_height
from door_robot.errors import RobotModelError
from door_robot.locations import params_dir
from door_robot.profile import CameraAxes, load_profile


def _profile_with_axes(tmp_path, axes) -> str:
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    if axes is None:
        document.pop("head_camera_axes")
    else:
        document["head_camera_axes"] = axes
    path = tmp_path / "robot_g1_variant.yaml"
    path.write_text(yaml.safe_dump(document))
    return str(path)


def test_g1_camera_looks_along_its_link_x_with_z_up():
    axes = load_profile("g1").head_camera_axes
    assert axes == CameraAxes(forward=(1.0, 0.0, 0.0), down=(0.0, 0.0, -1.0))
    assert axes.right == (0.0, -1.0, 0.0)  # optical x = y × z: the link's -y, to the right


@pytest.mark.parametrize("forward, down", [("x", "-z"), ("-y", "z"), ("+z", "x"), ("-x", "-y")])
def test_the_optical_frame_is_right_handed(forward, down):
    axes = CameraAxes.from_document({"forward": forward, "down": down})
    rotation = np.column_stack([axes.right, axes.down, axes.forward])
    assert np.linalg.det(rotation) == pytest.approx(1.0)
    np.testing.assert_allclose(rotation.T @ rotation, np.eye(3))


def test_a_profile_without_axes_leaves_them_to_the_simulator(tmp_path):
    assert load_profile(_profile_with_axes(tmp_path, None)).head_camera_axes is None


@pytest.mark.parametrize("axes, message", [
    ({"forward": "x", "down": "x"}, "different frame axes"),
    ({"forward": "x", "down": "-x"}, "different frame axes"),
    ({"forward": "w", "down": "z"}, "expected x, y or z"),
    ({"forward": "x"}, "exactly 'forward' and 'down'"),
    ({"forward": "x", "down": "-z", "up": "z"}, "exactly 'forward' and 'down'"),
    ("x", "must be a mapping"),
])
def test_bad_axes_are_refused_naming_the_field(tmp_path, axes, message):
    with pytest.raises(RobotModelError, match=message):
        load_profile(_profile_with_axes(tmp_path, axes))


def test_axes_that_are_not_signed_frame_axes_are_refused():
    with pytest.raises(RobotModelError, match="signed frame axis"):
        CameraAxes(forward=(0.6, 0.8, 0.0), down=(0.0, 0.0, -1.0))


def test_talos_grasps_as_the_motion_library_always_did():
    """Fingers (TCP −z) into the door, closing along y held vertical: x_tcp = y_G, y_tcp = z_G, z_tcp = x_G."""
    for arm in load_profile("talos").arms.values():
        np.testing.assert_array_equal(arm.grasp_axes.rotation_in_grasp(),
                                      np.column_stack([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]))


def test_grasp_axes_are_required_and_checked(tmp_path):
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    document["arms"]["left"]["grasp_axes"] = {"into_door": "y", "up": "-y"}
    path = tmp_path / "robot_bad_grasp.yaml"
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(RobotModelError, match="grasp_axes: into_door .* different frame axes"):
        load_profile(str(path))
    del document["arms"]["left"]["grasp_axes"]
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(RobotModelError, match="incomplete: 'grasp_axes'"):
        load_profile(str(path))


def test_a_hand_beside_the_door_holds_the_lever_as_its_profile_says():
    """G1 turns the lever fingers-down beside a push door (``grasp_axes_beside``) and
    fingers-up facing one; a profile without it (TALOS) holds it one way."""
    for arm in load_profile("g1").arms.values():
        assert arm.grasp_axes_for(beside=False) == arm.grasp_axes
        beside = arm.grasp_axes_for(beside=True)
        assert beside.into_door == arm.grasp_axes.into_door and beside.up == tuple(-v for v in arm.grasp_axes.up)
    for arm in load_profile("talos").arms.values():
        assert arm.grasp_axes_beside is None and arm.grasp_axes_for(beside=True) == arm.grasp_axes


def test_stance_sets_the_robots_stand_distances_and_is_checked(tmp_path):
    assert load_profile("g1").stance == {"push_side_reach": 0.42, "stand_reach_pull": 0.45}
    assert load_profile("talos").stance == {}
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    path = tmp_path / "robot_bad_stance.yaml"
    for stance, message in (({"stand_reach_push": 0.4}, r"unknown field\(s\) \['stand_reach_push'\]"),
                            ({"stand_reach": -0.4}, "positive and finite"),
                            ({"stand_reach": float("nan")}, "positive and finite")):
        document["stance"] = stance
        path.write_text(yaml.safe_dump(document))
        with pytest.raises(RobotModelError, match=message):
            load_profile(str(path))


@pytest.mark.parametrize("axes, message", [({"into_door": "y", "up": "w"}, r"grasp_axes_beside\.up = 'w'"),
                                           ({"into_door": "y"}, "grasp_axes_beside needs exactly"),
                                           ({"into_door": "y", "up": "-y"}, "different frame axes")])
def test_a_bad_beside_grasp_is_refused(tmp_path, axes, message):
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    document["arms"]["right"]["grasp_axes_beside"] = axes
    path = tmp_path / "robot_bad_beside.yaml"
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(RobotModelError, match=message):
        load_profile(str(path))


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(base_height="tall"), r"robot_talos.yaml': base_height must be a number, got 'tall'"),
    (lambda d: d["walking"].update(max_stride="far"), "walking.max_stride must be a number, got 'far'"),
    (lambda d: d["walking"].update(max_strides=0.2), r"walking: unknown field\(s\) \['max_strides'\]"),
    (lambda d: d["walking"].pop("foot_width"), r"walking: missing field\(s\) \['foot_width'\]"),
    (lambda d: d["nominal_posture"].update(leg_left_4_joint=[0.5]), "nominal_posture.leg_left_4_joint must be a number"),
    (lambda d: d.update(nominal_posture=[0.5]), "nominal_posture must be a mapping"),
    (lambda d: d.pop("nominal_posture"), "is incomplete: 'nominal_posture'"),
    (lambda d: d["arms"]["left"].update(grasp_offset=[0.0, 0.1]), r"arms.left.grasp_offset must be a list of 3 numbers"),
    (lambda d: d["arms"].update(middle=d["arms"]["left"]), "arms: 'middle' is no side"),
    (lambda d: d.update(stance={"stand_reach": "near"}), "stance.stand_reach must be a number, got 'near'"),
    (lambda d: d.update(joint_efforts={"arm_left_1_joint": True}), "joint_efforts.arm_left_1_joint must be a number"),
    (lambda d: d["arms"].update(left=5), "arms.left must be a mapping, got 5"),
    (lambda d: d["arms"]["left"].update(joints=7), "arms.left.joints must be a list of names, got 7"),
    (lambda d: d.update(push_passage_crouch=0.08), "push_passage_crouch must be a mapping, got 0.08"),
    (lambda d: d.update(low_lever_crouch=[0.95]), r"low_lever_crouch must be a mapping, got \[0.95\]"),
], ids=["base_height", "stride", "walking-unknown", "walking-missing", "posture-value", "posture-list",
        "posture-absent", "grasp_offset", "arm-side", "stance", "effort-bool", "arm-number", "joints-number",
        "passage-crouch-number", "low-lever-list"])
def test_a_value_that_is_no_number_is_refused_naming_its_field(tmp_path, edit, message):
    """Every number a profile holds is read through one check that names the field: a typo in
    the YAML is a RobotModelError saying where, never a bare ValueError from ``float()``."""
    document = yaml.safe_load((params_dir() / "robot_talos.yaml").read_text())
    edit(document)
    path = tmp_path / "robot_talos.yaml"
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(RobotModelError, match=message):
        load_profile(str(path))


def test_a_push_door_whose_lever_meets_the_pelvis_is_walked_through_crouched():
    crouch = PassageCrouch((1.00, 1.05), 0.06, min_door_width=0.87)
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.03, 0.95) == 0.06
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.03, 0.84) == 0.0  # narrow: no rise asked for
    talos = load_profile("talos").crouch.push_passage
    assert talos is not None and talos.narrow_rise == 0.04 and talos.narrow_rise_top == 1.02
    assert talos.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.00, 0.86) == -0.04  # narrow, lever low in the band
    assert talos.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.035, 0.86) == 0.0  # narrow, lever high in it
    assert walking_height(-0.04) == "0.040 m above the standing height"
    assert walking_height(0.08) == "0.080 m below the standing height"
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 0.95, 0.95) == 0.0  # below the band
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.07, 0.95) == 0.0  # above it
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, 1.03, 0.85) == 0.0  # a narrow door: upright
    assert crouch.for_walk(WalkGoal.THROUGH, DoorOpening.PULL, 1.03, 0.95) == 0.0  # a pull passage is upright
    assert crouch.for_walk(WalkGoal.STAND, DoorOpening.PUSH, 1.03, 0.95) == 0.0  # so is the walk to the door
    assert CrouchRules().for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, (1.03, 0.95)) == 0.0
    assert CrouchRules(push_passage=crouch).for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, None) == 0.0
    assert CrouchRules(push_passage=crouch).for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, (1.01, 0.87)) == 0.06


def test_talos_alone_crouches_through_a_push_door():
    talos = load_profile("talos").crouch.push_passage
    assert talos is not None and 0.0 < talos.crouch <= 0.10 and talos.lever_heights[0] < 1.032 < talos.lever_heights[1]
    assert load_profile("g1").crouch.push_passage is None


@pytest.mark.parametrize("field, crouch, message", [
    ("push_passage_crouch", {"lever_heights": [1.05, 1.00], "crouch": 0.05}, "lever_heights must be increasing"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.3}, r"crouch must be within \(0, 0.15\]"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "depth": 1},
     r"unknown field\(s\) \['depth'\]"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "min_door_width": -1},
     "min_door_width must be"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "narrow_rise": 0.06,
                             "narrow_rise_top": 1.02}, r"narrow_rise must be within \[0, 0.04\]"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "narrow_rise": -0.02,
                             "narrow_rise_top": 1.02}, r"narrow_rise must be within"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "narrow_rise": 0.04},
     r"narrow_rise_top must be within lever_heights"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.05], "crouch": 0.05, "narrow_rise": 0.04,
                             "narrow_rise_top": 1.10}, r"narrow_rise_top must be within lever_heights"),
    ("low_lever_crouch", {"reach_height": -0.9}, "reach_height must be a positive number"),
    ("low_lever_crouch", {"reach_height": 0.95, "max_crouch": 0.2}, r"max_crouch must be within \(0, 0.15\]"),
    ("low_lever_crouch", {"reach_height": 0.95, "max_crouch": float("nan")}, r"max_crouch must be within"),
    ("low_lever_crouch", {"reach_height": 0.95, "depth": 1}, r"unknown field\(s\) \['depth'\]"),
    ("low_lever_crouch", {"reach_height": 0.95, "openings": ["slide"]}, "openings must be a list of push, pull"),
    ("low_lever_crouch", {"reach_height": 0.95, "openings": []}, "openings must name at least one"),
    ("low_lever_crouch", {"reach_height": "high"}, "low_lever_crouch.reach_height must be a number, got 'high'"),
    ("push_passage_crouch", {"lever_heights": [1.00, 1.02, 1.05], "crouch": 0.05},
     r"push_passage_crouch.lever_heights must be a list of 2 numbers, got \[1.0, 1.02, 1.05\]"),
    ("push_passage_crouch", {"lever_heights": [1.00, "x"], "crouch": 0.05},
     r"push_passage_crouch.lever_heights\[1\] must be a number, got 'x'"),
    ("opening_crouch", "deep", "opening_crouch must be a number, got 'deep'"),
])
def test_a_bad_crouch_is_refused(tmp_path, field, crouch, message):
    document = yaml.safe_load((params_dir() / "robot_talos.yaml").read_text())
    document[field] = crouch
    path = tmp_path / "robot_bad_crouch_rule.yaml"
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(RobotModelError, match=message):
        load_profile(str(path))


def test_joint_efforts_are_positive_and_finite(tmp_path):
    """``joint_efforts`` replaces a URDF's effort limits (Atlas v4's ankles, cut in the copy
    ../shared/data holds); a bad number is refused here, an unknown joint where the robot is
    loaded (tests/sim_bridge/test_sim_robot.py)."""
    assert load_profile("talos").joint_efforts == {}
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    path = tmp_path / "robot_bad_efforts.yaml"
    for efforts in ({"left_ankle_pitch_joint": -50.0}, {"left_ankle_pitch_joint": float("nan")},
                    {"left_ankle_pitch_joint": 0.0}):
        document["joint_efforts"] = efforts
        path.write_text(yaml.safe_dump(document))
        with pytest.raises(RobotModelError, match="joint_efforts must be positive and finite"):
            load_profile(str(path))


def test_opening_crouch_lowers_every_walk_and_is_checked(tmp_path, shared_data):
    """A tall robot walks to the door, opens it and passes it ``opening_crouch`` lower (Atlas v4:
    0.15 m); a push passage's crouch takes it lower still where that is deeper; TALOS walks
    upright but for its passage crouch."""
    assert load_profile("atlas_v4").crouch.opening == 0.15
    assert load_profile("talos").crouch.opening == 0.0
    band = PassageCrouch((1.0, 1.04), 0.08)
    for goal in WalkGoal:
        assert CrouchRules(0.15).for_walk(goal, DoorOpening.PULL, None) == 0.15
    assert CrouchRules(0.05, band).for_walk(WalkGoal.STAND, DoorOpening.PUSH, (1.02, 0.95)) == 0.05
    assert CrouchRules(0.05, band).for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, (1.02, 0.95)) == 0.08
    assert CrouchRules(0.12, band).for_walk(WalkGoal.THROUGH, DoorOpening.PUSH, (1.02, 0.95)) == 0.12
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    path = tmp_path / "robot_bad_crouch.yaml"
    for crouch in (-0.05, 0.2, float("nan")):
        document["opening_crouch"] = crouch
        path.write_text(yaml.safe_dump(document))
        with pytest.raises(RobotModelError, match=r"opening_crouch must be within \[0, 0.15\] m"):
            load_profile(str(path))


def test_the_walk_to_a_door_with_a_low_lever_is_crouched_and_the_passage_is_not():
    """A lever below the arm's upright reach lowers the walk to the door by the difference, up
    to ``max_crouch``; the passage's walks stand up again (door_robot.crouch.LowLeverCrouch)."""
    rules = CrouchRules(low_lever=LowLeverCrouch(0.95, 0.10))
    pull_only = CrouchRules(low_lever=LowLeverCrouch(0.95, 0.10, frozenset({DoorOpening.PULL})))
    assert pull_only.for_walk(WalkGoal.STAND, DoorOpening.PULL, (0.88, 0.90)) == pytest.approx(0.07)
    assert pull_only.for_walk(WalkGoal.STAND, DoorOpening.PUSH, (0.88, 0.90)) == 0.0
    for opening in DoorOpening:
        assert rules.for_walk(WalkGoal.STAND, opening, (0.88, 0.90)) == pytest.approx(0.07)
        assert rules.for_walk(WalkGoal.STAND, opening, (0.80, 0.90)) == pytest.approx(0.10)  # at most max_crouch
        assert rules.for_walk(WalkGoal.STAND, opening, (1.00, 0.90)) == 0.0  # within reach
        for goal in (WalkGoal.DOORWAY, WalkGoal.THROUGH):
            assert rules.for_walk(goal, opening, (0.88, 0.90)) == 0.0
    assert rules.for_walk(WalkGoal.STAND, DoorOpening.PULL, None) == 0.0  # no door known
    assert CrouchRules(0.12, low_lever=LowLeverCrouch(0.95, 0.10)).for_walk(WalkGoal.STAND, DoorOpening.PULL,
                                                                             (0.88, 0.9)) == pytest.approx(0.12)
    talos = load_profile("talos").crouch.low_lever
    assert talos is not None and 0.85 < talos.reach_height < 1.0 and talos.max_crouch <= 0.15
    assert talos.openings == {DoorOpening.PULL}
    assert load_profile("g1").crouch.low_lever is None
