"""Hostile commands to the sim bridge over DDS: bad trajectories and footstep plans are REJECTED
and move nothing; an empty JointTrajectory holds the arm, an empty Path ends the walk at the
next stable stance; the dead-man stops everything when the supervisor falls silent; a
burst of grasp calls is answered call for call."""

import math

import numpy as np
import pytest
from fuzz_graph import STILL_BASE, Observer
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path as PathMsg
from ros_helpers import start_node, stop_node
from std_msgs.msg import Float64
from std_srvs.srv import SetBool
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from door_contract.converters.footsteps import FootPlacement, footsteps_to_path
from door_contract.converters.trajectory import JointPath, joint_path_to_msg
from door_contract.payloads import OutcomeStatus

pytestmark = pytest.mark.ros

ELBOW = "arm_right_4_joint"
DEADMAN_S = 3.0  # the default; at 1.5 s a bridge busy stepping on the loaded machine tripped it again


@pytest.fixture(scope="module")
def bridge(workspace, tmp_path_factory, rclpy_module_context):
    log = tmp_path_factory.mktemp("fuzz_bridge") / "sim.log"
    process = start_node(workspace, "sim_bridge", log, "camera_rate:=0.0", "real_time:=true",
                         f"supervisor_timeout:={DEADMAN_S}")
    observer = Observer(rclpy_module_context)
    observer.supervisor_beating = True  # the dead-man is armed from the first beat
    observer.wait_subscribed("ARM_TRAJECTORY", "FOOTSTEP_PLAN", "DIAGNOSTICS")
    assert observer.wait(lambda: observer.heartbeats.get("sim_bridge"), 60.0), log.read_text()
    observer.process = process
    yield observer
    observer.destroy()
    assert stop_node(process) == 0, log.read_text()[-3000:]


class Stamps:
    """Execution request ids: the stamp (s) of what is sent."""

    def __init__(self):
        self.sec = 100

    def next(self, msg):
        self.sec += 1
        msg.header.stamp.sec = self.sec
        return self.sec * 1_000_000_000


STAMPS = Stamps()


def _send(observer, topic, msg):
    request_id = STAMPS.next(msg)
    observer.pubs[topic].publish(msg)
    return request_id


def _trajectory(names, times, positions, velocities=None):
    msg = JointTrajectory(joint_names=list(names))
    for index, (time, row) in enumerate(zip(times, positions)):
        point = JointTrajectoryPoint(positions=[float(v) for v in row])
        if velocities is not None:
            point.velocities = [float(v) for v in velocities[index]]
        point.time_from_start.sec, point.time_from_start.nanosec = int(time), int(round((time % 1) * 1e9))
        msg.points.append(point)
    return msg


def _bad_trajectories(observer):
    elbow = observer.state().joints[ELBOW]
    return [
        ("NaN position", _trajectory([ELBOW], [1.0], [[float("nan")]]), "NaN"),
        ("infinite position", _trajectory([ELBOW], [1.0], [[float("inf")]]), "infinity"),
        ("unknown joint", _trajectory(["elbow_of_doom"], [1.0], [[0.0]]), "elbow_of_doom"),
        ("duplicate joints", _trajectory([ELBOW, ELBOW], [1.0], [[elbow, elbow]]), "unique"),
        ("too few positions", _trajectory([ELBOW, "arm_right_3_joint"], [1.0], [[elbow]]), "positions"),
        ("beyond the limits", _trajectory([ELBOW], [1.0], [[5.0]]), "limits"),
        ("too fast", _trajectory([ELBOW], [0.01], [[elbow - 1.0]]), "rad/s"),
        ("times going back", _trajectory([ELBOW], [2.0, 1.0], [[elbow], [elbow - 0.1]]), "increasing"),
        ("first point far from the arm", _trajectory([ELBOW], [0.0, 1.0], [[elbow - 1.0], [elbow - 1.0]]),
         "current position"),
        ("NaN velocity", _trajectory([ELBOW], [1.0], [[elbow - 0.1]], [[float("nan")]]), "NaN"),
        ("no joint names", _trajectory([], [1.0], [[]]), "joint"),
    ]


