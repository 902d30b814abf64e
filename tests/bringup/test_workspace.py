"""The colcon workspace: what ``ros2 run`` looks up exists, and each executable, started as a
process over real DDS, shows its node in the graph and shuts down cleanly on SIGINT."""

import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest
import rclpy
from ros_helpers import executor_for, node_names, spin_until

from door_bringup.graph_spec import GRAPH
from door_bringup.processes import ProcessSupervisor, stopped_cleanly
from door_bringup.workspace import WorkspaceError, find_repository_root


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


@pytest.mark.ros
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
    assert set(codes) == expected and all(stopped_cleanly(code) for code in codes.values()), _logs(tmp_path)


@pytest.mark.parametrize("launch, overrides, message", [
    (GRAPH[1], ["vote_frames:=0"], r"'vote_frames'.*\[1, 100\]"),
    (GRAPH[4], ["autonomy:=yolo"], r"'autonomy'.*one of 'full', 'supervised', 'step'"),
    (GRAPH[0], ["physics_rate:=5.0"], r"'physics_rate'.*\[60, 2000\] Hz"),
    # issue #12: these exited 1 with a traceback
    (GRAPH[1], ["door_width_min:=1.2", "door_width_max:=1.0"], r"'door_width_min' must not exceed 'door_width_max'"),
    (GRAPH[0], ["robot_profile:=nonexistent"], r"robot profile not found"),
    (GRAPH[1], ["robot_profile:=nonexistent"], r"'robot_profile' = 'nonexistent'.*not found"),
    (GRAPH[2], ["robot_profile:=nonexistent"], r"robot profile not found"),
    (GRAPH[3], ["robot_profile:=nonexistent"], r"'robot_profile' = 'nonexistent'.*not found"),
    (GRAPH[4], ["robot_profile:=nonexistent"], r"'robot_profile' = 'nonexistent'.*not found"),
])
@pytest.mark.ros  # each node starts (a DDS participant) before it reads its parameters
def test_bad_parameter_stops_the_node_with_one_line(workspace, launch, overrides, message):
    command = [str(workspace.executable(launch.package, launch.executable)), "--ros-args",
               "--params-file", str(workspace.params_file(launch.node_name))]
    for override in overrides:
        command += ["-p", override]
    result = subprocess.run(command, env=workspace.environment(), capture_output=True, text=True, timeout=60)
    output = result.stdout + result.stderr
    assert result.returncode == 2, output
    assert re.search(message, output), output
    assert "Traceback" not in output and len([line for line in output.splitlines() if "FATAL" in line]) == 1, output


@pytest.mark.ros
def test_an_undeclared_parameter_is_reported(workspace, tmp_path):
    fsm = GRAPH[4]
    command = [str(workspace.executable(fsm.package, fsm.executable)), "--ros-args", "-p", "aproval_timeout:=5.0",
               "-p", "required_nodes:=['nobody']"]
    log = tmp_path / "fsm.log"
    process = subprocess.Popen(command, env=workspace.environment(), stdout=log.open("w"), stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 30.0
        while "ready:" not in log.read_text() and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.05)  # polling the log file for a condition, with a deadline
    finally:
        process.send_signal(2)
        process.wait(timeout=20)
    assert "parameter 'aproval_timeout' is not a parameter of /fsm_supervisor and is ignored; did you mean " \
           "'approval_timeout'?" in log.read_text()


def test_the_installed_copy_finds_its_checkout(workspace):
    installed = next((workspace.install / "door_bringup").rglob("door_bringup/workspace.py"))
    assert find_repository_root(installed) == workspace.root
    with pytest.raises(WorkspaceError, match="DOOR_WORKSPACE"):
        find_repository_root(Path("/tmp/elsewhere/x.py"))


def test_sourcing_the_workspace_keeps_discovery_on_this_machine(workspace):
    """The colcon hook of door_contract: LOCALHOST unless the user chose a range (no DDS here)."""
    script = f"set +u; . {workspace.install}/setup.sh; echo \"range=$ROS_AUTOMATIC_DISCOVERY_RANGE\""
    for given, expected in ((None, "LOCALHOST"), ("SUBNET", "SUBNET")):
        env = {k: v for k, v in os.environ.items() if k != "ROS_AUTOMATIC_DISCOVERY_RANGE"}
        if given:
            env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = given
        result = subprocess.run(["sh", "-c", script], env=env, capture_output=True, text=True, timeout=30)
        assert f"range={expected}" in result.stdout, result.stdout + result.stderr


