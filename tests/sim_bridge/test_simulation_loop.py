"""The sim bridge's loop without ROS: streams due at their simulated rates, one execution at a
time, the dead-man, real-time pacing; and a bug in a tick (of the execution, the physics or a
publication) is reported, ends the execution it hit with FAILURE, and the simulation goes on.

On the kinematic robot (fast, exact); the bugs are real exceptions: an execution whose
command raises, a world whose physics client is gone, a publication that raises.
"""

import numpy as np
import pytest
from test_sim_execution import ARM, _start_over

from door_contract.payloads import ExecutionKind, OutcomeStatus
from door_contract.vocabulary import Side
from door_sim_bridge.base_velocity import BaseVelocity
from door_sim_bridge.deadman import DeadMan
from door_sim_bridge.execution import TrajectoryExecution
from door_sim_bridge.simulation_loop import (
    STEPS_PER_TICK,
    LoopReport,
    PublicationRates,
    SimulationLoop,
    Stop,
    Stream,
    TickStage,
)
from door_sim_bridge.world import DoorWorld, RobotMode, WorldConfig

RATES = PublicationRates(clock=100.0, state=50.0, tf=0.0, camera=2.0)
TRAJECTORY = ExecutionKind.TRAJECTORY
SWING = np.array([-0.4, 0.3, -0.5, 0.3])  # rad, of ARM: inside the limits from the start posture


@pytest.fixture(scope="module")
def world():
    with DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC)) as sim:
        yield sim


def _loop(world, timeout_s=0.0, real_time=False, wall_start=0.0):
    return SimulationLoop(world, DeadMan(timeout_s), RATES, real_time, wall_start)


class Published:
    """The ``publish`` of a test: records every call; raises ``error`` at call ``fail_at``."""

    def __init__(self, fail_at=None, error=None):
        self.calls, self.fail_at, self.error = [], fail_at, error

    def __call__(self, now, streams):
        self.calls.append((now, streams))
        if len(self.calls) == self.fail_at:
            raise self.error

    def count(self, stream):
        return sum(stream in streams for _, streams in self.calls)


def _move_arm(offset, duration=0.5):
    """Build a trajectory of the arm ``offset`` (rad) from where it is, over ``duration`` s."""
    def build(world):
        here = np.array([world.joint_positions()[name] for name in ARM])
        return TrajectoryExecution(world, [duration], ARM, [here + offset])
    return build


class BuggyTrajectory(TrajectoryExecution):
    """A trajectory whose command raises (a bug) from its ``fail_at``-th command on."""

    def __init__(self, world, fail_at, *args):
        super().__init__(world, *args)
        self.commands, self.fail_at = 0, fail_at

    def _command_now(self):
        self.commands += 1
        if self.commands >= self.fail_at:
            raise ZeroDivisionError("division by zero")
        super()._command_now()


def _arm(world):
    return np.array([world.joint_positions()[name] for name in ARM])


def _run(loop, publish, ticks):
    return [loop.tick(0.0, publish) for _ in range(ticks)]


def test_each_tick_steps_the_physics_and_publishes_what_is_due_at_its_simulated_rate(world):
    loop, publish = _loop(world), Published()
    start = world.time
    ticks = 60  # 240 steps: 1 s at 240 Hz
    _run(loop, publish, ticks)
    assert world.time == pytest.approx(start + ticks * STEPS_PER_TICK * world.config.time_step)
    times = [now for now, _ in publish.calls]
    assert len(times) == ticks * STEPS_PER_TICK and times == sorted(times) and times[-1] == world.time
    assert abs(publish.count(Stream.CLOCK) - 100) <= 1 and abs(publish.count(Stream.STATE) - 50) <= 1
    assert publish.count(Stream.CAMERA) in (2, 3)
    assert publish.count(Stream.TF) == 0  # rate 0: off


