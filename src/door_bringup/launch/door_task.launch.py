"""Launch the door-traversal graph on a real ROS 2 Jazzy install: ``ros2 launch door_bringup door_task.launch.py``.

Starts the five nodes of DESIGN.md with their parameter files (installed under
``share/door_bringup/params``) and ``use_sim_time`` (the sim bridge publishes /clock).
Where ``ros2 launch`` is unavailable, ``python -m door_bringup.graph`` does the same.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node

from door_bringup.graph_spec import GRAPH


def generate_launch_description() -> LaunchDescription:
    params = os.path.join(get_package_share_directory("door_bringup"), "params")
    return LaunchDescription([
        Node(package=launch.package, executable=launch.executable, name=launch.node_name,
             output="screen", emulate_tty=True,
             parameters=[os.path.join(params, f"{launch.node_name}.yaml"),
                         {"use_sim_time": launch.use_sim_time}],
             additional_env={"DOOR_PARAMS_DIR": params})
        for launch in GRAPH
    ])