def _raw_path(steps):
    """A Path of the steps as given (the contract's converter would refuse NaN before sending)."""
    path = PathMsg()
    path.header.frame_id = "odom"
    for step in steps:
        pose = PoseStamped()
        pose.header.frame_id = "odom"
        pose.pose.position.x, pose.pose.position.y = float(step.x), float(step.y)
        pose.pose.orientation.z, pose.pose.orientation.w = math.sin(step.yaw / 2), math.cos(step.yaw / 2)
        path.poses.append(pose)
    return path


def _bad_plans(observer):
    plan = observer.walk_plan(2)
    left, right = plan
    return [
        ("NaN step", [FootPlacement(left.foot, float("nan"), left.y, 0.0), right], "NaN"),
        ("the right foot's place as the first (left) step", [right, left], "legs cross"),
        ("a stride of 2 m", [FootPlacement(left.foot, left.x + 2.0, left.y, 0.0), right], "max_stride"),
        ("crossed legs", [FootPlacement(left.foot, left.x, right.y - 0.1, 0.0), right], "cross"),
        ("a 90° turn", [FootPlacement(left.foot, left.x, left.y, 1.57), right], "max_turn"),
    ]


def test_bad_trajectories_are_rejected_and_move_nothing(bridge):
    before = bridge.settled_state()
    for name, msg, words in _bad_trajectories(bridge):
        request_id = _send(bridge, "ARM_TRAJECTORY", msg)
        outcome = bridge.wait_answer("execution", request_id)
        assert outcome.status is OutcomeStatus.REJECTED and words in outcome.reason, (name, outcome.reason)
    _assert_still(bridge, before)
    bridge.assert_lives(bridge.process, "sim_bridge")


def test_bad_footstep_plans_are_rejected_and_move_nothing(bridge):
    before = bridge.settled_state()
    for name, steps, words in _bad_plans(bridge):
        request_id = _send(bridge, "FOOTSTEP_PLAN", _raw_path(steps))
        outcome = bridge.wait_answer("execution", request_id)
        assert outcome.status is OutcomeStatus.REJECTED and words in outcome.reason, (name, outcome.reason)
    _assert_still(bridge, before)
    bridge.assert_lives(bridge.process, "sim_bridge")


def test_a_bad_crouch_is_refused_and_a_good_one_lowers_the_next_walk(bridge):
    """/walking/crouch: a value the walker cannot take is REJECTED (request id 0: it names no
    plan), moves nothing and leaves the crouch as it was; a good one is taken (the heartbeat
    says so) and the next walk goes that much lower (a negative one: higher); back at 0 the next
    walk stands up again."""
    before = bridge.settled_state()
    for value, words in ((math.nan, "not a finite number"), (-0.06, "outside"), (0.4, "outside")):
        count = len(bridge.answers("execution", 0))
        bridge.pubs["WALK_CROUCH"].publish(Float64(data=value))
        assert bridge.wait(lambda n=count: len(bridge.answers("execution", 0)) > n), value
        outcome = bridge.answers("execution", 0)[-1]
        assert outcome.status is OutcomeStatus.REJECTED and words in outcome.reason, outcome.reason
        assert "walks keep 0.000 m" in outcome.reason
    _assert_still(bridge, before)
    bridge.assert_lives(bridge.process, "sim_bridge")
    for crouch, height in ((0.06, before.base[2] - 0.06), (-0.04, before.base[2] + 0.04), (0.0, before.base[2])):
        bridge.pubs["WALK_CROUCH"].publish(Float64(data=crouch))
        assert bridge.wait(lambda c=crouch: bridge.values.get("sim_bridge", {}).get("crouch") == f"{c:.3f}")
        request_id = _send(bridge, "FOOTSTEP_PLAN", footsteps_to_path(bridge.walk_plan(2)))
        assert bridge.wait_answer("execution", request_id, 60.0).status is OutcomeStatus.SUCCESS
        assert bridge.settled_state().base[2] == pytest.approx(height, abs=0.01)


def test_a_stop_with_nothing_running_moves_nothing(bridge):
    before = bridge.settled_state()
    count = len(bridge.outcomes["execution"])
    _send(bridge, "ARM_TRAJECTORY", JointTrajectory())
    _send(bridge, "FOOTSTEP_PLAN", footsteps_to_path([]))
    bridge.assert_lives(bridge.process, "sim_bridge")
    assert len(bridge.outcomes["execution"]) == count  # nothing to report
    _assert_still(bridge, before)


