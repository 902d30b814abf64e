"""Every topic and service of the graph: name, type, QoS, frame and unit, defined once.

Nodes, tests, the bag tools and the README table read these specs; nothing else spells a
topic name. Structured requests and outcomes between nodes travel as JSON in
``std_msgs/String`` (schemas in :mod:`door_contract.payloads`), so the graph needs
standard messages only and a rosbag of a run stays readable.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import MappingProxyType

from door_contract.frames import Frame
from door_contract.qos import CLOCK, EVENTS, LATCHED, REQUESTS, SENSOR, SERVICE, TF_STREAM, QosSpec
from door_contract.vocabulary import PlannerKind

__all__ = ["PLANNER_TOPICS", "PlannerTopics", "ServiceSpec", "Services", "TopicSpec", "Topics", "interface_class"]


@dataclass(frozen=True)
class TopicSpec:
    """One topic of the contract."""

    name: str
    type_name: str  # ROS interface name, e.g. "sensor_msgs/msg/Image"
    qos: QosSpec
    publisher: str  # who publishes it
    meaning: str
    frame: str = ""
    unit: str = ""

    def msg_class(self) -> type:
        """The message class, imported on first use (the contract itself stays import-light)."""
        return interface_class(self.type_name)


@dataclass(frozen=True)
class ServiceSpec:
    """One service of the contract.

    ``qos``: the request and response queues. rclpy's default keeps 10, so a burst of 100
    calls got 20 answers (issue #12); the contract's services queue deeply.
    """

    name: str
    type_name: str  # e.g. "std_srvs/srv/SetBool"
    server: str
    meaning: str
    qos: QosSpec = SERVICE

    def srv_class(self) -> type:
        return interface_class(self.type_name)


def interface_class(type_name: str) -> type:
    package, kind, name = type_name.split("/")
    interface: type = getattr(importlib.import_module(f"{package}.{kind}"), name)
    return interface


class Topics:
    """The topic table of DESIGN.md plus the developers' internal topics."""

    CLOCK = TopicSpec("/clock", "rosgraph_msgs/msg/Clock", CLOCK, "sim_bridge",
                      "simulation time; nodes run with use_sim_time", unit="s")
    JOINT_STATES = TopicSpec("/joint_states", "sensor_msgs/msg/JointState", SENSOR, "sim_bridge",
                             "all robot joints", unit="rad, rad/s")
    ODOM = TopicSpec("/odom", "nav_msgs/msg/Odometry", SENSOR, "sim_bridge",
                     "robot base pose", frame=Frame.ODOM.value, unit="m, rad")
    COLOR_IMAGE = TopicSpec("/head_camera/color/image_raw", "sensor_msgs/msg/Image", SENSOR,
                            "sim_bridge", "head camera colour image (rgb8)",
                            frame=Frame.HEAD_CAMERA_OPTICAL.value)
    COLOR_INFO = TopicSpec("/head_camera/color/camera_info", "sensor_msgs/msg/CameraInfo", SENSOR,
                           "sim_bridge", "colour intrinsics", frame=Frame.HEAD_CAMERA_OPTICAL.value)
    DEPTH_IMAGE = TopicSpec("/head_camera/depth/image_raw", "sensor_msgs/msg/Image", SENSOR,
                            "sim_bridge", "depth registered to colour (32FC1)",
                            frame=Frame.HEAD_CAMERA_OPTICAL.value, unit="m")
    DEPTH_INFO = TopicSpec("/head_camera/depth/camera_info", "sensor_msgs/msg/CameraInfo", SENSOR,
                           "sim_bridge", "depth intrinsics", frame=Frame.HEAD_CAMERA_OPTICAL.value)
    FOOT_POSES = TopicSpec("/feet", "nav_msgs/msg/Path", SENSOR, "sim_bridge",
                           "where the soles stand: poses[0] left, poses[1] right (also on /tf)",
                           frame=Frame.ODOM.value, unit="m")
    CAMERA_POSE = TopicSpec("/head_camera/pose", "geometry_msgs/msg/PoseStamped", SENSOR, "sim_bridge",
                            "head camera optical frame in odom, stamped like its images (also on /tf)",
                            frame=Frame.ODOM.value, unit="m")
    TF = TopicSpec("/tf", "tf2_msgs/msg/TFMessage", TF_STREAM, "sim_bridge",
                   "odom → base_link and every moving joint of the robot, stamped with sim time",
                   frame=Frame.ODOM.value, unit="m")
    TF_STATIC = TopicSpec("/tf_static", "tf2_msgs/msg/TFMessage", LATCHED, "sim_bridge",
                          "the URDF's fixed joints and the head camera's optical frame (transient local)",
                          unit="m")
    ROBOT_DESCRIPTION = TopicSpec("/robot_description", "std_msgs/msg/String", LATCHED, "sim_bridge",
                                  "URDF the sim loaded, meshes as package:// (or file://) URIs "
                                  "(transient local)")
    DOOR_JOINT_STATES = TopicSpec("/sim/door_joint_states", "sensor_msgs/msg/JointState", SENSOR,
                                  "sim_bridge", "ground-truth hinge and handle angles "
                                  "(evaluation only)", unit="rad")
    EXECUTION_OUTCOME = TopicSpec("/sim/execution_outcome", "std_msgs/msg/String", REQUESTS,
                                  "sim_bridge", "JSON ExecutionOutcome when a trajectory or "
                                  "footstep plan finishes or is rejected")
    ARM_TRAJECTORY = TopicSpec("/arm_controller/joint_trajectory",
                               "trajectory_msgs/msg/JointTrajectory", EVENTS, "fsm_supervisor",
                               "approved trajectory to execute; one without points stops the arm and "
                               "holds (ros2_control)", unit="rad, s")
    FOOTSTEP_PLAN = TopicSpec("/footstep_plan", "nav_msgs/msg/Path", EVENTS, "fsm_supervisor",
                              "approved footsteps to walk (even index = left foot, odd = right); an "
                              "empty path stops at the next stable stance",
                              frame=Frame.ODOM.value, unit="m")
    WALK_CROUCH = TopicSpec("/walking/crouch", "std_msgs/msg/Float64", LATCHED, "fsm_supervisor",
                            "how far below its standing height the pelvis walks the next footstep plans "
                            "(0 upright, negative above; a push door's lever at the pelvis); set with "
                            "each walk's request, read when a plan starts", unit="m")
    HANDLE_POSE = TopicSpec("/door/handle_pose", "geometry_msgs/msg/PoseStamped", EVENTS,
                            "door_detector", "handle grasp point; x = door normal towards the "
                            "robot, z up", frame=Frame.ODOM.value, unit="m")
    DOOR_ESTIMATE = TopicSpec("/door/estimate", "std_msgs/msg/String", LATCHED, "door_detector",
                              "JSON DoorEstimate: corners, normal, width, hinge side, confidence",
                              frame=Frame.ODOM.value, unit="m")
    DOOR_MARKERS = TopicSpec("/door/markers", "visualization_msgs/msg/MarkerArray", EVENTS,
                             "door_detector", "door, handle and normal for RViz/Foxglove",
                             frame=Frame.ODOM.value)
    DETECTION_DEBUG_IMAGE = TopicSpec("/door_detector/debug_image", "sensor_msgs/msg/Image",
                                      SENSOR, "door_detector", "colour image with overlays",
                                      frame=Frame.HEAD_CAMERA_OPTICAL.value)
    HEAD_LOOK = TopicSpec("/door_detector/look", "trajectory_msgs/msg/JointTrajectory", EVENTS,
                          "door_detector", "where the head search wants the neck while no door is "
                          "confirmed (the FSM executes it only while DETECT_DOOR waits)", unit="rad, s")
    SCRIBBLE = TopicSpec("/operator/scribble", "geometry_msgs/msg/PolygonStamped", EVENTS,
                         "operator", "pixel polygon on the handle: operator-aided detection",
                         unit="px")
    FOOTSTEP_REQUEST = TopicSpec("/footstep_planner/request", "std_msgs/msg/String", REQUESTS,
                                 "fsm_supervisor", "JSON FootstepRequest (id, goal)")
    FOOTSTEP_CANCEL = TopicSpec("/footstep_planner/cancel", "std_msgs/msg/String", REQUESTS,
                                "fsm_supervisor", "JSON PlanningCancel: drop a request (answered "
                                "superseded)")
    FOOTSTEP_PROPOSAL = TopicSpec("/footstep_planner/plan", "nav_msgs/msg/Path", EVENTS,
                                  "footstep_planner", "planned footsteps awaiting approval",
                                  frame=Frame.ODOM.value, unit="m")
    FOOTSTEP_OUTCOME = TopicSpec("/footstep_planner/outcome", "std_msgs/msg/String", REQUESTS,
                                 "footstep_planner", "JSON PlanningOutcome for a request id")
    FOOTSTEP_MARKERS = TopicSpec("/footstep_planner/markers", "visualization_msgs/msg/MarkerArray",
                                 EVENTS, "footstep_planner", "footprints for RViz/Foxglove",
                                 frame=Frame.ODOM.value)
    MOTION_REQUEST = TopicSpec("/trajectory_optimizer/request", "std_msgs/msg/String", REQUESTS,
                               "fsm_supervisor", "JSON MotionRequest (id, motion, backend)")
    MOTION_CANCEL = TopicSpec("/trajectory_optimizer/cancel", "std_msgs/msg/String", REQUESTS,
                              "fsm_supervisor", "JSON PlanningCancel: drop a request (answered "
                              "superseded)")
    MOTION_PROPOSAL = TopicSpec("/trajectory_optimizer/trajectory",
                                "trajectory_msgs/msg/JointTrajectory", EVENTS,
                                "trajectory_optimizer", "optimised trajectory awaiting approval",
                                unit="rad, s")
    MOTION_OUTCOME = TopicSpec("/trajectory_optimizer/outcome", "std_msgs/msg/String", REQUESTS,
                               "trajectory_optimizer", "JSON PlanningOutcome for a request id")
    PROPOSAL_MARKERS = TopicSpec("/door_task/proposal_markers", "visualization_msgs/msg/MarkerArray",
                                 LATCHED, "proposal_markers", "what the FSM is offered: footsteps, the "
                                 "hand's path of each trajectory, the door and its swing (transient local)",
                                 frame=Frame.ODOM.value)
    TASK_STATE = TopicSpec("/door_task/state", "std_msgs/msg/String", LATCHED, "fsm_supervisor",
                           "current FSM state")
    APPROVAL_REQUEST = TopicSpec("/door_task/approval_request", "std_msgs/msg/String", LATCHED,
                                 "fsm_supervisor", "what the FSM proposes and waits for")
    TASK_REPORT = TopicSpec("/door_task/report", "std_msgs/msg/String", LATCHED, "fsm_supervisor",
                            "JSON TaskReport when the task ends: every state attempt with its "
                            "outcome, planning, waiting and moving time", unit="s")
    OPERATOR = TopicSpec("/door_task/operator", "std_msgs/msg/String", REQUESTS, "operator",
                         "approve N, reject N, repeat N (N = the request id); pause, stop, resume, "
                         "abort, manual")
    DIAGNOSTICS = TopicSpec("/diagnostics", "diagnostic_msgs/msg/DiagnosticArray", EVENTS, "all",
                            "health, timings, outcomes")

    @classmethod
    def all(cls) -> tuple[TopicSpec, ...]:
        return tuple(v for v in vars(cls).values() if isinstance(v, TopicSpec))


@dataclass(frozen=True)
class PlannerTopics:
    """One planner's topics: the FSM requests and cancels, the planner proposes and answers."""

    request: TopicSpec
    proposal: TopicSpec
    outcome: TopicSpec
    cancel: TopicSpec


PLANNER_TOPICS = MappingProxyType({
    PlannerKind.FOOTSTEPS: PlannerTopics(Topics.FOOTSTEP_REQUEST, Topics.FOOTSTEP_PROPOSAL, Topics.FOOTSTEP_OUTCOME,
                                         Topics.FOOTSTEP_CANCEL),
    PlannerKind.MOTION: PlannerTopics(Topics.MOTION_REQUEST, Topics.MOTION_PROPOSAL, Topics.MOTION_OUTCOME,
                                      Topics.MOTION_CANCEL)})
"""Each planner's topics, by kind (read-only)."""


class Services:
    LEFT_GRASP = ServiceSpec("/left_hand/grasp", "std_srvs/srv/SetBool", "sim_bridge",
                             "close (true) / open (false) the left hand; attaches within 2 cm")
    RIGHT_GRASP = ServiceSpec("/right_hand/grasp", "std_srvs/srv/SetBool", "sim_bridge",
                              "close (true) / open (false) the right hand; attaches within 2 cm")

    @classmethod
    def all(cls) -> tuple[ServiceSpec, ...]:
        return tuple(v for v in vars(cls).values() if isinstance(v, ServiceSpec))
