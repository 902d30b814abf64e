"""The main job end to end: the whole graph as separate processes over real DDS, under
supervised autonomy with a scripted operator approving: a push door, recorded to a rosbag
(then the recorded camera topics replayed into a fresh detector reproduce its estimate),
and a pull door."""

import subprocess

import numpy as np
import pytest
import rclpy
from rclpy.serialization import deserialize_message
from ros_helpers import executor_for, spin_until

from door_bringup.bags.storage import read_messages
from door_bringup.door_task import TaskOptions, run_task
from door_bringup.graph_spec import GRAPH
from door_bringup.processes import stopped_cleanly
from door_contract.node_support import create_contract_subscription
from door_contract.payloads import DoorEstimate, decode
from door_contract.topics import Topics

pytestmark = [pytest.mark.slow, pytest.mark.ros]  # the whole graph as processes


@pytest.fixture(scope="module")
def push_run(workspace, tmp_path_factory):
    run_dir = tmp_path_factory.mktemp("push_run")
    options = TaskOptions(opening="push", hinge="left", autonomy="supervised", operator="auto",
                          timeout_s=600.0, record=True)
    report = run_task(options, run_dir, workspace)
    return run_dir, report


@pytest.fixture(scope="module")
def pull_run(workspace, tmp_path_factory):
    run_dir = tmp_path_factory.mktemp("pull_run")
    options = TaskOptions(opening="pull", hinge="right", autonomy="supervised", operator="auto",
                          timeout_s=600.0, record=False)
    return run_task(options, run_dir, workspace)


def _messages(bag, topic):
    return [deserialize_message(m.data, topic.msg_class()) for m in read_messages(bag, [topic.name])]


def _fell_safely_or_done(report) -> None:
    """The run ended DONE, or FAILED in the walk through (issue #11's open gap, below): the
    robot fell, or a pull door's tuck stopped with the wrist held off its goal by the leaf
    (footstep_planner.pull_passage); never by anything else."""
    if report["final_state"] == "DONE":
        return
    assert report["final_state"] == "FAILED"
    last = report["attempts"][-1]
    fell = last["state"].startswith("WALK_THROUGH") and last["outcome"] == "fell"
    tuck_stopped = (last["state"], last["outcome"]) == ("WALK_THROUGH/TUCK", "failed")
    assert fell or tuck_stopped, report["failure_reason"]


def _walk_through_done(report) -> None:
    """Known gap (issue #11): on the physical robot the walk through the doorway, where the
    body shoves the 25 kg leaf (push) or passes it on the blocking hand (pull), still falls in
    some runs (the full-range Monte-Carlo: 44 of 50 doors DONE, every failure but one a fall
    walking through; these two doors reached DONE in stop 29's suite); every phase before it
    succeeds. Reported as xfail, not a failure, until the campaign reaches issue #11's 98 %."""
    if report["final_state"] != "DONE":
        pytest.xfail(f"walk-through on the physical robot (issue #11): {report['failure_reason']}")


def test_push_door_is_detected_approached_and_opened(push_run):
    run_dir, report = push_run
    _fell_safely_or_done(report)
    states = [a["state"] for a in report["attempts"] if a["outcome"] == "succeeded"]
    for state in ("DETECT_DOOR", "WALK_TO_DOOR", "OPEN_DOOR/TURN_HANDLE", "OPEN_DOOR/PUSH", "OPEN_DOOR/READY_TO_WALK"):
        assert state in states
    assert all(stopped_cleanly(code) for code in report["exit_codes"].values()), report["exit_codes"]
    approvals = [m.data for m in _messages(run_dir / "bag", Topics.APPROVAL_REQUEST) if m.data]
    assert any(text.startswith("DETECT_DOOR") for text in approvals)  # supervised: the operator was asked
    door = _messages(run_dir / "bag", Topics.DOOR_JOINT_STATES)
    assert max(d.position[0] for d in door) > 0.15  # the hinge opened


