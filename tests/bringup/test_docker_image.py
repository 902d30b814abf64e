"""The Docker image is built as on a real Jazzy install: every package.xml names what its code
imports, with keys rosdep resolves; the keys rosdep cannot (or must not) install are exactly
docker/pip-keys.txt, which the image installs from requirements.txt with pip instead; no ROS
wheels from PyPI; no venv, runs or build trees in the build context."""

import ast
import sys
import xml.etree.ElementTree as ElementTree

import pytest

PACKAGES = ("msgs", "sim_bridge", "src/door_robot", "src/door_detection", "src/footstep_planner", "src/door_trajopt",
            "src/door_fsm", "src/door_bringup", "src/door_viz")
IMPORT_KEYS = {  # top-level module -> rosdep key (rosdistro's rosdep/python.yaml names)
    "numpy": "python3-numpy", "scipy": "python3-scipy", "cv2": "python3-opencv", "yaml": "python3-yaml",
    "matplotlib": "python3-matplotlib", "open3d": "python3-open3d-pip", "pybullet": "python3-pybullet-pip",
    "rosbags": "python3-rosbags-pip", "osqp": "python3-osqp-pip", "foxglove": "python3-foxglove-sdk-pip",
    "pinocchio": "pinocchio", "placo": "python3-placo-pip",
}
#: imported only when installed by hand, for a benchmark (README "Peer benchmark"): no dependency
OPTIONAL_IMPORTS = {"tesseract_robotics"}
ROS_PACKAGES = {"rclpy", "rcl_interfaces", "builtin_interfaces", "std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs",
                "trajectory_msgs", "visualization_msgs", "diagnostic_msgs", "std_srvs", "rosgraph_msgs", "tf2_msgs",
                "launch", "launch_ros", "ament_index_python", "ros2bag", "rosbag2_storage_mcap"}


def _name_and_depends(workspace, folder):
    root = ElementTree.parse(workspace.root / folder / "package.xml").getroot()
    depends = {e.text for tag in ("exec_depend", "depend") for e in root.iter(tag)}
    return root.find("name").text, depends


def _imports(workspace, folder, own_modules):
    modules = set()
    for path in (workspace.root / folder).rglob("*.py"):
        if path.name == "setup.py" or "test" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                modules |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                modules.add(node.module.split(".")[0])
    return {m for m in modules if m not in sys.stdlib_module_names and m not in own_modules | OPTIONAL_IMPORTS}


@pytest.mark.parametrize("folder", PACKAGES)
def test_package_xml_names_every_import(workspace, folder):
    workspace_packages = {_name_and_depends(workspace, f)[0] for f in PACKAGES}
    name, depends = _name_and_depends(workspace, folder)
    missing = set()
    for module in _imports(workspace, folder, {name}):
        key = IMPORT_KEYS.get(module, module)
        assert key in IMPORT_KEYS.values() or key in ROS_PACKAGES or key in workspace_packages, \
            f"{folder} imports {module}: add it to IMPORT_KEYS with its rosdep key"
        if key not in depends:
            missing.add(key)
    assert not missing, f"{folder}/package.xml lacks exec_depend {sorted(missing)}"


def test_pip_keys_are_the_declared_keys_rosdep_does_not_install(workspace):
    pip_keys = set((workspace.root / "docker" / "pip-keys.txt").read_text().split())
    declared = set().union(*(_name_and_depends(workspace, f)[1] for f in PACKAGES))
    workspace_packages = {_name_and_depends(workspace, f)[0] for f in PACKAGES}
    apt_keys = {"python3-numpy", "python3-scipy", "python3-opencv", "python3-yaml", "python3-matplotlib"}
    assert declared - workspace_packages - ROS_PACKAGES - apt_keys == pip_keys


def test_dockerfile_takes_ros_from_the_image_and_only_the_rest_from_pypi(workspace):
    dockerfile = (workspace.root / "docker" / "Dockerfile").read_text()
    steps = [line for line in dockerfile.splitlines() if not line.lstrip().startswith("#")]
    text = "\n".join(steps)
    assert "rosdep install" in text and "--skip-keys" in text and "docker/pip-keys.txt" in text
    assert "grep -vE '^(ros-jazzy-|colcon-|setuptools)' requirements.txt" in text  # no second ROS
    assert "setup.sh" not in text and "venv" not in text


def test_dockerignore_leaves_out_the_venv_runs_and_build_trees(workspace):
    ignored = set((workspace.root / ".dockerignore").read_text().split())
    assert {".venv", "runs", "ros_ws/build", "ros_ws/install", "ros_ws/log", "interfaces/build"} <= ignored
