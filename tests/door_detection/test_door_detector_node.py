"""The detector as a process over real DDS: rendered frames give a voted estimate in odom;
bad frames and a scribble outside the image give warnings, no estimate, and a live node."""

import numpy as np
import pytest
import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Point32, PolygonStamped
from ros_helpers import executor_for, node_process, spin_until

from door_contract.converters.camera_info import intrinsics_to_camera_info
from door_contract.converters.image import array_to_image
from door_contract.converters.pose import matrix_to_pose_stamped
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, decode
from door_contract.topics import Topics
from door_sim_bridge.world import DoorWorld, StanceConfig, WorldConfig

pytestmark = pytest.mark.ros
FRAME = "head_camera_optical_frame"


@pytest.fixture(scope="module")
def rendered():
    with DoorWorld(WorldConfig(stance=StanceConfig(distance=2.0))) as world:
        return world.render(), world.handle_grasp_pose()


@pytest.fixture(scope="module")
def detector(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("detector") / "detector.log"
    with node_process(workspace, "door_detector", log) as process:
        yield process, log


class Camera:
    def __init__(self, context):
        self.node = rclpy.create_node("detector_test_camera", context=context)
        self.executor = executor_for(self.node, context)
        self.pubs = {name: create_contract_publisher(self.node, getattr(Topics, name))
                     for name in ("COLOR_IMAGE", "DEPTH_IMAGE", "COLOR_INFO", "CAMERA_POSE", "SCRIBBLE")}
        self.estimates, self.rejected = [], []
        create_contract_subscription(self.node, Topics.DOOR_ESTIMATE,
                                     lambda m: self.estimates.append(decode(DoorEstimate, m.data)))
        self.frames = []  # frames the detector reports having taken in (its /diagnostics)
        self.messages = []
        self.node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, self._on_diagnostics, 10)
        assert spin_until(self.executor, lambda: all(p.get_subscription_count() for p in self.pubs.values()), 30.0)

    def _on_diagnostics(self, array):
        for status in array.status:
            if status.name == "door_detector":
                values = {kv.key: kv.value for kv in status.values}
                if "rejected" in values:
                    self.rejected.append(int(values["rejected"]))
                if "frames" in values:
                    self.frames.append(int(values["frames"]))
                self.messages.append(status.message)

    def publish(self, stamp, rgb, depth, intrinsics, pose, colour_encoding="rgb8"):
        self.pubs["COLOR_IMAGE"].publish(array_to_image(rgb, colour_encoding, FRAME, stamp))
        self.pubs["DEPTH_IMAGE"].publish(array_to_image(depth, "32FC1", FRAME, stamp))
        self.pubs["COLOR_INFO"].publish(intrinsics_to_camera_info(intrinsics, FRAME, stamp))
        self.pubs["CAMERA_POSE"].publish(matrix_to_pose_stamped(pose, "odom", stamp))


@pytest.fixture
def camera(detector, rclpy_context):
    camera = Camera(rclpy_context)
    yield camera
    camera.node.destroy_node()


def test_bad_frames_give_no_estimate_and_the_node_lives_on(camera, rendered):
    frame, _ = rendered
    rgb, depth = np.ascontiguousarray(frame.rgb), np.nan_to_num(frame.depth, nan=0.0).astype(np.float32)
    small_depth = np.ascontiguousarray(depth[::2, ::2])
    bad_frames = [
        (rgb, small_depth, frame.intrinsics, "rgb8"),                    # depth/colour size mismatch
        (rgb, np.full_like(depth, np.nan), frame.intrinsics, "rgb8"),    # all-invalid depth
        (rgb[:, :, ::-1].copy(), depth, frame.intrinsics, "bgr8"),        # unsupported colour encoding
        (rgb[:240].copy(), depth[:240].copy(), frame.intrinsics, "rgb8"),  # CameraInfo for another size
    ]
    for index, (colour, depth_image, intrinsics, encoding) in enumerate(bad_frames):
        camera.publish(100.0 + index, colour, depth_image, intrinsics, frame.camera_pose, encoding)
    assert spin_until(camera.executor, lambda: camera.rejected and camera.rejected[-1] >= len(bad_frames), 30.0)
    assert not any(100.0 <= e.stamp < 104.0 for e in camera.estimates)  # (a latched older one may arrive)
    assert spin_until(camera.executor, lambda: "door_detector" in camera.node.get_node_names(), 10.0)  # graph: a deadline


