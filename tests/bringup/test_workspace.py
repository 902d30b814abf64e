"""The colcon workspace: what ``ros2 run`` looks up exists, and each executable, started as a
process over real DDS, shows its node in the graph and shuts down cleanly on SIGINT."""

import re
import subprocess
from pathlib import Path

import pytest
import rclpy

from door_bringup.graph_spec import GRAPH
from door_bringup.processes import ProcessSupervisor
from door_bringup.workspace import WorkspaceError
from ros_helpers import executor_for, node_names, spin_until


def test_colcon_install_has_every_executable_and_ament_index_entry(workspace):
    for launch in GRAPH:
        prefix = workspace.install / launch.package
        assert (prefix / "share" / "ament_index" / "resource_index" / "packages" / launch.package).is_file()
        assert (prefix / "share" / launch.package / "package.xml").is_file()
        executable = workspace.executable(launch.package, launch.executable)
        assert executable == prefix / "lib" / launch.package / launch.executable


def test_unknown_package_or_executable(workspace):
    with pytest.raises(WorkspaceError, match="not found"):
        workspace.executable("no_such_package", "x")
    with pytest.raises(WorkspaceError, match="no executable"):
        workspace.executable("door_fsm", "no_such_executable")


def test_every_executable_starts_its_node_and_stops_on_sigint(workspace, rclpy_context, tmp_path):
    supervisor = ProcessSupervisor(workspace, tmp_path)
    probe = rclpy.create_node("workspace_test_probe", context=rclpy_context)
    executor = executor_for(probe, rclpy_context)
    expected = {launch.node_name for launch in GRAPH}
    try:
        for launch in GRAPH:
            supervisor.start(launch)
        up = spin_until(executor, lambda: expected <= node_names(probe) or bool(supervisor.exited()), 60.0)
        assert up and expected <= node_names(probe), _logs(tmp_path)
    finally:
        codes = supervisor.stop()
        probe.destroy_node()
    assert codes == {name: 0 for name in expected}, _logs(tmp_path)


@pytest.mark.parametrize("launch, override, message", [
    (GRAPH[1], "vote_frames:=0", r"'vote_frames'.*\[1, 100\]"),
    (GRAPH[4], "autonomy:=yolo", r"'autonomy'.*one of 'full', 'supervised', 'step'"),
    (GRAPH[0], "physics_rate:=5.0", r"'physics_rate'.*\[60, 2000\] Hz"),
])
def test_bad_parameter_stops_the_node_with_a_message(workspace, launch, override, message):
    command = [str(workspace.executable(launch.package, launch.executable)), "--ros-args",
               "--params-file", str(workspace.params_file(launch.node_name)), "-p", override]
    result = subprocess.run(command, env=workspace.environment(), capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert re.search(message, result.stdout + result.stderr), result.stderr


def _logs(log_dir: Path) -> str:
    return "\n".join(f"--- {p.name}\n{p.read_text()[-2000:]}" for p in sorted(log_dir.glob("*.log")))
