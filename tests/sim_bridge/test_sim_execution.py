"""Executing joint trajectories and footstep plans; every bad input is REJECTED and nothing moves.

These run on the kinematic robot (fixed base, glided along footsteps: fast and exact); the
physical robot's walking and balance are tested in test_sim_walking.py.
"""

import math

import numpy as np
import pytest

from door_contract.converters.footsteps import FootPlacement
from door_contract.converters.trajectory import JointPath
from door_contract.geometry import yaw_of
from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus, decode, encode
from door_contract.vocabulary import Foot
from door_sim_bridge.execution import ExecutionPhase, FootstepExecution, TrajectoryExecution
from door_sim_bridge.world import DoorWorld, RobotMode, StanceConfig, WorldConfig

ARM = ("arm_left_1_joint", "arm_left_2_joint", "arm_left_4_joint", "torso_1_joint")


@pytest.fixture(scope="module")
def world():
    with DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC)) as sim:
        yield sim


def _snapshot(world: DoorWorld) -> tuple[np.ndarray, np.ndarray]:
    return world.joint_states().positions.copy(), world.base_pose().copy()


def _start_over(world: DoorWorld) -> tuple[np.ndarray, np.ndarray]:
    """Robot back at its start, settled; its state then."""
    world.reset_robot()
    world.step(48)
    return _snapshot(world)


def _assert_did_not_move(world: DoorWorld, before: tuple[np.ndarray, np.ndarray]) -> None:
    world.step(24)
    positions, base = _snapshot(world)
    np.testing.assert_allclose(positions, before[0], atol=1e-4)
    np.testing.assert_allclose(base, before[1], atol=1e-9)


def test_trajectory_is_tracked_to_within_1_degree(world):
    _start_over(world)
    start = np.array([world.joint_positions()[name] for name in ARM])
    goal = start + np.array([-0.4, 0.3, -0.5, 0.3])
    middle = (start + goal) / 2 + np.array([0.0, 0.1, 0.0, 0.0])
    path = JointPath(np.array([0.8, 1.6]), ARM, np.vstack([middle, goal]))
    execution = TrajectoryExecution.from_joint_path(world, path)
    assert execution.phase is ExecutionPhase.PENDING
    steps = 0
    while not execution.command():  # the node's loop: command, step, publish
        world.step()
        steps += 1
    result = execution.result
    assert result.status is OutcomeStatus.SUCCESS and result.reason == ""
    assert result.duration_s == pytest.approx(1.6 + world.config.execution.settle_time, abs=0.01)
    assert steps == pytest.approx(result.duration_s * world.config.physics_rate, abs=2)
    reached = world.joint_positions()
    for name, value in zip(ARM, goal):
        assert abs(reached[name] - value) < math.radians(1.0)


def _bad_trajectories(world: DoorWorld) -> dict[str, tuple]:
    here = [world.joint_positions()[name] for name in ARM]
    shifted = [v + 0.1 for v in here]
    upper = world.joint_limits()["arm_left_2_joint"].upper
    beyond = list(shifted)
    beyond[1] = upper + 0.2
    return {
        "unknown joint 'wing_joint'": ([1.0], ("wing_joint",), [[0.0]]),
        "not finite": ([1.0], ARM, [[*shifted[:3], float("nan")]]),
        "strictly increasing": ([1.0, 1.0], ARM, [shifted, here]),
        "outside its limits": ([1.0], ARM, [beyond]),
        "rad/s": ([0.01], ARM, [shifted]),
        "from its current position": ([0.0, 1.0], ARM, [[here[0], here[1] + 0.5, *here[2:]], here]),
        "NaN or infinity": ([float("inf")], ARM, [shifted]),
        "shape": ([1.0], ARM, [shifted[:2]]),
    }


@pytest.mark.parametrize("expected", ["unknown joint 'wing_joint'", "not finite", "strictly increasing",
                                      "outside its limits", "rad/s", "from its current position",
                                      "NaN or infinity", "shape"])
def test_bad_trajectory_is_rejected_and_nothing_moves(world, expected):
    before = _start_over(world)
    times, names, positions = _bad_trajectories(world)[expected]
    execution = TrajectoryExecution(world, times, names, positions)
    assert execution.done and execution.advance(50)
    assert execution.result.status is OutcomeStatus.REJECTED
    assert expected in execution.result.reason
    _assert_did_not_move(world, before)


def test_trajectory_can_be_cancelled(world):
    _start_over(world)
    start = np.array([world.joint_positions()[name] for name in ARM])
    execution = TrajectoryExecution(world, [2.0], ARM, [start + np.array([-0.6, 0.0, 0.0, 0.0])])
    execution.advance(48)
    assert not execution.done
    result = execution.cancel("operator abort")
    assert result.status is OutcomeStatus.FAILURE and result.reason == "operator abort"
    assert result.duration_s == pytest.approx(0.2, abs=0.01)
    assert execution.cancel().reason == "operator abort"  # finished: no change


def _walk_plan(world: DoorWorld, stride: float, steps: int) -> list[FootPlacement]:
    feet = world.foot_placements()
    plan = []
    for index in range(steps):
        foot = Foot.LEFT if index % 2 == 0 else Foot.RIGHT
        plan.append(FootPlacement(foot, feet[foot].x + stride * (index + 1), feet[foot].y, 0.0))
    return plan


