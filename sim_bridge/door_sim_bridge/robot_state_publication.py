"""What ``robot_state_publisher`` would publish for the simulated robot: /robot_description,
/tf_static and /tf (node-side glue over :mod:`door_sim_bridge.tf_tree`).

The description and the static transforms are published once, transient local, so a viewer
that connects later still gets them. Without ``tf2_msgs`` (ROS 2 from PyPI before set-up
built it) only /robot_description is published, and the node says so once.
"""

from __future__ import annotations

from rclpy.node import Node
from std_msgs.msg import String

from door_contract.converters.transforms import TfMessageBuffer, tf_message, tf_messages_available
from door_contract.node_support import create_contract_publisher
from door_contract.topics import Topics
from door_robot.meshes import MeshUris
from door_sim_bridge.robot_description import loaded_urdf, robot_description
from door_sim_bridge.tf_tree import world_tf_tree
from door_sim_bridge.world import DoorWorld

__all__ = ["RobotStatePublication"]


class RobotStatePublication:
    def __init__(self, node: Node, world: DoorWorld, mesh_uris: MeshUris, now: float) -> None:
        description = create_contract_publisher(node, Topics.ROBOT_DESCRIPTION)
        description.publish(String(data=robot_description(world, mesh_uris)))
        self._tf = None
        if not tf_messages_available():
            node.get_logger().warning("tf2_msgs is not importable: no /tf or /tf_static "
                                      "(./setup.sh builds it; see README)")
            return
        self.tree = world_tf_tree(world, loaded_urdf(world)[0])
        if self.tree.skipped:
            node.get_logger().warning(f"TF: joints whose links the sim lacks: {', '.join(self.tree.skipped)}")
        self._static = create_contract_publisher(node, Topics.TF_STATIC)
        self._static.publish(tf_message(self.tree.static_transforms(), now))
        self._tf = create_contract_publisher(node, Topics.TF)
        self._buffer = TfMessageBuffer()

    def publish(self, now: float) -> None:
        """/tf with every moving transform at sim time ``now`` (s)."""
        if self._tf is not None:
            self._tf.publish(self._buffer.message(self.tree.moving_transforms(), now))
