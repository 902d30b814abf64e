"""ROS 2 node ``/door_detector``: door and handle estimates from the head RGB-D camera.

Each frame (colour + depth + CameraInfo + the camera's pose in odom, matched by stamp)
goes through the automatic pipeline ([Banerjee 2015] Sec. III-A) — or, when the operator has
scribbled on the handle (``/operator/scribble``), the operator-aided one (Sec. III-B),
which then takes precedence. Estimates are moved into ``odom`` and voted over the last N
frames (a sequential vote: confirmed as soon as enough agree precisely, whatever view of
the head search they came from); the consensus goes out as ``/door/estimate``,
``/door/handle_pose`` and markers.
Bad frames (empty, wrong encoding, size mismatch, no valid depth, inconsistent
CameraInfo) are logged and counted; nothing is published. A frame that never completes
(e.g. no CameraInfo) is reported on /diagnostics with the stream it lacked. A scribble is
checked on arrival (:mod:`door_detection.scribble`): a bad one is refused at once and
automatic detection goes on. Streams are matched by :mod:`door_detection.frame_sync`, the debug
image drawn by :mod:`door_detection.overlay`.
"""

from __future__ import annotations

import time

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
from door_contract.topics import Topics
from door_detection.automatic import detect_automatic
from door_detection.errors import DetectionError
from door_detection.frame_sync import STREAMS, DroppedFrame, FrameSync
from door_detection.markers import door_markers
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.overlay import draw_estimate
from door_detection.parameters import DETECTOR_PARAMETERS, NODE_NAME
from door_detection.payload import contract_estimate
from door_detection.scribble import scribble_problem
from door_detection.voting import Voter

VOTE_PARAMETERS = ("vote_frames", "vote_min_agreeing", "vote_handle_confidence", "vote_normal_confidence_deg")
"""Node parameters that are the sequential vote's DetectionOptions fields of the same name."""


class DoorDetectorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, DETECTOR_PARAMETERS)
        self.parameters = p
        require_ordered(p, "door_width_min", "door_width_max")
        with as_parameter_error("detection options", DetectionError):
            self.options = DetectionOptions(door_width_min=p["door_width_min"], door_width_max=p["door_width_max"],
                                            **{name: p[name] for name in VOTE_PARAMETERS})
        self.voter = Voter(self.options)
        self.sync = FrameSync(p["sync_tolerance"])  # the streams matched into frames by stamp
        self.scribble: tuple[float, np.ndarray] | None = None  # (wall time, N×2 pixels)
        self.frames = self.rejected = self.incomplete = 0
        self.image_size: tuple[int, int] | None = None  # (width, height) of the last CameraInfo
        self.heartbeat = Heartbeat(self)
        def pub(topic):
            return create_contract_publisher(self, topic)
        self.estimate_pub, self.handle_pub = pub(Topics.DOOR_ESTIMATE), pub(Topics.HANDLE_POSE)
        self.marker_pub, self.debug_pub = pub(Topics.DOOR_MARKERS), pub(Topics.DETECTION_DEBUG_IMAGE)
        for stream, topic in zip(STREAMS, (Topics.COLOR_IMAGE, Topics.DEPTH_IMAGE, Topics.COLOR_INFO,
                                           Topics.CAMERA_POSE)):
            create_contract_subscription(self, topic, lambda msg, s=stream: self._on_stream(s, msg))
        create_contract_subscription(self, Topics.SCRIBBLE, self._on_scribble)
        self.get_logger().info(f"ready: voting over {p['vote_frames']} frames (confirmed from "
                               f"{p['vote_min_agreeing']} agreeing), doors "
                               f"{p['door_width_min']:.2f}–{p['door_width_max']:.2f} m")

    # ------------------------------------------------------------------ inputs
    def _on_scribble(self, msg: PolygonStamped) -> None:
        pixels = np.array([[p.x, p.y] for p in msg.polygon.points], dtype=float).reshape(-1, 2)
        problem = scribble_problem(pixels, *(self.image_size or (None, None)))
        if problem:
            note = f"scribble refused: {problem}; automatic detection goes on"
            self.get_logger().warning(note)
            self.heartbeat.update(Health.WARN, note, frames=self.frames, rejected=self.rejected)
            return
        self.scribble = (time.monotonic(), pixels)
        self.voter.reset()  # the operator's word replaces what was voted so far
        note = f"scribble with {len(pixels)} points: operator-aided detection next"
        self.get_logger().info(note)
        self.heartbeat.update(Health.OK, note, frames=self.frames, rejected=self.rejected)

    def _on_stream(self, stream: str, msg: Image | CameraInfo | PoseStamped) -> None:
        if stream == "info":
            self.image_size = (int(msg.width), int(msg.height))
        complete, dropped = self.sync.add(stream, from_time_msg(msg.header.stamp), msg)
        if complete is not None:
            key, frame = complete
            try:
                self._process(key, frame)
            except Exception as error:  # a bug drops this frame, it does not take the node down
                self.get_logger().error(f"frame at {key:.2f} s crashed the detector: {error!r}")
                self._reject(f"frame at {key:.2f} s: internal error: {error!r}")
        for frame_dropped in dropped:  # incomplete old frames, saying what they lacked
            self._report_incomplete(frame_dropped)

    def _report_incomplete(self, dropped: DroppedFrame) -> None:
        self.incomplete += 1
        missing = dropped.describe()
        note = f"frame at {dropped.stamp:.2f} s dropped: no {missing} with its stamp"
        self.get_logger().warning(note, throttle_duration_sec=2.0)
        self.heartbeat.update(Health.WARN, note, frames=self.frames, rejected=self.rejected,
                              incomplete=self.incomplete, missing=missing)

    # ------------------------------------------------------------------ one frame
    def _process(self, stamp: float, frame: dict) -> None:
        self.frames += 1
        try:
            rgb = image_to_array(frame["color"])
            if frame["color"].encoding != "rgb8":
                raise ContractError(f"colour must be rgb8, got {frame['color'].encoding!r}")
            depth = depth_to_metres(frame["depth"])
            intrinsics = camera_info_to_intrinsics(frame["info"])
            check_matches_image(intrinsics, rgb.shape[1], rgb.shape[0])
            camera_pose = pose_to_matrix(frame["pose"].pose)
        except ContractError as error:
            self._reject(f"frame at {stamp:.2f} s rejected: {error}")
            return
        result = self._detect(rgb, depth, intrinsics, camera_pose)
        if not result.ok:
            self._reject(f"frame at {stamp:.2f} s: {result.outcome.value}: {result.reason}", Health.OK)
            self.voter.add(None)
            return
        in_odom = result.estimate.transformed(camera_pose)
        vote = self.voter.add(in_odom)
        self.heartbeat.update(Health.OK, f"{vote.outcome.value} {vote.agreeing}/{vote.window}",
                              frame_ms=round(result.elapsed * 1000.0, 1), frames=self.frames,
                              rejected=self.rejected, mode=result.estimate.mode.value)
        self._publish_debug(frame["color"], rgb, intrinsics, result.estimate)
        if vote.ok:
            self._publish(stamp, vote.estimate)

    def _detect(self, rgb, depth, intrinsics, camera_pose):
        up_in_optical = camera_pose[:3, :3].T @ np.array([0.0, 0.0, 1.0])
        if self.scribble is not None and time.monotonic() - self.scribble[0] <= self.parameters["scribble_timeout"]:
            return detect_from_scribble(rgb, depth, intrinsics, self.scribble[1], self.options, up=up_in_optical)
        return detect_automatic(rgb, depth, intrinsics, self.options)

    def _reject(self, reason: str, health: Health = Health.WARN) -> None:
        self.rejected += 1
        self.get_logger().warning(reason, throttle_duration_sec=2.0)
        self.heartbeat.update(health, reason[:120], frames=self.frames, rejected=self.rejected)

    # ------------------------------------------------------------------ outputs
    def _publish(self, stamp: float, estimate) -> None:
        payload = contract_estimate(estimate, stamp, self.parameters)
        self.estimate_pub.publish(String(data=encode(payload)))
        pose = estimate.handle_pose(up=np.array([0.0, 0.0, 1.0]))
        self.handle_pub.publish(matrix_to_pose_stamped(pose, Frame.ODOM.value, stamp))
        self.marker_pub.publish(door_markers(payload))

    def _publish_debug(self, color_msg: Image, rgb: np.ndarray, intrinsics, estimate) -> None:
        if self.debug_pub.get_subscription_count() == 0:
            return
        overlay = draw_estimate(rgb, intrinsics, estimate)
        self.debug_pub.publish(array_to_image(overlay, "rgb8", color_msg.header.frame_id,
                                              from_time_msg(color_msg.header.stamp)))


main = node_main(DoorDetectorNode, __name__)
