"""Execution.stop: a trajectory holds where the arm is at once; a walk ends at the next stable
stance (for the kinematic walk: the step in progress is finished); both report STOPPED."""

import numpy as np
import pytest
from test_sim_execution import ARM, _start_over, _walk_plan

from door_contract.converters.trajectory import JointPath
from door_contract.payloads import OutcomeStatus
from door_sim_bridge.execution import ExecutionPhase, FootstepExecution, TrajectoryExecution
from door_sim_bridge.world import DoorWorld, RobotMode, WorldConfig


@pytest.fixture(scope="module")
def world():
    with DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC)) as sim:  # the physical stop: test_sim_walking
        yield sim


def test_a_stopped_trajectory_holds_where_the_arm_is(world):
    _start_over(world)
    start = np.array([world.joint_positions()[name] for name in ARM])
    goal = start + np.array([-0.4, 0.3, -0.5, 0.3])
    execution = TrajectoryExecution.from_joint_path(world, JointPath(np.array([4.0]), ARM, goal[None, :]))
    execution.advance(240)  # 1 s of the 4 s motion
    execution.stop("operator said stop")
    assert execution.done and execution.result.status is OutcomeStatus.STOPPED
    assert "operator said stop" in execution.result.reason
    world.step(12)  # the motors brake (50 ms)
    held = np.array([world.joint_positions()[name] for name in ARM])
    world.step(240)
    after = np.array([world.joint_positions()[name] for name in ARM])
    np.testing.assert_allclose(after, held, atol=2e-3)  # it holds
    assert np.max(np.abs(after - goal)) > 0.2  # far from where the trajectory was going


def test_a_stopped_walk_ends_with_the_step_in_progress(world):
    _start_over(world)
    plan = _walk_plan(world, 0.2, 8)
    execution = FootstepExecution(world, plan)
    duration = world.config.execution.step_duration
    steps_before = int(1.5 * duration * world.config.physics_rate)
    execution.advance(steps_before)  # halfway through step 1 (the second)
    assert execution.steps_done == 1
    execution.stop("supervisor lost")
    assert not execution.done  # both feet are not down yet
    execution.advance(int(duration * world.config.physics_rate))
    assert execution.done and execution.result.status is OutcomeStatus.STOPPED
    assert execution.steps_done == 2 and "after step 2 of 8" in execution.result.reason
    base = world.base_pose().copy()
    world.step(240)
    np.testing.assert_allclose(world.base_pose(), base, atol=1e-9)  # no further step


def test_stopping_before_the_start_moves_nothing(world):
    before = _start_over(world)
    execution = FootstepExecution(world, _walk_plan(world, 0.2, 4))
    assert execution.phase is ExecutionPhase.PENDING
    execution.stop("paused")
    assert execution.result.status is OutcomeStatus.STOPPED and execution.command()
    np.testing.assert_allclose(world.base_pose(), before[1], atol=1e-9)
