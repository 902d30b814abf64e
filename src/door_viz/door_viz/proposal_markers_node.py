"""ROS 2 node ``/proposal_markers``: what the FSM is offered, as markers in ``odom``.

Listens to the proposals (door estimate, footstep plans, trajectories) and the FSM's planning
requests (how the door opens, how far it is open), and publishes the whole picture as one
latched MarkerArray on /door_task/proposal_markers (:mod:`door_viz.picture`). A trajectory's
hand paths come from the latest /joint_states and /odom through Pinocchio (a trajectory that
arrives before either is drawn as soon as both are there); those two streams are kept as bytes
and decoded only when a trajectory needs them, so following them costs the graph almost
nothing. A message that breaks the contract is logged and leaves the picture as it was.
"""

from __future__ import annotations

from nav_msgs.msg import Odometry, Path
import numpy as np
from rclpy.node import Node
from rclpy.serialization import deserialize_message
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
from door_contract.node_support import (Heartbeat, create_contract_publisher, create_contract_subscription,
                                        declare_parameters, run_node)
from door_contract.payloads import DoorEstimate, FootstepRequest, MotionRequest, decode
from door_contract.topics import Topics
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_viz.hand_paths import hand_paths
from door_viz.parameters import MARKERS_NODE, MARKERS_PARAMETERS
from door_viz.picture import ProposalPicture, SoleSize


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
        self.latest: dict[str, bytes] = {}  # topic -> serialized last message (/joint_states, /odom)
        self.pending_trajectory: JointPath | None = None  # waiting for /joint_states and /odom
        self.heartbeat = Heartbeat(self)
        self.markers_pub = create_contract_publisher(self, Topics.PROPOSAL_MARKERS)
        sub = lambda topic, callback: create_contract_subscription(self, topic, callback)
        for topic in (Topics.JOINT_STATES, Topics.ODOM):
            self.create_subscription(topic.msg_class(), topic.name, lambda data, t=topic.name: self._keep(t, data),
                                     topic.qos.to_profile(), raw=True)
        sub(Topics.DOOR_ESTIMATE, self._guarded(self._on_door))
        sub(Topics.FOOTSTEP_REQUEST, self._guarded(lambda m: self._on_request(decode(FootstepRequest, m.data))))
        sub(Topics.MOTION_REQUEST, self._guarded(lambda m: self._on_request(decode(MotionRequest, m.data))))
        sub(Topics.FOOTSTEP_PROPOSAL, self._guarded(self._on_footsteps))
        sub(Topics.MOTION_PROPOSAL, self._guarded(self._on_trajectory))
        self.get_logger().info(f"ready: {profile.name}, markers on {Topics.PROPOSAL_MARKERS.name}")

    def _guarded(self, handler):
        """``handler`` that logs a contract violation instead of raising, then republishes."""
        def guarded(msg) -> None:
            try:
                changed = handler(msg) is not False
            except (ContractError, RobotModelError) as error:
                self.get_logger().warning(f"{type(msg).__name__} ignored: {error}")
                self.heartbeat.update(Health.WARN, f"ignored: {error}")
                return
            if changed:
                self.markers_pub.publish(shapes_to_marker_array(self.picture.shapes(),
                                                                self.get_clock().now().nanoseconds * 1e-9))
        return guarded

    def _keep(self, topic: str, data: bytes) -> None:
        first = topic not in self.latest
        self.latest[topic] = data
        if first and self.pending_trajectory is not None:
            self._guarded(self._show_hand_paths)(self.pending_trajectory)

    def _robot_state(self) -> tuple[dict[str, float], np.ndarray] | None:
        """The latest joint positions and base pose, decoded now; None until both arrived."""
        if not {Topics.JOINT_STATES.name, Topics.ODOM.name} <= set(self.latest):
            return None
        joints = deserialize_message(self.latest[Topics.JOINT_STATES.name], JointState)
        odom = deserialize_message(self.latest[Topics.ODOM.name], Odometry)
        return joint_state_to_positions(joints), pose_to_matrix(odom.pose.pose)

    def _on_door(self, msg: String) -> None:
        self.picture.show_door(decode(DoorEstimate, msg.data))

    def _on_request(self, request: FootstepRequest | MotionRequest) -> None:
        self.picture.show_request(request.opening, request.door_angle)

    def _on_footsteps(self, msg: Path) -> None:
        self.picture.show_footsteps(path_to_footsteps(msg))

    def _on_trajectory(self, msg: JointTrajectory) -> bool:
        self.pending_trajectory = msg_to_joint_path(msg)
        return self._show_hand_paths(self.pending_trajectory)

    def _show_hand_paths(self, path: JointPath) -> bool:
        """Draw ``path``'s hand paths; False (kept pending) until /joint_states and /odom arrived."""
        state = self._robot_state()
        if state is None:
            return False
        self.pending_trajectory = None
        joints, base_pose = state
        self.picture.show_hand_paths(hand_paths(self.kinematics, joints, path, base_pose))
        return True


def main(args: list[str] | None = None) -> int:
    return run_node(ProposalMarkersNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
