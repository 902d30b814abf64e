"""ROS 2 node ``/proposal_markers``: what the FSM is offered, as markers in ``odom``.

Listens to the proposals (door estimate, footstep plans, trajectories) and the FSM's planning
requests (how the door opens, how far it is open), and publishes the whole picture as one
latched MarkerArray on /door_task/proposal_markers (:mod:`door_viz.picture`). A trajectory's
hand paths come from the robot's configuration and base when the trajectory arrives, through
Pinocchio: the node subscribes to /joint_states and /odom only then, takes one message of each
and unsubscribes (following both 50 Hz streams cost ~10 % of a core in rclpy's executor). A
message that breaks the contract is logged and leaves the picture as it was.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
from nav_msgs.msg import Odometry, Path
from rclpy.node import Node
from rclpy.serialization import deserialize_message
from rclpy.subscription import Subscription
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import path_to_footsteps
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.converters.markers import shapes_to_marker_array
from door_contract.converters.pose import pose_to_matrix
from door_contract.converters.trajectory import JointPath, msg_to_joint_path
from door_contract.errors import ContractError, ParameterRangeError
from door_contract.node_support import (
    Heartbeat,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.payloads import DoorEstimate, FootstepRequest, MotionRequest, decode
from door_contract.topics import Topics, TopicSpec
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_viz.hand_paths import hand_paths
from door_viz.parameters import MARKERS_NODE, MARKERS_PARAMETERS
from door_viz.picture import ProposalPicture, SoleSize

__all__ = ["ProposalMarkersNode", "main"]


class ProposalMarkersNode(Node):
    def __init__(self) -> None:
        super().__init__(MARKERS_NODE)
        p = declare_parameters(self, MARKERS_PARAMETERS)
        try:
            profile = load_profile(p["robot_profile"])
            self.kinematics = RobotKinematics(profile)
        except RobotModelError as error:
            raise ParameterRangeError(f"parameter 'robot_profile': {error}") from None
        self.picture = ProposalPicture(SoleSize(profile.walking.foot_length, profile.walking.foot_width))
        self.sampled: dict[str, bytes] = {}  # topic -> one serialized message (/joint_states, /odom)
        self.sampling: list[Subscription] = []  # the subscriptions taking them, while a trajectory waits
        self.pending_trajectory: JointPath | None = None  # waiting for /joint_states and /odom
        self.heartbeat = Heartbeat(self)
        self.markers_pub = create_contract_publisher(self, Topics.PROPOSAL_MARKERS)
        def sub(topic: TopicSpec, callback: Callable[[Any], None]) -> None:
            create_contract_subscription(self, topic, callback)
        sub(Topics.DOOR_ESTIMATE, self._guarded(self._on_door))
        sub(Topics.FOOTSTEP_REQUEST, self._guarded(lambda m: self._on_request(decode(FootstepRequest, m.data))))
        sub(Topics.MOTION_REQUEST, self._guarded(lambda m: self._on_request(decode(MotionRequest, m.data))))
        sub(Topics.FOOTSTEP_PROPOSAL, self._guarded(self._on_footsteps))
        sub(Topics.MOTION_PROPOSAL, self._guarded(self._on_trajectory))
        self.get_logger().info(f"ready: {profile.name}, markers on {Topics.PROPOSAL_MARKERS.name}")

    def _guarded(self, handler: Callable[[Any], bool | None]) -> Callable[[Any], None]:
        """``handler`` that logs a contract violation instead of raising, then republishes
        (unless it returns False: nothing changed)."""
        def guarded(msg: Any) -> None:
            try:
                changed = handler(msg) is not False
            except (ContractError, RobotModelError) as error:
                self.get_logger().warning(f"{type(msg).__name__} ignored: {error}")
                self.heartbeat.update(Health.WARN, f"ignored: {error}")
                return
            if changed:  # unstamped: a viewer draws them with the latest transforms (odom is fixed)
                self.markers_pub.publish(shapes_to_marker_array(self.picture.shapes()))
        return guarded

    def _sample_robot_state(self) -> None:
        """Subscribe to /joint_states and /odom until one message of each has arrived."""
        self.sampled.clear()
        if not self.sampling:
            self.sampling = [self.create_subscription(topic.msg_class(), topic.name,
                                                      partial(self._keep, topic.name),
                                                      topic.qos.to_profile(), raw=True)
                             for topic in (Topics.JOINT_STATES, Topics.ODOM)]

    def _keep(self, topic: str, data: bytes) -> None:
        self.sampled[topic] = data
        if len(self.sampled) == 2 and self.pending_trajectory is not None:
            for subscription in self.sampling:
                self.destroy_subscription(subscription)
            self.sampling = []
            self._guarded(self._show_hand_paths)(self.pending_trajectory)

    def _robot_state(self) -> tuple[dict[str, float], np.ndarray] | None:
        """The sampled joint positions and base pose; None until both arrived."""
        if len(self.sampled) < 2:
            return None
        joints = deserialize_message(self.sampled[Topics.JOINT_STATES.name], JointState)
        odom = deserialize_message(self.sampled[Topics.ODOM.name], Odometry)
        return joint_state_to_positions(joints), pose_to_matrix(odom.pose.pose)

    def _on_door(self, msg: String) -> None:
        self.picture.show_door(decode(DoorEstimate, msg.data))

    def _on_request(self, request: FootstepRequest | MotionRequest) -> None:
        self.picture.show_request(request.opening, request.door_angle)

    def _on_footsteps(self, msg: Path) -> None:
        self.picture.show_footsteps(path_to_footsteps(msg))

    def _on_trajectory(self, msg: JointTrajectory) -> bool:
        self.pending_trajectory = msg_to_joint_path(msg)
        self._sample_robot_state()
        return False  # drawn when the robot's state has been sampled

    def _show_hand_paths(self, path: JointPath) -> bool:
        """Draw ``path``'s hand paths from the sampled robot state."""
        state = self._robot_state()
        if state is None:
            return False
        self.pending_trajectory = None
        joints, base_pose = state
        self.picture.show_hand_paths(hand_paths(self.kinematics, joints, path, base_pose))
        return True


main = node_main(ProposalMarkersNode, __name__)