def test_the_camera_renders_faster_while_the_robot_does_not_walk(world):
    """Frames at ``camera_standing`` Hz standing or moving an arm, at ``camera`` Hz while a
    footstep plan executes (what the loop knows of walking is the execution's kind)."""
    _start_over(world)
    rates = PublicationRates(clock=100.0, state=50.0, tf=0.0, camera=2.0, camera_standing=8.0)
    loop, publish = SimulationLoop(world, DeadMan(0.0), rates, False, 0.0), Published()
    _run(loop, publish, 60)  # 1 s standing
    assert publish.count(Stream.CAMERA) in (8, 9)
    loop.submit(ExecutionKind.FOOTSTEPS, 21, _move_arm(np.zeros(4), duration=2.0))
    walking = Published()
    _run(loop, walking, 60)  # 1 s of the "walk"
    assert loop.running is not None and walking.count(Stream.CAMERA) in (2, 3)


def test_one_execution_at_a_time_and_its_outcome_when_it_ends(world):
    _start_over(world)
    loop, publish = _loop(world), Published()
    offset = np.array([-0.2, 0.1, -0.2, 0.1])
    goal = _arm(world) + offset
    report = loop.submit(TRAJECTORY, 7, _move_arm(offset))
    assert report.started is not None and str(report.started) == "trajectory 7" and not report.outcomes
    busy = loop.submit(TRAJECTORY, 8, _move_arm(offset))
    assert [(o.request_id, o.status) for o in busy.outcomes] == [(8, OutcomeStatus.REJECTED)]
    assert "busy executing trajectory 7" in busy.outcomes[0].reason
    outcomes = [o for r in _run(loop, publish, 100) for o in r.outcomes]
    assert [(o.request_id, o.status) for o in outcomes] == [(7, OutcomeStatus.SUCCESS)]
    assert loop.running is None and np.max(np.abs(_arm(world) - goal)) < np.radians(1)


def test_a_stopped_trajectory_frees_the_robot_at_once_for_the_next_command(world):
    """The head search's look stopped as the door is confirmed, then the walk: the stop ends the
    trajectory at once, so the next command is taken without waiting for a tick (it was refused
    "busy executing trajectory …" three repeats in a row on a loaded machine), and the stopped
    one's outcome comes first."""
    _start_over(world)
    loop, publish = _loop(world), Published()
    loop.submit(TRAJECTORY, 11, _move_arm(np.array([-0.2, 0.1, -0.2, 0.1]), duration=2.0))
    _run(loop, publish, 5)
    assert loop.stop(TRAJECTORY, "the door is confirmed").stop.stopped is not None
    report = loop.submit(TRAJECTORY, 12, _move_arm(np.zeros(4)))
    assert [(o.request_id, o.status) for o in report.outcomes] == [(11, OutcomeStatus.STOPPED)]
    assert report.started is not None and report.started.request_id == 12
    outcomes = [o for r in _run(loop, publish, 100) for o in r.outcomes]
    assert [(o.request_id, o.status) for o in outcomes] == [(12, OutcomeStatus.SUCCESS)]


def test_an_invalid_execution_is_answered_at_once_and_an_empty_stop_names_nothing(world):
    loop = _loop(world)
    report = loop.submit(TRAJECTORY, 9, lambda w: TrajectoryExecution(w, [1.0], ("wing_joint",), [[0.0]]))
    assert report.outcomes[0].status is OutcomeStatus.REJECTED and "wing_joint" in report.outcomes[0].reason
    assert loop.running is None
    stop = loop.stop(ExecutionKind.FOOTSTEPS, "operator").stop
    assert stop.why == "operator" and stop.stopped is None and not stop.dead_man


def test_a_bug_while_building_an_execution_is_a_failure_and_nothing_runs(world):
    loop = _loop(world)
    report = loop.submit(TRAJECTORY, 10, lambda w: 1 / 0)
    assert [(o.request_id, o.status) for o in report.outcomes] == [(10, OutcomeStatus.FAILURE)]
    assert report.outcomes[0].reason.startswith("internal error: building the execution failed")
    assert [f.stage for f in report.faults] == [TickStage.BUILD] and "ZeroDivisionError" in report.faults[0].error
    assert loop.running is None and loop.fault_count == 1


