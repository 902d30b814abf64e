"""Launch the door-traversal graph on a real ROS 2 Jazzy install: ``ros2 launch door_bringup door_task.launch.py``.

Starts the five nodes of DESIGN.md and the proposal markers with their parameter files
(installed under ``share/door_bringup/params``; the robot profiles they name are door_robot's,
under ``share/door_robot/profiles``) and ``use_sim_time`` (the sim bridge publishes
/clock); ``robot:=g1`` (``talos``, ``atlas_v4``, ``drc_hubo``, ``g1``) sets ``robot_profile`` on
every node that declares it; ``foxglove:=true`` adds the Foxglove WebSocket bridge (ws://127.0.0.1:8765).
Where ``ros2 launch`` is unavailable, ``python -m door_bringup.graph`` does the same.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from door_bringup.graph_spec import FOXGLOVE_BRIDGE, GRAPH
from door_bringup.params_files import ROBOT_PARAMETER, robot_nodes


def generate_launch_description() -> LaunchDescription:
    params = os.path.join(get_package_share_directory("door_bringup"), "params")
    foxglove, robot = LaunchConfiguration("foxglove"), LaunchConfiguration("robot")
    takes_robot = robot_nodes()

    def node(launch, **kwargs) -> Node:
        return Node(package=launch.package, executable=launch.executable, name=launch.node_name,
                    output="screen", emulate_tty=True,
                    parameters=[os.path.join(params, f"{launch.node_name}.yaml"),
                                {"use_sim_time": launch.use_sim_time},
                                *([{ROBOT_PARAMETER: robot}] if launch.node_name in takes_robot else [])], **kwargs)

    return LaunchDescription([
        DeclareLaunchArgument("foxglove", default_value="false", description="serve the graph on a Foxglove WebSocket"),
        DeclareLaunchArgument("robot", default_value="talos", description="robot profile (robot_<name>.yaml)"),
        *(node(launch) for launch in GRAPH),
        node(FOXGLOVE_BRIDGE, condition=IfCondition(foxglove)),
    ])
