"""The passage rig's sequence and report line (the scenes themselves serve tests/door_trajopt)."""

import pytest

from door_bringup.passage_rig import (
    NODE_DEFAULTS,
    HandCommand,
    PassageRun,
    main,
    opening_hand,
    opening_sequence,
    passage_steps,
    perfect_estimate,
    stand_world,
)
from door_contract.vocabulary import DoorOpening, HingeSide, Motion, WalkGoal, grasp_hand
from door_sim_bridge.world import DoorConfig


def test_the_doors_are_opened_in_the_fsms_order():
    assert opening_sequence(DoorOpening.PUSH) == (Motion.APPROACH_HANDLE, HandCommand.GRASP, Motion.TURN_HANDLE,
                                                  Motion.PUSH_DOOR, HandCommand.RELEASE, Motion.READY_TO_WALK)
    pull = opening_sequence(DoorOpening.PULL)
    assert pull[3:5] == (Motion.PULL_DOOR, Motion.BLOCK_DOOR)  # the other hand blocks before the release


def test_the_doors_are_walked_through_in_the_fsms_order():
    assert passage_steps(DoorOpening.PUSH) == (WalkGoal.THROUGH,)
    assert passage_steps(DoorOpening.PULL) == (WalkGoal.DOORWAY, Motion.TUCK_ARM, WalkGoal.THROUGH)


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