def test_an_empty_trajectory_stops_the_arm_and_holds(bridge):
    start = bridge.settled_state().joints[ELBOW]
    goal = start - 0.5
    request_id = _send(bridge, "ARM_TRAJECTORY", joint_path_to_msg(JointPath(np.array([5.0]), (ELBOW,),
                                                                             np.array([[goal]]))))
    assert bridge.wait(lambda: abs(bridge.joints[ELBOW] - start) > 0.05, 30.0)
    _send(bridge, "ARM_TRAJECTORY", JointTrajectory())
    outcome = bridge.wait_answer("execution", request_id)
    assert outcome.status is OutcomeStatus.STOPPED and "without points" in outcome.reason, outcome
    held = bridge.settled_state(samples=10).joints[ELBOW]
    assert abs(bridge.settled_state(samples=25).joints[ELBOW] - held) < 5e-3  # it holds
    assert abs(held - goal) > 0.2  # it did not go on


def test_an_empty_path_stops_the_walk_at_the_next_stable_stance(bridge):
    start = bridge.settled_state().base
    plan = bridge.walk_plan(20)  # ~15 s of walking for the physical robot
    request_id = _send(bridge, "FOOTSTEP_PLAN", footsteps_to_path(plan))
    assert bridge.wait(lambda: np.linalg.norm(bridge.base - start) > 0.02, 30.0)
    _send(bridge, "FOOTSTEP_PLAN", footsteps_to_path([]))
    outcome = bridge.wait_answer("execution", request_id)
    assert outcome.status is OutcomeStatus.STOPPED and "stopped after step" in outcome.reason, outcome
    steps_done = int(outcome.reason.split("after step ")[1].split(" ")[0])
    assert steps_done < len(plan) - 6  # it stopped long before the plan's end
    stopped = bridge.settled_state().base
    assert np.linalg.norm(bridge.settled_state(samples=25).base - stopped) < 2e-3  # standing (sub-mm sway)


def test_the_dead_man_stops_everything_when_the_supervisor_falls_silent(bridge):
    start = bridge.settled_state().joints[ELBOW]
    request_id = _send(bridge, "ARM_TRAJECTORY", joint_path_to_msg(JointPath(np.array([10.0]), (ELBOW,),
                                                                             np.array([[start + 0.4]]))))
    assert bridge.wait(lambda: abs(bridge.joints[ELBOW] - start) > 0.03, 30.0)
    bridge.supervisor_beating = False
    outcome = bridge.wait_answer("execution", request_id, timeout_s=DEADMAN_S + 10.0)
    assert outcome.status is OutcomeStatus.STOPPED and "dead-man" in outcome.reason, outcome
    assert abs(bridge.joints[ELBOW] - (start + 0.4)) > 0.1
    refused = _send(bridge, "ARM_TRAJECTORY", joint_path_to_msg(JointPath(np.array([1.0]), (ELBOW,),
                                                                          np.array([[start]]))))
    assert "heartbeat lost" in bridge.wait_answer("execution", refused).reason
    back = "is back: executions accepted"  # not "… refused until it is back", a refusal's reason
    backs = bridge.process.log.read_text().count(back)
    bridge.supervisor_beating = True  # back: executions are accepted again
    assert bridge.wait(lambda: bridge.process.log.read_text().count(back) > backs, 10.0)
    accepted = _send(bridge, "ARM_TRAJECTORY", joint_path_to_msg(JointPath(np.array([1.0]), (ELBOW,),
                                                                           np.array([[start]]))))
    assert bridge.wait_answer("execution", accepted).status is OutcomeStatus.SUCCESS


def test_a_burst_of_100_grasp_calls_gets_100_answers(bridge):
    """Issue #12: 20 of 100 were answered. Opening a hand that holds nothing moves nothing."""
    client = bridge.grasp["/right_hand/grasp"]
    assert client.wait_for_service(timeout_sec=30.0)
    before = bridge.settled_state()
    futures = [client.call_async(SetBool.Request(data=False)) for _ in range(100)]
    assert bridge.wait(lambda: all(f.done() for f in futures), 60.0), sum(f.done() for f in futures)
    assert all(f.result() is not None for f in futures)
    _assert_still(bridge, before)


def _assert_still(observer, before):
    joints, base, door = observer.settled_state().moved(before)
    assert joints < 3e-3 and base < STILL_BASE and door < 1e-3, (joints, base, door)
