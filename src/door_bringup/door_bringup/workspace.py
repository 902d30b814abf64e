"""The colcon workspace as ``ros2 run`` sees it: ament index, executables, environment.

ros2cli is not on PyPI, so this reproduces the part of ``ros2 run`` the project needs: an
executable is ``<prefix>/lib/<package>/<executable>`` of the first prefix in
``AMENT_PREFIX_PATH`` whose ament index lists the package.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from door_robot.locations import find_checkout

__all__ = ["Workspace", "WorkspaceError", "find_repository_root", "repository_root"]


class WorkspaceError(RuntimeError):
    """The workspace is not built, or a package/executable is not in it."""


def repository_root() -> Path:
    """$DOOR_WORKSPACE, else the checkout this module is in — from the sources or from the
    colcon install inside the checkout (``ros_ws/install/door_bringup/lib/…``)."""
    if "DOOR_WORKSPACE" in os.environ:
        return Path(os.environ["DOOR_WORKSPACE"])
    return find_repository_root(Path(__file__))


def find_repository_root(start: Path) -> Path:
    """The checkout above ``start`` (:func:`door_robot.locations.find_checkout`); WorkspaceError
    outside one."""
    checkout = find_checkout(start)
    if checkout is None:
        raise WorkspaceError(f"no checkout (a folder with ros_ws/src and params/) above {start}; "
                             f"set DOOR_WORKSPACE")
    return checkout


@dataclass(frozen=True)
class Workspace:
    root: Path

    @property
    def install(self) -> Path:
        return self.root / "ros_ws" / "install"

    @property
    def params(self) -> Path:
        """The checkout's ``params/``, the paths the README and the nodes' command lines show: links
        to the files the packages own (door_bringup's ``src/door_bringup/params``: the node
        parameter files and the Fast DDS profile; door_robot's ``src/door_robot/profiles``)."""
        return self.root / "params"

    def package_prefixes(self) -> list[Path]:
        """Install prefixes of the built packages (colcon's isolated layout)."""
        if not self.install.is_dir():
            raise WorkspaceError(f"{self.install} does not exist: run the README's set-up (colcon build)")
        return sorted(p for p in self.install.iterdir()
                      if (p / "share" / "ament_index" / "resource_index" / "packages" / p.name).is_file())

    def executable(self, package: str, executable: str) -> Path:
        """What ``ros2 run <package> <executable>`` would start."""
        for prefix in self.package_prefixes():
            if prefix.name == package:
                path = prefix / "lib" / package / executable
                if path.is_file():
                    return path
                raise WorkspaceError(f"package {package!r} has no executable {executable!r}")
        raise WorkspaceError(f"package {package!r} not found in {self.install}")

    def environment(self, base: Mapping[str, str] | None = None) -> dict[str, str]:
        """``base`` (default: os.environ) plus what sourcing ``install/setup.sh`` would set.

        ``ROS_AUTOMATIC_DISCOVERY_RANGE`` defaults to LOCALHOST: no DDS traffic leaves the
        machine unless the user asks for it. door_bringup's Fast DDS profile
        (params/fastdds_profile.xml) shortens the participant lease so a killed node leaves the
        graph in ~2 s.
        """
        env = dict(os.environ if base is None else base)
        prefixes = self.package_prefixes()
        site = f"lib/python{sys.version_info.major}.{sys.version_info.minor}/site-packages"
        python_paths = [str(p / site) for p in prefixes]
        env["PYTHONPATH"] = os.pathsep.join(python_paths + [v for v in [env.get("PYTHONPATH")] if v])
        # existing entries stay (a real install's /opt/ros/jazzy: type support is found through it)
        ament = [str(p) for p in prefixes] + [sys.prefix] + [v for v in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if v]
        env["AMENT_PREFIX_PATH"] = os.pathsep.join(dict.fromkeys(ament))
        env.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
        env.setdefault("FASTRTPS_DEFAULT_PROFILES_FILE", str(self.params / "fastdds_profile.xml"))
        env.setdefault("DOOR_PARAMS_DIR", str(self.params))
        env.setdefault("DOOR_SHARED_DATA", str(self.root.parent / "shared" / "data"))
        env.setdefault("PYTHONUNBUFFERED", "1")
        return env

    def params_file(self, node_name: str) -> Path:
        return self.params / f"{node_name}.yaml"
