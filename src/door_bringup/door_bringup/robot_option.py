"""``--robot NAME``: the one robot option of the main job, the Monte-Carlo and the passage rig.

ROS-free, so that the rig (which runs the cores in one process) takes it without rclpy.
"""

from __future__ import annotations

import argparse

from door_bringup.params_files import robot_names
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile

__all__ = ["add_robot_argument", "check_robot"]


def add_robot_argument(parser: argparse.ArgumentParser,
                       help_text: str = "robot profile (params/robot_<name>.yaml) of every node that takes one") -> None:
    """``--robot NAME``: one of the robot profiles there are (default TALOS)."""
    parser.add_argument("--robot", choices=robot_names(), default="talos", help=help_text)


def check_robot(parser: argparse.ArgumentParser, robot: str) -> None:
    """Refuse (exit 2) a profile that cannot be loaded, e.g. a URDF from ../shared that is absent,
    before anything starts: each node would otherwise stop on the same parameter error."""
    try:
        load_profile(robot)
    except RobotModelError as error:
        parser.error(f"--robot: {error}")  # the error names the profile
