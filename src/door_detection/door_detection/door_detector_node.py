"""ROS 2 node ``/door_detector``: door and handle estimates from the head RGB-D camera.

Thin glue over :class:`door_detection.detector.DoorDetector` ([Banerjee 2015] Sec. III): the
camera's streams (colour, depth, CameraInfo, the camera's pose in odom) are matched by stamp
(:mod:`door_detection.frame_sync`), decoded through the contract and handed to the core, which
detects (automatic, or operator-aided after a scribble on ``/operator/scribble``), votes and
says what to publish: ``/door/estimate``, ``/door/handle_pose``, markers and the debug image
(:mod:`door_detection.overlay`). The camera is the ``robot_profile``'s head camera. Bad frames
(empty, wrong encoding, size mismatch, no valid depth, inconsistent CameraInfo, another camera's
frame) are logged and counted; nothing is published. A frame that never completes is reported
on /diagnostics with the stream it lacked; a bad scribble is refused at once.
"""

from __future__ import annotations

import time
from functools import partial
from typing import Any

import numpy as np
from geometry_msgs.msg import PolygonStamped, PoseStamped
from rclpy.node import Node
from sensor_msgs.msg import CameraInfo, Image
from std_msgs.msg import String

from door_contract.converters.camera_info import camera_info_to_intrinsics, check_matches_image
from door_contract.converters.diagnostics import Health
from door_contract.converters.image import array_to_image, depth_to_metres, image_to_array
from door_contract.converters.pose import matrix_to_pose_stamped, pose_to_matrix
from door_contract.errors import ContractError
from door_contract.frames import Frame
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.parameters import require_ordered
from door_contract.payloads import encode
from door_contract.stamps import from_time_msg
from door_contract.topics import Topics, TopicSpec
from door_detection.detector import CameraFrame, DetectorCamera, DoorDetector, FrameReport
from door_detection.errors import DetectionError
from door_detection.frame_sync import STREAMS, FrameSync
from door_detection.markers import door_markers
from door_detection.options import DetectionOptions
from door_detection.overlay import draw_estimate
from door_detection.parameters import DETECTOR_PARAMETERS, NODE_NAME
from door_detection.payload import NominalDoor
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile

VOTE_PARAMETERS = ("vote_frames", "vote_min_agreeing", "vote_handle_confidence", "vote_normal_confidence_deg")
"""Node parameters that are the sequential vote's DetectionOptions fields of the same name."""


class DoorDetectorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = self.parameters = declare_parameters(self, DETECTOR_PARAMETERS)
        with as_parameter_error(f"parameter 'robot_profile' = {p['robot_profile']!r}", RobotModelError):
            camera = DetectorCamera.of(load_profile(p["robot_profile"]))
        require_ordered(p, "door_width_min", "door_width_max")
        with as_parameter_error("detection options", DetectionError):
            options = DetectionOptions(door_width_min=p["door_width_min"], door_width_max=p["door_width_max"],
                                       **{name: p[name] for name in VOTE_PARAMETERS})
        nominal = NominalDoor(p["nominal_door_width"], p["nominal_door_height"], p["grasp_to_free_edge"])
        self.detector = DoorDetector(options, camera, nominal, p["scribble_timeout"])
        self.sync = FrameSync(p["sync_tolerance"])  # the streams matched into frames by stamp
        self.heartbeat = Heartbeat(self)
        self.heartbeat.update(Health.OK, "ready", camera=camera.camera_link)

        def pub(topic: TopicSpec) -> Any:
            return create_contract_publisher(self, topic)
        self.estimate_pub, self.handle_pub = pub(Topics.DOOR_ESTIMATE), pub(Topics.HANDLE_POSE)
        self.marker_pub, self.debug_pub = pub(Topics.DOOR_MARKERS), pub(Topics.DETECTION_DEBUG_IMAGE)
        for stream, topic in zip(STREAMS, (Topics.COLOR_IMAGE, Topics.DEPTH_IMAGE, Topics.COLOR_INFO,
                                           Topics.CAMERA_POSE)):
            create_contract_subscription(self, topic, partial(self._on_stream, stream))
        create_contract_subscription(self, Topics.SCRIBBLE, self._on_scribble)
        self.get_logger().info(f"ready: {camera.robot}'s camera {camera.camera_link}, voting over "
                               f"{p['vote_frames']} frames (confirmed from {p['vote_min_agreeing']} agreeing), "
                               f"doors {p['door_width_min']:.2f}–{p['door_width_max']:.2f} m")

    def _on_scribble(self, msg: PolygonStamped) -> None:
        pixels = np.array([[p.x, p.y] for p in msg.polygon.points], dtype=float).reshape(-1, 2)
        report = self.detector.take_scribble(pixels, time.monotonic())
        if report.warning:  # one call site per severity (rclpy's rule); the operator's every word is logged
            self.get_logger().warning(report.note)
        else:
            self.get_logger().info(report.note)
        self._beat(report)

    def _on_stream(self, stream: str, msg: Image | CameraInfo | PoseStamped) -> None:
        if stream == "info":
            self.detector.image_size = (int(msg.width), int(msg.height))
        complete, dropped = self.sync.add(stream, from_time_msg(msg.header.stamp), msg)
        if complete is not None:
            stamp, parts = complete
            try:
                self._process(stamp, parts)
            except Exception as error:  # a bug drops this frame, it does not take the node down
                self.get_logger().error(f"frame at {stamp:.2f} s crashed the detector: {error!r}")
                self._report(self.detector.refuse(f"frame at {stamp:.2f} s: internal error: {error!r}"))
        for frame in dropped:  # incomplete old frames, saying what they lacked
            self._report(self.detector.dropped(frame))

    def _process(self, stamp: float, parts: dict[str, Any]) -> None:
        try:
            frame = self._decode(stamp, parts)
        except ContractError as error:
            self._report(self.detector.reject_input(stamp, str(error)))
            return
        report = self.detector.process(frame, time.monotonic())
        self._report(report)
        if report.seen is not None and self.debug_pub.get_subscription_count():
            overlay = draw_estimate(frame.rgb, frame.intrinsics, report.seen)
            self.debug_pub.publish(array_to_image(overlay, "rgb8", parts["color"].header.frame_id, stamp))
        if report.confirmed is not None and report.handle_pose is not None:
            self.estimate_pub.publish(String(data=encode(report.confirmed)))
            self.handle_pub.publish(matrix_to_pose_stamped(report.handle_pose, Frame.ODOM.value, stamp))
            self.marker_pub.publish(door_markers(report.confirmed))

    def _decode(self, stamp: float, parts: dict[str, Any]) -> CameraFrame:
        """The frame's messages as arrays (:class:`ContractError` saying what is wrong with them)."""
        problem = self.detector.camera.frame_problem(
            {stream: parts[stream].header.frame_id for stream in ("color", "depth", "info")},
            parts["pose"].header.frame_id)
        if problem:
            raise ContractError(problem)
        rgb = image_to_array(parts["color"])
        if parts["color"].encoding != "rgb8":
            raise ContractError(f"colour must be rgb8, got {parts['color'].encoding!r}")
        intrinsics = camera_info_to_intrinsics(parts["info"])
        check_matches_image(intrinsics, rgb.shape[1], rgb.shape[0])
        return CameraFrame(stamp, rgb, depth_to_metres(parts["depth"]), intrinsics, pose_to_matrix(parts["pose"].pose))

    def _report(self, report: FrameReport) -> None:
        """Log a frame's ``report`` (at most every 2 s per severity) and put it on the heartbeat."""
        if report.warning:
            self.get_logger().warning(report.note, throttle_duration_sec=2.0)
        elif report.logged:
            self.get_logger().info(report.note, throttle_duration_sec=2.0)
        self._beat(report)

    def _beat(self, report: FrameReport) -> None:
        self.heartbeat.update(Health.WARN if report.warning else Health.OK, report.note[:120],
                              **self.detector.counters(), **report.values)


main = node_main(DoorDetectorNode, __name__)