def test_nothing_moves_after_the_walk_through_ends(push_run):
    """Whatever the walk's outcome (a fall included), no command follows the task's end (its
    terminal state on /door_task/state: the FSM turns FAILED the moment the fall is reported;
    the recorder once missed that ExecutionOutcome itself, so the state is the reference)."""
    run_dir, report = push_run
    bag = run_dir / "bag"
    ends = [m for m in read_messages(bag, [Topics.TASK_STATE.name])
            if deserialize_message(m.data, Topics.TASK_STATE.msg_class()).data == report["final_state"]]
    assert ends
    last = ends[0].timestamp_ns
    later = []  # motion commands after it (an empty trajectory or plan is a stop, not motion)
    for topic, field in ((Topics.ARM_TRAJECTORY, "points"), (Topics.FOOTSTEP_PLAN, "poses")):
        later += [m for m in read_messages(bag, [topic.name]) if m.timestamp_ns > last
                  and getattr(deserialize_message(m.data, topic.msg_class()), field)]
    assert not later


def test_push_door_is_traversed(push_run):
    run_dir, report = push_run
    _walk_through_done(report)
    final_base = _messages(run_dir / "bag", Topics.ODOM)[-1].pose.pose.position
    assert final_base.x > 0.5  # beyond the wall plane at x = 0
    # the DRC door is 0.914 m wide: the pushing arm tucks in the doorway (footstep_planner.push_passage)
    states = [a["state"] for a in report["attempts"] if a["outcome"] == "succeeded"]
    assert states[-3:] == ["WALK_THROUGH/TO_DOORWAY", "WALK_THROUGH/TUCK", "WALK_THROUGH"]


def test_pull_door_is_pulled_and_blocked(pull_run):
    """[Banerjee 2015] Fig. 2: pull with the hinge-side hand, block with the other."""
    report = pull_run
    _fell_safely_or_done(report)
    states = [a["state"] for a in report["attempts"] if a["outcome"] == "succeeded"]
    for state in ("WALK_TO_DOOR", "OPEN_DOOR/PULL", "OPEN_DOOR/BLOCK", "OPEN_DOOR/READY_TO_WALK"):
        assert state in states
    assert "OPEN_DOOR/PUSH" not in states
    assert all(stopped_cleanly(code) for code in report["exit_codes"].values()), report["exit_codes"]


def test_pull_door_is_traversed(pull_run):
    """... and walk through."""
    report = pull_run
    _walk_through_done(report)
    assert report["final_base_xy"][0] > 0.5  # beyond the wall plane at x = 0
    states = [a["state"] for a in report["attempts"] if a["outcome"] == "succeeded"]
    assert states[-3:] == ["WALK_THROUGH/TO_DOORWAY", "WALK_THROUGH/TUCK", "WALK_THROUGH"]


def test_recorded_camera_replayed_into_a_detector_reproduces_its_estimate(push_run, workspace, rclpy_context):
    run_dir, _ = push_run
    bag = run_dir / "bag"
    recorded = [decode(DoorEstimate, m.data) for m in _messages(bag, Topics.DOOR_ESTIMATE)]
    assert recorded
    detector = next(launch for launch in GRAPH if launch.node_name == "door_detector")
    node = rclpy.create_node("replay_listener", context=rclpy_context)
    replayed = []
    create_contract_subscription(node, Topics.DOOR_ESTIMATE, lambda m: replayed.append(decode(DoorEstimate, m.data)))
    executor = executor_for(node, rclpy_context)
    process = subprocess.Popen([str(workspace.executable(detector.package, detector.executable)), "--ros-args",
                                "--params-file", str(workspace.params_file("door_detector"))],
                               env=workspace.environment(), stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    camera = [Topics.COLOR_IMAGE.name, Topics.DEPTH_IMAGE.name, Topics.COLOR_INFO.name, Topics.CAMERA_POSE.name]
    player = subprocess.Popen([str(workspace.executable("door_bringup", "bag_play")), str(bag), "--rate", "1",
                               "--wait-for-subscribers", "30", "--topics", *camera],
                              env=workspace.environment(), stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    try:
        assert spin_until(executor, lambda: bool(replayed), 120.0)
    finally:
        player.kill()
        process.send_signal(2)
        process.wait(timeout=20)
        node.destroy_node()
    # The live detector may have joined later than the recorder (or the reverse), so the
    # voting windows can start at different frames: the consensus must agree, not the stamp.
    first, again = recorded[0], replayed[0]
    assert np.linalg.norm(np.subtract(again.handle_position, first.handle_position)) < 0.005
    assert np.degrees(np.arccos(np.clip(np.dot(again.normal, first.normal), -1, 1))) < 1.0
    assert again.hinge_side == first.hinge_side
