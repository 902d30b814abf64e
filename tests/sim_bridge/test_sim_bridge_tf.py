"""What a ROS user sees of the simulated robot, over real DDS: /robot_description (transient
local) names every link /tf and /tf_static carry, its meshes resolve, and a link's composed
transform equals the sim's own pose of it (the head camera's, published on /head_camera/pose)."""

import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest
import rclpy
from ros_helpers import executor_for, node_process, spin_until

from door_contract.converters.pose import pose_stamped_to_matrix
from door_contract.converters.transforms import tf_message_frames
from door_contract.frames import Frame
from door_contract.node_support import create_contract_subscription
from door_contract.stamps import stamp_ns
from door_contract.topics import Topics
from door_robot.meshes import PACKAGE_URI, resolve_package_uri
from door_robot.profile import load_profile
from door_sim_bridge.tf_tree import compose
from door_sim_bridge.urdf_joints import urdf_joints

pytestmark = pytest.mark.ros


@pytest.fixture(scope="module")
def bridge(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("bridge_tf") / "sim_bridge.log"
    with node_process(workspace, "sim_bridge", log, "camera_rate:=2.0", "camera_width:=160", "camera_height:=120"):
        yield log


class TfListener:
    """Subscribes late (after the bridge published its latched topics) to everything TF."""

    def __init__(self, context):
        self.node = rclpy.create_node("tf_listener", context=context)
        self.executor = executor_for(self.node, context)
        self.tf, self.static, self.description, self.camera = {}, [], [], {}
        create_contract_subscription(self.node, Topics.TF, self._on_tf)
        create_contract_subscription(self.node, Topics.TF_STATIC, lambda m: self.static.extend(tf_message_frames(m)))
        create_contract_subscription(self.node, Topics.ROBOT_DESCRIPTION, lambda m: self.description.append(m.data))
        create_contract_subscription(self.node, Topics.CAMERA_POSE, lambda m: self.camera.setdefault(
            stamp_ns(m.header.stamp), pose_stamped_to_matrix(m)))

    def _on_tf(self, msg):
        self.tf[stamp_ns(msg.transforms[0].header.stamp)] = tf_message_frames(msg)

    def common_stamps(self):
        return sorted(set(self.tf) & set(self.camera))


@pytest.fixture
def listener(bridge, rclpy_context):
    listener = TfListener(rclpy_context)
    assert spin_until(listener.executor, lambda: listener.static and listener.description
                      and len(listener.common_stamps()) >= 2, 60.0), bridge.read_text()
    yield listener
    listener.node.destroy_node()


def test_robot_description_is_latched_and_its_meshes_resolve(listener):
    text = listener.description[0]
    assert '<robot name="talos"' in text
    uris = {m.group(0) for m in PACKAGE_URI.finditer(text)}
    profile = ElementTree.parse(load_profile("talos").urdf_path).getroot()
    drawn = {mesh.get("filename") for mesh in profile.iterfind(".//visual//mesh")}
    assert len(drawn) > 20 and drawn <= uris  # every mesh a viewer draws (the soles' collisions are boxes)
    assert all(resolve_package_uri(uri) is not None for uri in uris)


def test_tf_names_every_link_of_the_description(listener):
    links = {j.child for j in urdf_joints(listener.description[0])}
    frames = {t.child for t in listener.static} | {t.child for t in next(iter(listener.tf.values()))}
    assert links <= frames
    assert {Frame.BASE_LINK.value, Frame.HEAD_CAMERA_OPTICAL.value} <= frames
    assert all(t.parent == Frame.ODOM.value for t in listener.tf[min(listener.tf)] if t.child == Frame.BASE_LINK.value)


def test_camera_frame_composed_from_tf_equals_the_sims_camera_pose(listener):
    for stamp in listener.common_stamps():
        composed = compose([*listener.static, *listener.tf[stamp]], Frame.ODOM.value, Frame.HEAD_CAMERA_OPTICAL.value)
        np.testing.assert_allclose(composed, listener.camera[stamp], atol=1e-6)
