"""The Docker image is built as on a real Jazzy install: every package.xml names what its code
imports — message packages it reaches through door_contract's Topics/Services included — and
nothing it does not, with keys rosdep resolves; the keys rosdep cannot (or must not) install are exactly
docker/pip-keys.txt, which the image installs from requirements.txt with pip instead; no ROS
wheels from PyPI; no venv, runs or build trees in the build context, and every link in it
(params/, ros_ws/src) resolves inside it."""

import ast
import os
import re
import sys
import xml.etree.ElementTree as ElementTree
from fnmatch import fnmatch
from pathlib import Path, PurePosixPath

import pytest

PACKAGES = ("msgs", "sim_bridge", "src/door_robot", "src/door_detection", "src/footstep_planner", "src/door_trajopt",
            "src/door_fsm", "src/door_bringup", "src/door_viz", "src/door_evaluation")
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


INTERFACE_NAME = re.compile(r"^(\w+)/(?:msg|srv|action)/\w+$")
#: declared, never imported by the package's code, and needed all the same (why)
RUNTIME_ONLY = {
    "src/door_robot": {"python3-example-robot-data-pip": "the profiles' URDFs and meshes are its data files"},
    "src/door_bringup": {"ros2bag": "a run's bags are read with `ros2 bag` on a real install",
                         "rosbag2_storage_mcap": "`ros2 bag` reads the mcap bags (--storage mcap)"},
}


def _name_and_depends(workspace, folder):
    root = ElementTree.parse(workspace.root / folder / "package.xml").getroot()
    depends = {e.text for tag in ("exec_depend", "depend") for e in root.iter(tag)}
    return root.find("name").text, depends


def _trees(workspace, folder):
    for path in sorted((workspace.root / folder).rglob("*.py")):
        if path.name == "setup.py" or "test" in path.parts:
            continue
        yield ast.parse(path.read_text())


def _interface_packages(workspace, folder):
    """The message packages the code imports by name: door_contract's ``interface_class`` imports
    the type of every ``Topics.X`` / ``Services.X`` a node subscribes to, publishes or serves
    (also ``getattr(Topics, "X")`` with a literal name, and ``Services.all()``), and every
    interface it names in full (``"sensor_msgs/msg/Image"``: the contract's own topic table)."""
    from door_contract.topics import Services, ServiceSpec, Topics, TopicSpec
    tables = {"Topics": Topics, "Services": Services}
    packages = set()
    for tree in _trees(workspace, folder):
        nodes = list(ast.walk(tree))
        names = {(n.value.id, n.attr) for n in nodes if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name)
                 and n.value.id in tables}
        if any(table == "Topics" for table, _ in names):  # getattr(Topics, t) over literal names
            names |= {("Topics", n.value) for n in nodes if isinstance(n, ast.Constant) and isinstance(n.value, str)}
        packages |= {match.group(1) for n in nodes if isinstance(n, ast.Constant) and isinstance(n.value, str)
                     for match in [INTERFACE_NAME.match(n.value)] if match}  # "sensor_msgs/msg/Image"
        specs = [getattr(tables[table], attr, None) for table, attr in names]
        if ("Services", "all") in names:
            specs += Services.all()
        packages |= {s.type_name.split("/")[0] for s in specs if isinstance(s, (TopicSpec, ServiceSpec))}
    return packages


def _imports(workspace, folder, own_modules):
    modules = set()
    for tree in _trees(workspace, folder):
        for node in ast.walk(tree):
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
    for module in _imports(workspace, folder, {name}) | _interface_packages(workspace, folder):
        key = IMPORT_KEYS.get(module, module)
        assert key in IMPORT_KEYS.values() or key in ROS_PACKAGES or key in workspace_packages, \
            f"{folder} imports {module}: add it to IMPORT_KEYS with its rosdep key"
        if key not in depends:
            missing.add(key)
    assert not missing, f"{folder}/package.xml lacks exec_depend {sorted(missing)}"


@pytest.mark.parametrize("folder", PACKAGES)
def test_package_xml_names_nothing_the_package_does_not_use(workspace, folder):
    name, depends = _name_and_depends(workspace, folder)
    used = {IMPORT_KEYS.get(m, m) for m in _imports(workspace, folder, {name}) | _interface_packages(workspace, folder)}
    stale = depends - used - set(RUNTIME_ONLY.get(folder, {}))
    assert not stale, f"{folder}/package.xml declares {sorted(stale)}, which its code never imports " \
                      f"(or name it in RUNTIME_ONLY with the reason)"


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



def _dockerignored(relative, patterns):
    """Whether ``.dockerignore`` leaves ``relative`` (or a folder above it) out of the context."""
    prefixes = [PurePosixPath(*relative.parts[:i]) for i in range(1, len(relative.parts) + 1)]
    return any(fnmatch(prefix.as_posix(), pattern) or (pattern.startswith("**/") and fnmatch(prefix.name, pattern[3:]))
               for prefix in prefixes for pattern in patterns)


def _build_context_links(root, patterns):
    """Every symbolic link Docker's ``COPY . .`` copies (as a link: COPY does not follow them)."""
    for folder, subfolders, files in os.walk(root):
        relative = Path(folder).relative_to(root)
        subfolders[:] = [s for s in subfolders if not _dockerignored(relative / s, patterns)]
        for name in subfolders + files:
            if (Path(folder) / name).is_symlink() and not _dockerignored(relative / name, patterns):
                yield Path(folder) / name


def test_every_link_in_the_build_context_resolves_inside_it(workspace):
    """params/ links to the files the packages own, ros_ws/src to the packages: in the image they
    resolve only if relative and pointing at something COPY brings along (not dockerignored)."""
    patterns = [line.strip() for line in (workspace.root / ".dockerignore").read_text().splitlines()
                if line.strip() and not line.startswith("#")]
    root = workspace.root.resolve()
    links = list(_build_context_links(root, patterns))
    assert {"params", "ros_ws"} <= {link.relative_to(root).parts[0] for link in links}
    for link in links:
        assert not Path(os.readlink(link)).is_absolute(), link
        target = link.resolve()
        assert target.exists() and target.is_relative_to(root), link
        assert not _dockerignored(target.relative_to(root), patterns), link