def test_a_bug_in_the_execution_ends_it_with_failure_the_arm_holds_and_the_simulation_goes_on(world):
    _start_over(world)
    loop, publish = _loop(world), Published()
    here = _arm(world)
    assert loop.submit(TRAJECTORY, 11, lambda w: BuggyTrajectory(w, 60, [1.0], ARM, [here + SWING])).started
    reports = _run(loop, publish, 20)
    failed = [r for r in reports if r.outcomes]
    assert len(failed) == 1 and failed[0].outcomes[0].request_id == 11
    outcome, fault = failed[0].outcomes[0], failed[0].faults[0]
    assert outcome.status is OutcomeStatus.FAILURE and "commanding the execution failed" in outcome.reason
    assert fault.stage is TickStage.EXECUTION and "division by zero" in fault.error
    assert outcome.duration_s > 0 and loop.running is None and loop.fault_count == 1
    held = _arm(world)
    assert np.max(np.abs(held - here)) > 0.05  # it had moved before the bug …
    time_then = world.time
    _run(loop, publish, 30)
    assert world.time > time_then  # … the physics goes on, and the arm stays where the bug left it
    np.testing.assert_allclose(_arm(world), held, atol=3e-3)
    assert loop.submit(TRAJECTORY, 12, _move_arm(np.zeros(4))).started is not None  # and accepts the next
    assert "commanding the execution" in loop.status(1.0)["last_fault"]


def test_a_bug_in_a_publication_skips_the_rest_of_that_tick_only(world):
    _start_over(world)
    loop, publish = _loop(world), Published(fail_at=3, error=RuntimeError("render failed"))
    assert loop.submit(TRAJECTORY, 13, _move_arm(np.full(4, 0.1))).started
    first, *rest = _run(loop, publish, 100)
    assert len(publish.calls) == 3 + 99 * STEPS_PER_TICK  # the failing tick stopped at its third step
    assert [f.stage for f in first.faults] == [TickStage.PUBLICATION] and not first.outcomes
    outcomes = [o for r in rest for o in r.outcomes]
    assert [(o.request_id, o.status) for o in outcomes] == [(13, OutcomeStatus.SUCCESS)]  # nothing else moved
    assert loop.fault_count == 1 and not any(r.faults for r in rest)


def test_a_broken_physics_is_counted_every_tick_reported_once_and_fails_the_execution():
    world = DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC))
    loop, publish = _loop(world), Published()
    assert loop.submit(TRAJECTORY, 14, _move_arm(np.full(4, 0.1), duration=2.0)).started
    _run(loop, publish, 10)
    world.close()  # the physics client is gone: every call into it raises
    reports = _run(loop, publish, 5)
    first = reports[0]
    assert [(o.request_id, o.status) for o in first.outcomes] == [(14, OutcomeStatus.FAILURE)]
    assert [f.stage for f in first.faults] == [TickStage.EXECUTION, TickStage.HOLD]  # the hold failed too
    assert [f.stage for f in reports[1].faults] == [TickStage.PHYSICS]  # nothing runs now: the step raises
    assert not any(r.faults or r.outcomes for r in reports[2:])  # the same fault again: counted only
    assert loop.fault_count == 2 + 4 and loop.status(1.0)["tick_faults"] == 6


def test_a_repeated_fault_is_reported_again_after_another_one():
    world = DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC))
    loop = _loop(world)
    publish = Published(fail_at=1, error=RuntimeError("first"))
    assert [f.error for f in loop.tick(0.0, publish).faults] == ["RuntimeError('first')"]
    world.close()
    assert [f.stage for f in loop.tick(0.0, publish).faults] == [TickStage.PHYSICS]
    assert loop.tick(0.0, publish).faults == ()
    assert [f.stage for f in loop.submit(TRAJECTORY, 15, lambda w: 1 / 0).faults] == [TickStage.BUILD]
    assert [f.stage for f in loop.tick(0.0, publish).faults] == [TickStage.PHYSICS]


