"""The main job gives a run up after ``timeout_s`` of the robot's time, not of the wall clock:
with two graphs per core the simulation runs slower than real time, and a wall-clock limit
ended trials that were still working (issue #13: success independent of load)."""

import time

import pytest
import rclpy

from door_bringup.door_task import ScriptedOperator, _wait_for_report
from door_bringup.graph_spec import GRAPH
from door_bringup.processes import ProcessSupervisor

pytestmark = pytest.mark.ros  # the sim bridge as a process, its /odom over DDS


def test_a_run_without_a_report_ends_after_its_timeout_of_robot_time(workspace, tmp_path):
    sim_bridge = next(launch for launch in GRAPH if launch.node_name == "sim_bridge")
    supervisor = ProcessSupervisor(workspace, tmp_path)
    rclpy.init()
    operator = ScriptedOperator(approve=False)
    started = time.monotonic()  # before the sim's clock starts: the robot's time cannot outrun this
    try:
        # no FSM: no report ever comes; paced so that its clock never runs ahead of the wall clock
        supervisor.start(sim_bridge, ["-p", "camera_rate:=0.0", "-p", "real_time:=true"])
        report = _wait_for_report(operator, supervisor, timeout_s=3.0)
        waited = time.monotonic() - started
    finally:
        codes = supervisor.stop()
        operator.destroy_node()
        rclpy.try_shutdown()
    assert report["final_state"] == "FAILED" and report["attempts"] == []
    assert report["failure_reason"] == "no TaskReport within 3 s of the robot's time", report
    assert operator.robot_time_s > 3.0 and waited >= 3.0  # paced: at most real time
    assert codes == {"sim_bridge": 0}