def test_rendered_frames_give_a_voted_estimate_in_odom(camera, rendered, detector):
    frame, handle = rendered
    depth = np.where(np.isfinite(frame.depth), frame.depth, np.nan).astype(np.float32)
    for index in range(10):  # the window is N = 10 frames; one frame at a time,
        seen = camera.frames[-1] if camera.frames else 0  # as a camera would send them
        camera.publish(200.0 + index * 0.5, np.ascontiguousarray(frame.rgb), depth, frame.intrinsics,
                       frame.camera_pose)
        if any(e.stamp >= 200.0 for e in camera.estimates):
            break
        assert spin_until(camera.executor, lambda seen=seen: camera.frames and camera.frames[-1] > seen, 30.0)
    assert spin_until(camera.executor, lambda: any(e.stamp >= 200.0 for e in camera.estimates), 60.0)
    estimate = next(e for e in camera.estimates if e.stamp >= 200.0)
    assert estimate.stamp == pytest.approx(200.5) and estimate.frames_voted == 2   # sequential: 2 agree
    assert estimate.frame_id == "odom"
    assert np.linalg.norm(np.subtract(estimate.handle_position, handle[:3, 3])) < 0.02
    assert np.dot(estimate.normal, handle[:3, 0]) > np.cos(np.radians(2.0))


@pytest.mark.parametrize("points, why", [
    ([(1e6, 1e6), (1e6 + 5, 1e6), (1e6, 1e6 + 5)], "outside"),   # issue #12: blocked detection for 30 s
    ([(5000.0, 10.0), (5010.0, 12.0), (5005.0, 20.0)], "outside"),
    ([(float("nan"), 10.0), (20.0, 20.0)], "NaN"),
    ([], "0 point(s)"),
])
def test_a_bad_scribble_is_refused_at_once_and_automatic_detection_goes_on(camera, rendered, detector, points, why):
    frame, handle = rendered
    depth = np.where(np.isfinite(frame.depth), frame.depth, np.nan).astype(np.float32)
    first = 300.0 + 20.0 * len(camera.estimates)
    camera.publish(first, np.ascontiguousarray(frame.rgb), depth, frame.intrinsics, frame.camera_pose)
    assert spin_until(camera.executor, lambda: camera.frames and camera.frames[-1] >= 1, 30.0)  # it knows the size
    scribble = PolygonStamped()
    scribble.polygon.points = [Point32(x=x, y=y) for x, y in points]
    camera.pubs["SCRIBBLE"].publish(scribble)
    assert spin_until(camera.executor, lambda: any("scribble refused" in m and why in m for m in camera.messages),
                      10.0), camera.messages[-5:]
    for index in range(1, 12):  # automatic detection is not blocked: a voted estimate follows
        if any(e.stamp >= first for e in camera.estimates):
            break
        seen = camera.frames[-1]
        camera.publish(first + index * 0.5, np.ascontiguousarray(frame.rgb), depth, frame.intrinsics, frame.camera_pose)
        assert spin_until(camera.executor, lambda seen=seen: camera.frames[-1] > seen, 30.0)
    assert spin_until(camera.executor, lambda: any(e.stamp >= first for e in camera.estimates), 30.0)
    estimate = next(e for e in camera.estimates if e.stamp >= first)
    assert estimate.mode == "automatic"
    assert np.linalg.norm(np.subtract(estimate.handle_position, handle[:3, 3])) < 0.02


def test_frames_without_camera_info_are_reported(camera, rendered):
    frame, _ = rendered
    depth = np.where(np.isfinite(frame.depth), frame.depth, np.nan).astype(np.float32)
    def reported():
        return any("dropped" in m and "CameraInfo" in m for m in camera.messages)
    for index in range(30):  # frame after frame, a second apart, never with its CameraInfo
        stamp = 500.0 + index
        camera.pubs["COLOR_IMAGE"].publish(array_to_image(np.ascontiguousarray(frame.rgb), "rgb8", FRAME, stamp))
        camera.pubs["DEPTH_IMAGE"].publish(array_to_image(depth, "32FC1", FRAME, stamp))
        camera.pubs["CAMERA_POSE"].publish(matrix_to_pose_stamped(frame.camera_pose, "odom", stamp))
        if spin_until(camera.executor, reported, 0.5):
            break
    assert reported(), camera.messages[-3:]
    assert spin_until(camera.executor, lambda: "door_detector" in camera.node.get_node_names(), 10.0)  # graph: a deadline
