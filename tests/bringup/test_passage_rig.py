"""The passage rig's sequence and report line (the scenes themselves serve tests/door_trajopt)."""

import numpy as np
import pytest

from door_bringup.passage_rig import (
    NODE_DEFAULTS,
    EstimateError,
    HandCommand,
    PassageRun,
    erroneous_estimate,
    main,
    opening_hand,
    opening_sequence,
    passage_steps,
    perfect_estimate,
    stand_world,
)
from door_contract.vocabulary import DoorOpening, HingeSide, Motion, TaskState, WalkGoal, grasp_hand
from door_fsm.work import STATE_WORK
from door_sim_bridge.world import ContactSolver, DoorConfig


def test_the_doors_are_opened_in_the_fsms_order():
    assert opening_sequence(DoorOpening.PUSH) == (Motion.APPROACH_HANDLE, HandCommand.GRASP, Motion.TURN_HANDLE,
                                                  Motion.PUSH_DOOR, HandCommand.RELEASE, Motion.READY_TO_WALK)
    pull = opening_sequence(DoorOpening.PULL)
    assert pull[3:5] == (Motion.PULL_DOOR, Motion.BLOCK_DOOR)  # the other hand blocks before the release


@pytest.mark.parametrize("opening", list(DoorOpening))
def test_the_doors_are_walked_through_in_the_fsms_order(opening):
    """To the doorway, the tuck, on through; a door without a doorway walk (a narrow push door)
    skips to WALK_THROUGH, as the FSM's wiring does."""
    assert passage_steps(opening) == ((TaskState.TO_DOORWAY, WalkGoal.DOORWAY), (TaskState.TUCK, Motion.TUCK_ARM),
                                      (TaskState.WALK_THROUGH, WalkGoal.THROUGH))
    assert STATE_WORK[TaskState.TO_DOORWAY].skip_to is TaskState.WALK_THROUGH


def test_a_run_says_where_it_ended_and_what_struck_hardest():
    run = PassageRun("talos", DoorOpening.PULL, HingeSide.RIGHT, 2, "walk through", "fell", "base tilted 35°", 0.97,
                     (("arm_left_3_link | base", 2393.0), ("torso_2_link | leaf", 503.4)))
    line = run.line()
    assert line.startswith("talos pull right #2: walk through: fell (base tilted 35°); door 0.97 rad")
    assert line.endswith("hardest contacts: arm_left_3_link | base 2393 N, torso_2_link | leaf 503 N")


def test_no_trials_is_refused():
    with pytest.raises(SystemExit):
        main(["--trials", "0"])