def test_the_dead_man_stops_the_execution_and_refuses_new_ones_until_the_supervisor_is_back(world):
    _start_over(world)
    loop, publish = _loop(world, timeout_s=3.0), Published()
    loop.supervisor_beat(100.0)
    assert loop.submit(TRAJECTORY, 16, _move_arm(np.full(4, 0.1), duration=2.0)).started
    assert all(loop.tick(now, publish).stop is None for now in np.arange(100.0, 103.0, 0.5))
    report = loop.tick(103.25, publish)
    assert report.stop.dead_man and str(report.stop.stopped) == "trajectory 16" and "silent" in report.stop.why
    assert [(o.request_id, o.status) for o in report.outcomes] == [(16, OutcomeStatus.STOPPED)]
    refused = loop.submit(TRAJECTORY, 17, _move_arm(np.zeros(4)))
    assert refused.outcomes[0].status is OutcomeStatus.REJECTED and "heartbeat lost" in refused.outcomes[0].reason
    assert loop.supervisor_beat(104.0)  # back
    assert loop.submit(TRAJECTORY, 18, _move_arm(np.zeros(4))).started


def test_a_real_time_simulation_does_not_run_ahead_of_the_wall_clock(world):
    loop, publish = _loop(world, real_time=True, wall_start=0.0), Published()
    ahead = world.time - 0.1  # the wall clock is 0.1 s behind the simulated one
    loop.tick(ahead, publish)
    assert publish.calls == []
    loop.tick(world.time + 0.1, publish)
    assert len(publish.calls) == STEPS_PER_TICK


def test_base_velocity_is_the_difference_of_positions_over_simulated_time():
    velocity, pose = BaseVelocity(), np.eye(4)
    assert velocity.update(1.0, pose) is None
    pose[:3, 3] = 0.02, -0.01, 0.0
    np.testing.assert_allclose(velocity.update(1.1, pose), [0.2, -0.1, 0.0])
    assert velocity.update(1.1, pose) is None  # simulated time did not advance
    np.testing.assert_allclose(velocity.update(1.2, pose), [0.0, 0.0, 0.0])


def test_a_bug_in_a_grasp_is_a_refused_call_and_a_reported_fault():
    world = DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC))
    loop = _loop(world)
    success, message, report = loop.grasp(Side.RIGHT, False)  # opening an open hand: fine
    assert success and not report.faults
    world.close()  # every call into the physics raises now
    success, message, report = loop.grasp(Side.RIGHT, True)
    assert not success and message.startswith("internal error: operating a gripper failed")
    assert [f.stage for f in report.faults] == [TickStage.GRASP] and loop.fault_count == 1


def test_a_report_sorts_its_log_lines_by_severity():
    """The node logs each list at its own call site (rclpy: one severity per call site)."""
    quiet = LoopReport(stop=Stop("an empty footstep plan", None))
    assert quiet.notes == ["stop (an empty footstep plan): no such execution running"]
    assert quiet.errors == [] and quiet.warnings == []
    dead = LoopReport(stop=Stop("supervisor silent for 2.0 s", None, dead_man=True))
    assert dead.errors == ["supervisor silent for 2.0 s"]
    assert LoopReport().errors == LoopReport().warnings == LoopReport().notes == []


def test_a_tick_that_kept_the_bridge_busy_is_not_the_supervisors_silence(world):
    """The first tick of a long walk computes its pattern for seconds: the heartbeats wait in
    the bridge's queue and the simulation stands still, so that gap does not trip the dead-man;
    silence while the bridge ticks does."""
    _start_over(world)
    loop, publish = _loop(world, timeout_s=3.0), Published()
    loop.supervisor_beat(100.0)
    assert loop.submit(TRAJECTORY, 19, _move_arm(np.full(4, 0.1), duration=20.0)).started
    assert loop.tick(100.1, publish).stop is None
    assert loop.tick(104.6, publish).stop is None  # 4.5 s inside one tick
    assert all(loop.tick(now, publish).stop is None for now in np.arange(104.8, 107.4, 0.2))
    report = loop.tick(107.8, publish)  # 3.3 s of listening since the beat (the 4.5 s deaf taken off)
    assert report.stop.dead_man and "silent" in report.stop.why