def test_footsteps_move_the_base_to_the_midpoint_of_the_feet(world):
    _start_over(world)
    start = world.base_pose()
    np.testing.assert_allclose(world.base_pose_for_feet(*_standing_feet(world)), start, atol=1e-6)
    plan = _walk_plan(world, 0.2, 4)  # left +0.2, right +0.4, left +0.6, right +0.8 in x
    execution = FootstepExecution(world, plan)
    while not execution.command():
        world.step()
    result = execution.result
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    assert execution.steps_done == 4
    assert result.duration_s == pytest.approx(4 * world.config.execution.step_duration, abs=0.05)
    end = world.base_pose()
    assert end[0, 3] - start[0, 3] == pytest.approx(0.7, abs=1e-6)  # midpoint of 0.6 and 0.8
    assert end[1, 3] == pytest.approx(start[1, 3], abs=1e-6)
    assert end[2, 3] == pytest.approx(world.profile.base_height, abs=1e-6)
    assert yaw_of(end) == pytest.approx(0.0, abs=1e-9)


def _standing_feet(world: DoorWorld) -> tuple[FootPlacement, FootPlacement]:
    feet = world.foot_placements()
    return feet[Foot.LEFT], feet[Foot.RIGHT]


def test_footsteps_turn_in_place(world):
    _start_over(world)
    left, right = _standing_feet(world)
    centre = np.array([(left.x + right.x) / 2, (left.y + right.y) / 2])
    half = np.hypot(left.x - right.x, left.y - right.y) / 2
    plan = []
    for index, yaw in enumerate([0.2, 0.2, 0.4, 0.4]):  # TALOS's max_turn: 0.20 rad per step
        foot = Foot.LEFT if index % 2 == 0 else Foot.RIGHT
        sign = 1.0 if foot is Foot.LEFT else -1.0
        x, y = centre + sign * half * np.array([-np.sin(yaw), np.cos(yaw)])
        plan.append(FootPlacement(foot, float(x), float(y), yaw))
    before = yaw_of(world.base_pose())
    assert FootstepExecution(world, plan).run().status is OutcomeStatus.SUCCESS
    assert yaw_of(world.base_pose()) - before == pytest.approx(0.4, abs=1e-6)


def _bad_plans(world: DoorWorld) -> dict[str, list[FootPlacement]]:
    good = _walk_plan(world, 0.1, 2)
    left, right = good
    return {
        "exceeds max_stride": _walk_plan(world, 0.4, 2),
        "alternate": [right, left],
        "NaN": [FootPlacement(Foot.LEFT, float("nan"), left.y, 0.0), right],
        "exceeds max_turn": [FootPlacement(Foot.LEFT, left.x, left.y, 1.0), right],
        "legs cross": [FootPlacement(Foot.LEFT, left.x, right.y - 0.05, 0.0), right],
        "more than": [FootPlacement(Foot.LEFT, left.x, left.y + 0.3, 0.0), right],
        "empty": [],
    }


@pytest.mark.parametrize("expected", ["exceeds max_stride", "alternate", "NaN", "exceeds max_turn",
                                      "legs cross", "more than", "empty"])
def test_bad_footstep_plan_is_rejected_and_nothing_moves(world, expected):
    before = _start_over(world)
    plan = _bad_plans(world)[expected]
    execution = FootstepExecution(world, plan)
    assert execution.advance(100)
    assert execution.result.status is OutcomeStatus.REJECTED and expected in execution.result.reason
    _assert_did_not_move(world, before)


def test_walking_into_the_wall_stops_with_a_failure(world):
    world.reset_robot(StanceConfig(distance=1.2, lateral_offset=1.2))  # beside the doorway
    plan = _walk_plan(world, 0.25, 12)  # 1.5 m forward: through the wall at x = 0
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.FAILURE and "wall or door frame" in result.reason
    assert -0.6 < world.base_pose()[0, 3] < 0.0


def test_trajectory_with_velocities_and_the_outcome_payload(world):
    _start_over(world)
    start = np.array([world.joint_positions()[name] for name in ARM])
    goal = start + np.array([-0.3, 0.2, -0.3, 0.2])
    times = np.array([0.0, 0.7, 1.4])
    positions = np.vstack([start, (start + goal) / 2, goal])
    velocities = np.vstack([np.zeros(4), (goal - start) / 1.4, np.zeros(4)])
    result = TrajectoryExecution(world, times, ARM, positions, velocities).run()
    assert result.status is OutcomeStatus.SUCCESS
    reached = world.joint_positions()
    assert max(abs(reached[name] - value) for name, value in zip(ARM, goal)) < math.radians(1.0)
    outcome = result.outcome(ExecutionKind.TRAJECTORY, 42)
    assert (outcome.kind, outcome.request_id, outcome.status) == (ExecutionKind.TRAJECTORY, 42,
                                                                  OutcomeStatus.SUCCESS)
    assert decode(ExecutionOutcome, encode(outcome)) == outcome


def test_ragged_trajectory_is_rejected_not_raised(world):
    execution = TrajectoryExecution(world, [0.5, 1.0], ARM[:2], [[0.1, 0.2], [0.3]])
    assert execution.result.status is OutcomeStatus.REJECTED and "numeric" in execution.result.reason