@pytest.mark.parametrize("arguments", [["--tuck-at", "0.1"], ["--tuck-at", "nan"]])
def test_a_tuck_point_outside_the_planners_range_is_refused_naming_it(arguments, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(arguments)
    assert stopped.value.code == 2 and "tuck_at" in capsys.readouterr().err


def test_an_unknown_robot_is_refused():
    with pytest.raises(SystemExit) as stopped:
        main(["--robot", "asimo"])
    assert stopped.value.code == 2


@pytest.mark.parametrize(("opening", "passage", "hinge_side_hand"), [
    (DoorOpening.PUSH, "facing", False),    # facing, the handle 0.20 m towards the latch
    (DoorOpening.PULL, "facing", True),     # facing, beyond the latch edge
    (DoorOpening.PUSH, "sideways", True),   # sideways, the back to the hinge
])
def test_the_door_is_opened_by_the_hand_on_the_handles_side_of_each_stand_pose(opening, passage, hinge_side_hand):
    """door_trajopt.requests.grasping_hand, as the optimiser picks it for the approach."""
    parameters = {**NODE_DEFAULTS, "push_passage": passage}
    for hinge in HingeSide:
        with stand_world(DoorConfig(opening=opening, hinge_side=hinge), parameters=parameters) as world:
            hand = opening_hand(world, perfect_estimate(world))
        assert hand is (hinge if hinge_side_hand else hinge.other)
        assert (hand is grasp_hand(hinge, opening)) is (passage == "facing")  # the FSM's rule when facing


def test_an_unknown_push_passage_is_refused(capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["--push-passage", "diagonal"])
    assert stopped.value.code == 2 and "push-passage" in capsys.readouterr().err


@pytest.mark.parametrize("distance", ["0.2", "nan", "9"])
def test_a_walk_from_outside_its_range_is_refused(distance, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["--walk-from", distance])
    assert stopped.value.code == 2 and "--walk-from" in capsys.readouterr().err


@pytest.mark.slow
def test_walked_to_the_stand_pose_the_robot_opens_the_door_and_walks_through_it():
    """--walk-from: as in the graph, the walk to the stand pose comes first (it ends at rest);
    then the opening, then the passage (which may fall: issue #11)."""
    from door_bringup.passage_rig import WALKED_THROUGH, run_door
    from door_robot.kinematics import RobotKinematics
    from door_robot.profile import load_profile

    run = run_door(DoorOpening.PUSH, HingeSide.LEFT, 0, RobotKinematics(load_profile("talos")), walk_from=1.5)
    assert run.stage == WALKED_THROUGH, run.line()


@pytest.mark.slow
def test_a_pull_door_with_a_low_lever_is_opened_crouched_and_passed_without_striking_the_body():
    """Seed 10 trial 13's door (lever 0.861 m, wind 1.68 N·m): walked to upright, the torso stayed
    bent from the pull through the block and tuck, and the leaf struck the knees and upper arm at
    0.7-1.7 kN (3 of 6 jittered runs fell). Walked to 9 cm lower (the profile's low_lever_crouch)
    it passes with the leaf on the grippers only (door_robot.crouch.LowLeverCrouch)."""
    from door_bringup.passage_rig import WALKED_THROUGH, DoorShape, EstimateError, run_door
    from door_robot.kinematics import RobotKinematics
    from door_robot.profile import load_profile

    run = run_door(DoorOpening.PULL, HingeSide.RIGHT, 1, RobotKinematics(load_profile("talos")), walk_from=2.5,
                   estimate_error=EstimateError(0.006, np.radians(0.5)), door_shape=DoorShape(0.9222, 0.8605),
                   wind=1.679)
    assert run.stage == WALKED_THROUGH and run.status == "success", run.line()
    assert run.strikes and run.strikes[0][1] < 400.0, run.line()  # upright: 1.2-1.7 kN


@pytest.mark.slow
def test_a_narrow_push_door_whose_lever_meets_the_notch_is_walked_through_higher(monkeypatch):
    """A 0.86 m push door hinged left, its lever at 1.00 m: upright, the lever hooked the pelvis
    as the body swayed back at a side-step and the robot fell (0 of 3); the profile's
    ``narrow_rise`` asks the walk through to go 4 cm higher (door_robot.crouch.PassageCrouch;
    the walker's rise is tests/sim_bridge/test_sim_walking.py's) and it passes — on some machines:
    a physical walk is chaotic, and the same trial that passed on one machine falls on another
    (24.3 s into the walk, at stop 44's build too; 8 of 9 such rig walks passed, stop 42). The
    rise itself is asserted; a fall walking through is issue #11's open gap, an xfail, as the
    graph's push door is (tests/door_task/test_end_to_end.py)."""
    from door_bringup import passage_rig
    from door_bringup.passage_rig import WALKED_THROUGH, DoorShape, EstimateError, run_door
    from door_robot.kinematics import RobotKinematics
    from door_robot.profile import load_profile

    heights: list[float] = []

    class Watched(passage_rig.FootstepExecution):  # the walks the rig starts, their crouch recorded
        def __init__(self, world, footsteps, crouch=0.0):
            heights.append(crouch)
            super().__init__(world, footsteps, crouch)

    monkeypatch.setattr(passage_rig, "FootstepExecution", Watched)
    run = run_door(DoorOpening.PUSH, HingeSide.LEFT, 0, RobotKinematics(load_profile("talos")), walk_from=2.5,
                   estimate_error=EstimateError(0.006, np.radians(0.5)), door_shape=DoorShape(0.86, 1.00))
    assert heights == [0.0, -0.04]  # to the door upright, through it 4 cm higher
    assert run.stage == WALKED_THROUGH, run.line()  # opened; no doorway walk (a narrow door is walked in one go)
    if run.status != "success":
        assert run.status == "fell", run.line()
        pytest.xfail(f"the walk through on the physical robot (issue #11): {run.line()}")


@pytest.fixture(scope="module")
def true_estimate():
    with stand_world(DoorConfig()) as world:
        return perfect_estimate(world)


def test_an_erroneous_estimate_is_the_true_door_moved_rigidly(true_estimate):
    shift, yaw = np.array([0.01, -0.006, 0.004]), np.radians(1.5)
    moved = erroneous_estimate(true_estimate, shift, yaw)
    normal, handle = np.array(true_estimate.normal), np.array(true_estimate.handle_position)
    along = np.cross([0.0, 0.0, 1.0], normal)
    offset = np.array(moved.handle_position) - handle
    assert np.allclose(offset, shift[0] * normal + shift[1] * along / np.linalg.norm(along) + [0, 0, shift[2]])
    assert np.degrees(np.arccos(np.clip(np.dot(moved.normal, normal), -1, 1))) == pytest.approx(1.5, abs=1e-6)
    corners, moved_corners = np.array(true_estimate.corners), np.array(moved.corners)
    spans = lambda c: np.linalg.norm(c[:, None] - c[None], axis=-1)  # noqa: E731
    assert np.allclose(spans(corners), spans(moved_corners)) and not np.allclose(corners, moved_corners)
    assert moved.width == true_estimate.width and moved.hinge_side is true_estimate.hinge_side
    unmoved = erroneous_estimate(true_estimate, np.zeros(3), 0.0)
    assert np.allclose(unmoved.corners, corners) and np.allclose(unmoved.handle_position, handle)


def test_each_trial_draws_its_error_within_the_bounds():
    bounds = EstimateError(0.006, np.radians(0.5))
    draws = [bounds.drawn(np.random.default_rng([trial, 1])) for trial in range(50)]
    assert all(np.all(np.abs(shift) <= 0.006) and abs(yaw) <= np.radians(0.5) for shift, yaw in draws)
    assert len({round(yaw, 9) for _, yaw in draws}) == 50
    shift, yaw = EstimateError().drawn(np.random.default_rng(3))
    assert not np.any(shift) and yaw == 0.0


@pytest.mark.parametrize("width", ["0.7", "nan", "1.2"])
def test_a_door_width_outside_the_full_range_is_refused(width, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["--door-width", width])
    assert stopped.value.code == 2 and "--door-width" in capsys.readouterr().err


@pytest.mark.parametrize(("option", "value"), [("--handle-height", "0.8"), ("--handle-height", "nan"),
                                               ("--wind", "-0.5"), ("--wind", "4")])
def test_a_handle_height_or_wind_outside_its_range_is_refused(option, value, capsys):
    with pytest.raises(SystemExit) as stopped:
        main([option, value])
    assert stopped.value.code == 2 and option in capsys.readouterr().err


@pytest.mark.parametrize("bounds", [["-1", "0"], ["0.5", "nan"], ["11", "1"]])
def test_an_estimate_error_outside_its_range_is_refused(bounds, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["--estimate-error", *bounds])
    assert stopped.value.code == 2 and "--estimate-error" in capsys.readouterr().err


@pytest.mark.parametrize(("arguments", "field"), [(["--solver-iterations", "0"], "solver_iterations"),
                                                 (["--physics-rate", "10"], "physics_rate"),
                                                 (["--contact-solver", "pgs"], "--contact-solver")])
def test_physics_outside_the_sims_ranges_is_refused_naming_it(arguments, field, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(arguments)
    assert stopped.value.code == 2 and field in capsys.readouterr().err


def test_the_physics_options_reach_the_world_they_run_in():
    physics = {"physics_rate": 480.0, "contact_solver": ContactSolver.DANTZIG, "solver_iterations": 80}
    with stand_world(DoorConfig(), physics=physics) as world:
        assert (world.config.physics_rate, world.config.contact_solver, world.config.solver_iterations) == (
            480.0, ContactSolver.DANTZIG, 80)
