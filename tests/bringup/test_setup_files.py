"""The README's commands, CI, Docker image and requirements agree with each other."""

import re

import pytest


def test_ci_runs_the_readme_test_command(workspace):
    readme = (workspace.root / "README.md").read_text()
    ci = (workspace.root / ".ci" / "run").read_text()
    assert "./setup.sh" in readme and "./test.sh" in readme
    assert re.search(r"^\./test\.sh\s*$", ci, re.MULTILINE)


def test_dockerfile_installs_the_same_requirements_and_builds_the_workspace(workspace):
    dockerfile = (workspace.root / "docker" / "Dockerfile").read_text()
    assert dockerfile.startswith("FROM ros:jazzy") or "\nFROM ros:jazzy" in dockerfile
    assert "requirements.txt" in dockerfile
    assert "colcon build" in dockerfile


def test_requirements_are_pinned(workspace):
    for line in (workspace.root / "requirements.txt").read_text().splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            assert "==" in line or line.startswith("setuptools<"), line


@pytest.mark.parametrize("folder", ["ros_ws", "src", "msgs", "params", "sim_bridge", "tests", "docker"])
def test_layout_of_design_md(workspace, folder):
    assert (workspace.root / folder).is_dir()


def test_ros_ws_links_every_package(workspace):
    linked = {p.name for p in (workspace.root / "ros_ws" / "src").iterdir() if (p / "package.xml").is_file()}
    assert {"door_contract", "door_robot", "door_sim_bridge", "door_detection", "footstep_planner",
            "door_trajopt", "door_fsm", "door_bringup", "door_viz", "door_evaluation"} <= linked
