"""What the robot's drivers would publish for the simulated robot, at the streams the loop
says are due (node-side glue over the world's state and :mod:`door_contract.converters`):
/clock; /joint_states, /odom (twist from :class:`~door_sim_bridge.base_velocity.BaseVelocity`),
/feet and the door's ground-truth joints; the head camera's images, intrinsics and pose;
and, through :class:`~door_sim_bridge.robot_state_publication.RobotStatePublication`,
/robot_description and /tf.
"""

from __future__ import annotations

import numpy as np
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rosgraph_msgs.msg import Clock

from door_contract.converters.camera_info import intrinsics_to_camera_info
from door_contract.converters.footsteps import footsteps_to_path
from door_contract.converters.image import array_to_image
from door_contract.converters.joint_state import positions_to_joint_state
from door_contract.converters.pose import matrix_to_pose, matrix_to_pose_stamped
from door_contract.frames import Frame
from door_contract.node_support import create_contract_publisher
from door_contract.stamps import to_time_msg
from door_contract.topics import Topics
from door_contract.vocabulary import Foot
from door_robot.meshes import MeshUris
from door_sim_bridge.base_velocity import BaseVelocity
from door_sim_bridge.robot_state_publication import RobotStatePublication
from door_sim_bridge.simulation_loop import Stream
from door_sim_bridge.world import DoorWorld
from door_sim_bridge.world.door import HANDLE_JOINT, HINGE_JOINT

__all__ = ["SensorPublication"]

TOPICS = (Topics.CLOCK, Topics.JOINT_STATES, Topics.ODOM, Topics.COLOR_IMAGE, Topics.COLOR_INFO, Topics.DEPTH_IMAGE,
          Topics.DEPTH_INFO, Topics.CAMERA_POSE, Topics.DOOR_JOINT_STATES, Topics.FOOT_POSES)
"""The contract topics published here."""


class SensorPublication:
    def __init__(self, node: Node, world: DoorWorld, mesh_uris: MeshUris) -> None:
        self.world = world
        self.publishers = {topic: create_contract_publisher(node, topic) for topic in TOPICS}
        self.base_velocity = BaseVelocity()
        self.robot_state = RobotStatePublication(node, world, mesh_uris, world.time)

    def publish(self, now: float, streams: tuple[Stream, ...]) -> None:
        """Publish ``streams`` at simulated time ``now`` (s)."""
        if Stream.CLOCK in streams:
            self.publishers[Topics.CLOCK].publish(Clock(clock=to_time_msg(now)))
        if Stream.STATE in streams:
            self._publish_state(now)
        if Stream.TF in streams:
            self.robot_state.publish(now)
        if Stream.CAMERA in streams:
            self._publish_camera()

    def _publish_state(self, now: float) -> None:
        states = self.world.joint_states()
        self.publishers[Topics.JOINT_STATES].publish(positions_to_joint_state(
            dict(zip(states.names, states.positions)), stamp=now,
            velocities=dict(zip(states.names, states.velocities))))
        base = self.world.base_pose()
        odom = Odometry()
        odom.header.stamp, odom.header.frame_id = to_time_msg(now), Frame.ODOM.value
        odom.child_frame_id = Frame.BASE_LINK.value
        odom.pose.pose = matrix_to_pose(base)
        velocity = self.base_velocity.update(now, base)
        if velocity is not None:
            linear = odom.twist.twist.linear
            linear.x, linear.y, linear.z = (float(v) for v in velocity)
        self.publishers[Topics.ODOM].publish(odom)
        feet = self.world.foot_placements()
        self.publishers[Topics.FOOT_POSES].publish(footsteps_to_path([feet[Foot.LEFT], feet[Foot.RIGHT]], now))
        door = self.world.door_state()
        self.publishers[Topics.DOOR_JOINT_STATES].publish(positions_to_joint_state(
            {HINGE_JOINT: door.hinge_angle, HANDLE_JOINT: door.handle_angle}, stamp=now,
            velocities={HINGE_JOINT: door.hinge_velocity, HANDLE_JOINT: door.handle_velocity}))

    def _publish_camera(self) -> None:
        frame = self.world.render()
        frame_id = Frame.HEAD_CAMERA_OPTICAL.value
        info = intrinsics_to_camera_info(frame.intrinsics, frame_id, frame.time)
        depth = np.where(np.isfinite(frame.depth), frame.depth, np.nan).astype(np.float32)
        camera_pose = matrix_to_pose_stamped(frame.camera_pose, Frame.ODOM.value, frame.time)
        self.publishers[Topics.CAMERA_POSE].publish(camera_pose)
        rgb = array_to_image(np.ascontiguousarray(frame.rgb), "rgb8", frame_id, frame.time)
        self.publishers[Topics.COLOR_IMAGE].publish(rgb)
        self.publishers[Topics.COLOR_INFO].publish(info)
        self.publishers[Topics.DEPTH_IMAGE].publish(array_to_image(depth, "32FC1", frame_id, frame.time))
        self.publishers[Topics.DEPTH_INFO].publish(info)
