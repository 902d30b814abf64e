"""ROS 2 node ``/proposal_markers``: what the FSM is offered, as markers in ``odom``.

Listens to the proposals (door estimate, footstep plans, trajectories) and the FSM's planning
requests (how the door opens, how far it is open), and publishes the whole picture as one
latched MarkerArray on /door_task/proposal_markers (:mod:`door_viz.picture`). A trajectory's
hand paths come from the latest /joint_states and /odom through Pinocchio (a trajectory that
arrives before either is drawn as soon as both are there). A message that breaks the contract
is logged and leaves the picture as it was.
"""

from __future__ import annotations

from nav_msgs.msg import Odometry, Path
from rclpy.node import Node
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
        self.joints: dict[str, float] | None = None
        self.base_pose = None
        self.pending_trajectory: JointPath | None = None  # waiting for /joint_states and /odom
        self.heartbeat = Heartbeat(self)
        self.markers_pub = create_contract_publisher(self, Topics.PROPOSAL_MARKERS)
        sub = lambda topic, callback: create_contract_subscription(self, topic, callback)
        sub(Topics.JOINT_STATES, self._on_joint_states)
        sub(Topics.ODOM, self._on_odom)
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

    def _on_joint_states(self, msg: JointState) -> None:
        try:
            self.joints = joint_state_to_positions(msg)
        except ContractError:
            return  # the last good state stays; the bridge's own tests cover its messages
        self._draw_pending_trajectory()

    def _on_odom(self, msg: Odometry) -> None:
        try:
            self.base_pose = pose_to_matrix(msg.pose.pose)
        except ContractError:
            return
        self._draw_pending_trajectory()

    def _draw_pending_trajectory(self) -> None:
        if self.pending_trajectory is not None and self.joints is not None and self.base_pose is not None:
            self._guarded(lambda path: self._show_hand_paths(path))(self.pending_trajectory)

    def _on_door(self, msg: String) -> None:
        self.picture.show_door(decode(DoorEstimate, msg.data))

    def _on_request(self, request: FootstepRequest | MotionRequest) -> None:
        self.picture.show_request(request.opening, request.door_angle)

    def _on_footsteps(self, msg: Path) -> None:
        self.picture.show_footsteps(path_to_footsteps(msg))

    def _on_trajectory(self, msg: JointTrajectory) -> bool:
        self.pending_trajectory = msg_to_joint_path(msg)
        if self.joints is None or self.base_pose is None:
            return False  # drawn when both have arrived
        return self._show_hand_paths(self.pending_trajectory)

    def _show_hand_paths(self, path: JointPath) -> bool:
        self.pending_trajectory = None
        self.picture.show_hand_paths(hand_paths(self.kinematics, self.joints, path, self.base_pose))
        return True


def main(args: list[str] | None = None) -> int:
    return run_node(ProposalMarkersNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
