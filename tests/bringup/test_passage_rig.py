"""The passage rig's sequence and report line (the scenes themselves serve tests/door_trajopt)."""

import numpy as np
import pytest

from door_bringup.passage_rig import GRASP, RELEASE, TUCK_DURATION, PassageRun, main, opening_sequence, tuck_path
from door_contract.vocabulary import DoorOpening, HingeSide, Side
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.world import DoorWorld, WorldConfig
from door_trajopt.chain import ArmChain
from door_trajopt.motions import Motion


def test_the_doors_are_opened_in_the_fsms_order():
    assert opening_sequence(DoorOpening.PUSH) == (Motion.APPROACH_HANDLE, GRASP, Motion.TURN_HANDLE,
                                                  Motion.PUSH_DOOR, RELEASE, Motion.READY_TO_WALK)
    pull = opening_sequence(DoorOpening.PULL)
    assert pull[3:5] == (Motion.PULL_DOOR, Motion.BLOCK_DOOR)  # the other hand blocks before the release


def test_a_run_says_where_it_ended_and_what_struck_hardest():
    run = PassageRun("talos", DoorOpening.PULL, HingeSide.RIGHT, 2, "walk through", "fell", "base tilted 35°", 0.97,
                     (("arm_left_3_link | base", 2393.0), ("torso_2_link | leaf", 503.4)))
    line = run.line()
    assert line.startswith("talos pull right #2: walk through: fell (base tilted 35°); door 0.97 rad")
    assert line.endswith("hardest contacts: arm_left_3_link | base 2393 N, torso_2_link | leaf 503 N")


def test_no_trials_is_refused():
    with pytest.raises(SystemExit):
        main(["--trials", "0"])


def test_a_tuck_point_outside_the_doorway_approach_is_refused():
    with pytest.raises(SystemExit):
        main(["--pull-passage", "tuck", "--tuck-at", "0.1"])


def test_the_tuck_takes_the_blocking_arm_alone_to_the_walking_posture():
    """Only the arm's own joints move (the torso is shared with the other arm), and they end
    where the profile's walking posture puts them."""
    kinematics = RobotKinematics(load_profile("talos"))
    with DoorWorld(WorldConfig()) as world:
        path = tuck_path(world, kinematics, Side.RIGHT)
        now = world.joint_positions()
    assert path.joint_names and all(name.startswith("arm_right") for name in path.joint_names)
    walking = dict(zip(ArmChain(kinematics, Side.RIGHT, kinematics.nominal_q).joint_names,
                       ArmChain(kinematics, Side.RIGHT, kinematics.nominal_q).chain_of(kinematics.walking_q)))
    assert np.allclose(path.positions[-1], [walking[name] for name in path.joint_names])
    assert path.times[-1] == pytest.approx(TUCK_DURATION)
    first_step = np.abs(path.positions[0] - [now[name] for name in path.joint_names])
    assert first_step.max() <= np.abs(path.positions[-1] - [now[name] for name in path.joint_names]).max() / 10 + 1e-9


def test_an_unknown_robot_is_refused():
    with pytest.raises(SystemExit) as stopped:
        main(["--robot", "asimo"])
    assert stopped.value.code == 2