def test_every_entry_point_defaults_discovery_to_localhost():
    """Each command creates its participant only after keep_discovery_local (no DDS started here)."""
    import inspect

    from door_bringup import door_task, graph, ros2_cli
    from door_bringup.bags import player
    from door_contract import node_support
    for module, function in ((node_support, "run_node"), (graph, "check_graph"), (door_task, "run_task"),
                             (ros2_cli, "_topic"), (player, "_play")):
        source = inspect.getsource(getattr(module, function))
        assert source.index("keep_discovery_local()") < source.index("rclpy.init("), module.__name__


def _logs(log_dir: Path) -> str:
    return "\n".join(f"--- {p.name}\n{p.read_text()[-2000:]}" for p in sorted(log_dir.glob("*.log")))


def test_the_installed_door_robot_finds_the_robot_profiles_in_its_own_share(workspace, tmp_path):
    """Robot profiles are door_robot's: installed in share/door_robot/profiles and found there
    through the ament index (no checkout params/, no $DOOR_PARAMS_DIR, nothing of door_bringup)."""
    env = workspace.environment()
    env.pop("DOOR_PARAMS_DIR")
    script = ("import door_robot.locations, door_robot.profile as p; print(door_robot.locations.__file__); "
              "print(p.profile_path('talos')); p.load_profile('talos')")
    result = subprocess.run([sys.executable, "-c", script], env=env, cwd=tmp_path, capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    module, profile = result.stdout.split()
    share = workspace.install / "door_robot" / "share" / "door_robot" / "profiles"
    assert Path(module).is_relative_to(workspace.install / "door_robot")  # the installed copy, not the sources
    assert Path(profile) == share / "robot_talos.yaml"
    sources = workspace.root / "src" / "door_robot" / "profiles"
    assert {p.name for p in share.iterdir()} == {p.name for p in sources.glob("robot_*.yaml")}
    assert not list((workspace.install / "door_bringup" / "share" / "door_bringup" / "params").glob("robot_*"))


def test_the_installed_door_bringup_has_its_node_parameter_files(workspace):
    """door_bringup installs its own params/ (what launch/door_task.launch.py reads installed)."""
    share = workspace.install / "door_bringup" / "share" / "door_bringup" / "params"
    sources = workspace.root / "src" / "door_bringup" / "params"
    assert {p.name for p in share.glob("*.yaml")} == {p.name for p in sources.glob("*.yaml")} \
        >= {f"{launch.node_name}.yaml" for launch in GRAPH}


def test_params_links_each_file_to_the_package_that_owns_it(workspace):
    """params/ is where the README sends users (``--params-file params/<node>.yaml``,
    ``params/robot_<name>.yaml``); the files are the packages' own (issue #17), linked relatively
    so that any clone, tarball or Docker build context resolves them."""
    entries = sorted((workspace.root / "params").iterdir())
    assert entries
    for entry in entries:
        assert entry.is_symlink() and not Path(os.readlink(entry)).is_absolute(), \
            f"{entry}: move the file into the package that reads it and link it from params/"
        target = entry.resolve()
        package = next((folder for folder in target.parents if (folder / "package.xml").is_file()), None)
        assert target.is_file() and package is not None and package.parent == (workspace.root / "src").resolve(), entry


LEAVES_THE_FOLDER = re.compile(r"(^|/)\.\.(/|$)")


def test_every_setup_py_names_only_files_in_its_own_folder(workspace):
    """A setup.py that globs ``../../params`` builds only inside this checkout (not from a
    tarball, nor in a build of one package): no path in it leaves the package folder."""
    import ast

    for package in sorted((workspace.root / "ros_ws" / "src").iterdir()):
        tree = ast.parse((package / "setup.py").read_text())
        in_f_strings = {id(part) for n in ast.walk(tree) if isinstance(n, ast.JoinedStr) for part in n.values}
        strings = [n.value for n in ast.walk(tree)  # f-strings name install destinations (f"share/{PACKAGE}/params")
                   if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in in_f_strings]
        outside = [s for s in strings if LEAVES_THE_FOLDER.search(s) or s.startswith("/")]
        assert not outside, f"{package.name}/setup.py names {outside}"
