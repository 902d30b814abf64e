"""ROS 2 node ``/door_detector``: door and handle estimates from the head RGB-D camera.

Thin glue over :class:`door_detection.detector.DoorDetector` ([Banerjee 2015] Sec. III): the
camera's streams (colour, depth, CameraInfo, the camera's pose in odom) are matched by stamp
(:mod:`door_detection.frame_sync`), decoded through the contract and handed to the core, which
detects (automatic, or operator-aided after a scribble on ``/operator/scribble``), votes and
says what to publish: ``/door/estimate``, ``/door/handle_pose``, markers and the debug image
(:mod:`door_detection.overlay`). The camera is the ``robot_profile``'s head camera. Bad frames
(empty, wrong encoding, size mismatch, no valid depth, inconsistent CameraInfo, another camera's
frame) are logged and counted; nothing is published. A frame that never completes is reported
on /diagnostics with the stream it lacked; a bad scribble is refused at once. While no door is
confirmed it asks on ``/door_detector/look`` to pan and tilt the head (:mod:`door_detection.head_search`,
from ``/joint_states``); the FSM sends those moves to the robot only while DETECT_DOOR waits.
"""

from __future__ import annotations

import time
from functools import partial
from typing import Any

import numpy as np
from geometry_msgs.msg import PolygonStamped, PoseStamped
from rclpy.node import Node
from sensor_msgs.msg import CameraInfo, Image, JointState
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.converters.image import array_to_image
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.converters.pose import matrix_to_pose_stamped
from door_contract.converters.trajectory import joint_path_to_msg
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
from door_contract.payloads import encode
from door_contract.stamps import from_time_msg
from door_contract.topics import Topics, TopicSpec
from door_detection.detector import DetectorCamera, DoorDetector, FrameReport
from door_detection.errors import DetectionError
from door_detection.frame_messages import decode_frame
from door_detection.frame_sync import STREAMS, FrameSync
from door_detection.head_search import head_search_of
from door_detection.markers import door_markers
from door_detection.overlay import draw_estimate
from door_detection.parameters import DETECTOR_PARAMETERS, NODE_NAME
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile

__all__ = ["DoorDetectorNode", "main"]


class DoorDetectorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = self.parameters = declare_parameters(self, DETECTOR_PARAMETERS)
        with as_parameter_error(f"parameter 'robot_profile' = {p['robot_profile']!r}", RobotModelError):
            profile = load_profile(p["robot_profile"])
            camera = DetectorCamera.of(profile)
            self.search = head_search_of(RobotKinematics(profile), p["head_search_max_pan"]) if p["head_search"] else None
        self.joints: dict[str, float] | None = None  # the robot's, for the head search
        with as_parameter_error("detection options", DetectionError):
            self.detector = DoorDetector.from_parameters(p, camera)
        self.sync = FrameSync(p["sync_tolerance"])  # the streams matched into frames by stamp
        self.heartbeat = Heartbeat(self)
        self.heartbeat.update(Health.OK, "ready", camera=camera.camera_link)

        def pub(topic: TopicSpec) -> Any:
            return create_contract_publisher(self, topic)
        self.estimate_pub, self.handle_pub = pub(Topics.DOOR_ESTIMATE), pub(Topics.HANDLE_POSE)
        self.marker_pub, self.debug_pub = pub(Topics.DOOR_MARKERS), pub(Topics.DETECTION_DEBUG_IMAGE)
        self.look_pub = pub(Topics.HEAD_LOOK)
        create_contract_subscription(self, Topics.JOINT_STATES, self._on_joint_states)
        for stream, topic in zip(STREAMS, (Topics.COLOR_IMAGE, Topics.DEPTH_IMAGE, Topics.COLOR_INFO,
                                           Topics.CAMERA_POSE)):
            create_contract_subscription(self, topic, partial(self._on_stream, stream))
        create_contract_subscription(self, Topics.SCRIBBLE, self._on_scribble)
        self.get_logger().info(f"ready: {camera.robot}'s camera {camera.camera_link}, voting over "
                               f"{p['vote_frames']} frames (confirmed from {p['vote_min_agreeing']} agreeing), "
                               f"doors {p['door_width_min']:.2f}–{p['door_width_max']:.2f} m, head search "
                               f"{'on' if self.search else 'off'}")

    def _on_joint_states(self, msg: JointState) -> None:
        try:
            self.joints = joint_state_to_positions(msg)
        except ContractError:
            self.joints = None  # the sim bridge's own node reports it; the search waits for good ones

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
            frame = decode_frame(self.detector.camera, stamp, parts)
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
        if self.search and (look := self.search.after_frame(stamp, self.joints, report.seen is not None,
                                                            report.confirmed is not None)):
            self.look_pub.publish(joint_path_to_msg(look.as_path()))  # the FSM sends it while DETECT_DOOR waits
            self.get_logger().info(f"no door confirmed: {look}", throttle_duration_sec=2.0)

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
