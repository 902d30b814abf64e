"""The proposal markers node over real DDS: from a door estimate, a planning request, a footstep
plan and a trajectory (with the robot's joint states and odometry, streamed as the sim does,
which the node samples only when a trajectory arrives) it publishes one latched picture with the
door, its swing, the footsteps and the hand path; bad input changes nothing."""

import numpy as np
import pytest
import rclpy
from nav_msgs.msg import Odometry
from ros_helpers import executor_for, node_process, spin_until
from std_msgs.msg import String
from test_proposal_shapes import ESTIMATE, STEPS

from door_contract.converters.footsteps import footsteps_to_path
from door_contract.converters.joint_state import positions_to_joint_state
from door_contract.converters.trajectory import JointPath, joint_path_to_msg
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import MotionRequest, encode
from door_contract.topics import Topics
from door_contract.vocabulary import Side
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile

pytestmark = pytest.mark.ros


@pytest.fixture
def markers_node(workspace, tmp_path):
    log = tmp_path / "proposal_markers.log"
    with node_process(workspace, "proposal_markers", log):
        yield log


def test_picture_of_the_proposals(markers_node, rclpy_context):
    node = rclpy.create_node("markers_test", context=rclpy_context)
    executor = executor_for(node, rclpy_context)
    arrays = []
    create_contract_subscription(node, Topics.PROPOSAL_MARKERS, arrays.append)
    pub = {t.name: create_contract_publisher(node, t) for t in (
        Topics.JOINT_STATES, Topics.ODOM, Topics.DOOR_ESTIMATE, Topics.MOTION_REQUEST, Topics.FOOTSTEP_PROPOSAL,
        Topics.MOTION_PROPOSAL)}
    proposals = [p for name, p in pub.items() if name not in (Topics.JOINT_STATES.name, Topics.ODOM.name)]
    assert spin_until(executor, lambda: all(p.get_subscription_count() for p in proposals), 60.0), \
        markers_node.read_text()
    posture = dict(load_profile("talos").nominal_posture)
    odom = Odometry()
    odom.pose.pose.position.x, odom.pose.pose.position.z, odom.pose.pose.orientation.w = -1.0, 1.0, 1.0
    pub[Topics.DOOR_ESTIMATE.name].publish(String(data=encode(ESTIMATE)))
    pub[Topics.MOTION_REQUEST.name].publish(String(data=encode(MotionRequest(4, "pull_door", "pull", door_angle=0.3))))
    pub[Topics.FOOTSTEP_PROPOSAL.name].publish(footsteps_to_path(STEPS, 2.0))
    path = JointPath(np.array([0.0, 1.0]), ("arm_right_4_joint",), np.array([[-0.5], [-1.5]]))
    pub[Topics.MOTION_PROPOSAL.name].publish(joint_path_to_msg(path))
    def namespaces():
        return {m.ns for m in arrays[-1].markers[1:]} if arrays else set()

    def streaming_until_drawn() -> bool:  # the robot's state streams on, as from the sim bridge
        pub[Topics.JOINT_STATES.name].publish(positions_to_joint_state(posture, stamp=1.0))
        pub[Topics.ODOM.name].publish(odom)
        return namespaces() == {"door", "door_swing", "footsteps", "hand_path"}
    assert spin_until(executor, streaming_until_drawn, 30.0), markers_node.read_text()
    assert spin_until(executor, lambda: pub[Topics.JOINT_STATES.name].get_subscription_count() == 0, 30.0)
    kinematics = RobotKinematics(load_profile("talos"))
    q = kinematics.configuration({**posture, "arm_right_4_joint": -1.5})
    expected = kinematics.frame_pose(q, kinematics.profile.tcp_frame(Side.RIGHT))[:3, 3] + (-1.0, 0.0, 1.0)
    end = next(m for m in arrays[-1].markers if m.ns == "hand_path" and m.type == m.SPHERE).pose.position
    np.testing.assert_allclose((end.x, end.y, end.z), expected, atol=1e-6)

    count = len(arrays)
    bad = joint_path_to_msg(path)
    bad.points[1].positions = [float("nan")]
    pub[Topics.MOTION_PROPOSAL.name].publish(bad)
    pub[Topics.DOOR_ESTIMATE.name].publish(String(data='{"stamp": "soon"}'))
    assert spin_until(executor, lambda: markers_node.read_text().count("ignored") >= 2, 30.0), markers_node.read_text()
    assert len(arrays) == count  # nothing republished: the picture is unchanged
    node.destroy_node()
