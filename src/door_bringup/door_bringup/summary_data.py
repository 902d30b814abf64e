"""The time series of a run's summary figure, read from its bag (ROS-free apart from decoding).

Everything comes from the bus; what the bus does not carry is derived, and says so:

* **time** is simulated time: header stamps where messages have them; the FSM's states
  (no header) are placed by the recorded /clock, interpolated at their bag time stamps, and
  read by their labels (a text that is no state's label is a ContractError, as a malformed
  door estimate is);
* **door angle**: the simulated hinge on /sim/door_joint_states (ground truth, evaluation only);
* **hands**: each tool-centre point from /joint_states and /odom through Pinocchio
  (``odom_T_tcp = odom_T_base · base_T_tcp(q)``);
* **handle**: *derived* — not on the bus while the door moves: the grasp point of the door
  estimate (/door/estimate, closed door) turned about the hinge axis by the measured hinge
  angle towards the door's opening side (the lever's own turn is ignored);
* **centre of mass**: Pinocchio's whole-body CoM of the same configurations, and the
  **support polygon** the convex hull of both soles (/feet, sole size from the robot profile);
  the **margin** is the CoM's horizontal distance to the polygon's edge, positive inside.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from rclpy.serialization import deserialize_message

from door_bringup.bags.storage import read_messages
from door_contract.converters.footsteps import path_to_footsteps
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.converters.pose import pose_to_matrix
from door_contract.geometry import planar_pose
from door_contract.payloads import DoorEstimate, decode
from door_contract.stamps import from_time_msg
from door_contract.topics import Topics
from door_contract.vocabulary import TaskState
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.walking.support import signed_margin, support_polygon
from door_sim_bridge.world.door import HINGE_JOINT
from door_viz.proposals import leaf_axes

__all__ = ["Decoded", "RunSeries", "handle_position", "read_run"]

SAMPLE_PERIOD_S = 0.1  # s of sim time between samples of the robot's state


@dataclass(frozen=True, eq=False)
class RunSeries:
    """Sim-time series of one run; arrays are empty where the bag had nothing."""

    estimate: DoorEstimate | None
    opening: str
    states: list[tuple[float, TaskState]]  # (sim time, state) at each change
    footsteps: list  # FootPlacement of every executed plan
    base: np.ndarray  # (N, 3): t, x, y
    door: np.ndarray  # (N, 2): t, hinge angle (rad)
    hands: dict[str, np.ndarray]  # side -> (N, 2): t, hand–handle distance (m)
    com: np.ndarray  # (N, 4): t, x, y, margin (m)
    support: list[np.ndarray]  # hull vertices (M, 2) at each CoM sample


SUMMARY_TOPICS = (Topics.CLOCK, Topics.DOOR_ESTIMATE, Topics.FOOTSTEP_REQUEST, Topics.MOTION_REQUEST, Topics.TASK_STATE,
                  Topics.FOOTSTEP_PLAN, Topics.DOOR_JOINT_STATES, Topics.ODOM, Topics.FOOT_POSES, Topics.JOINT_STATES)


Decoded = list[tuple[int, Any]]
"""(bag time ns, message) of one topic; ROS 2's generated message classes carry no types."""


def _decoded_by_topic(bag: Path) -> dict[str, Decoded]:
    """The summary's topics, decoded, in one pass over the bag (an mcap bag is decompressed once)."""
    classes = {topic.name: topic.msg_class() for topic in SUMMARY_TOPICS}
    messages: dict[str, Decoded] = {name: [] for name in classes}
    for message in read_messages(bag, list(classes)):
        messages[message.topic].append((message.timestamp_ns, deserialize_message(message.data, classes[message.topic])))
    return messages


def _sim_time_of(clock: Decoded) -> Callable[[int], float]:
    """Bag time (ns) → sim time (s), from the recorded /clock (identity without one)."""
    if not clock:
        return lambda ns: ns * 1e-9
    stamps = np.array([ns for ns, _ in clock], dtype=float)
    times = np.array([from_time_msg(msg.clock) for _, msg in clock])
    return lambda ns: float(np.interp(ns, stamps, times))


def _json_payloads(messages: Decoded) -> list[dict]:
    return [json.loads(msg.data) for _, msg in messages if msg.data]


def handle_position(estimate: DoorEstimate, opening: str, hinge_angle: float) -> np.ndarray:
    """The estimate's grasp point turned about the (vertical) hinge axis by ``hinge_angle``."""
    hinge, u, s, _ = leaf_axes(estimate, opening)
    offset = np.array(estimate.handle_position) - hinge
    along, across = offset @ u, offset @ s
    c, si = math.cos(hinge_angle), math.sin(hinge_angle)
    rotated_u, rotated_s = c * u + si * s, -si * u + c * s
    return hinge + along * rotated_u + across * rotated_s + np.array([0.0, 0.0, offset[2]])


def read_run(bag: Path, robot_profile: str = "talos", opening: str | None = None) -> RunSeries:
    """The summary's series of the run recorded in ``bag``."""
    bus = _decoded_by_topic(bag)
    sim_time = _sim_time_of(bus[Topics.CLOCK.name])
    estimates = _json_payloads(bus[Topics.DOOR_ESTIMATE.name])
    estimate = decode(DoorEstimate, json.dumps(estimates[-1])) if estimates else None
    requests = _json_payloads(bus[Topics.FOOTSTEP_REQUEST.name]) + _json_payloads(bus[Topics.MOTION_REQUEST.name])
    opening = opening or (requests[0]["opening"] if requests else "push")
    states = [(sim_time(ns), TaskState.of_label(msg.data)) for ns, msg in bus[Topics.TASK_STATE.name]]
    footsteps = [step for _, plan in bus[Topics.FOOTSTEP_PLAN.name] for step in path_to_footsteps(plan)]
    door = np.array([(from_time_msg(m.header.stamp), joint_state_to_positions(m).get(HINGE_JOINT, 0.0))
                     for _, m in bus[Topics.DOOR_JOINT_STATES.name]]).reshape(-1, 2)
    odometry = {(m.header.stamp.sec, m.header.stamp.nanosec): pose_to_matrix(m.pose.pose)
                for _, m in bus[Topics.ODOM.name]}
    base = np.array([(s + n * 1e-9, p[0, 3], p[1, 3]) for (s, n), p in sorted(odometry.items())]).reshape(-1, 3)
    hands, com, support = _robot_state(bus, robot_profile, odometry, estimate, opening, door)
    return RunSeries(estimate, opening, states, footsteps, base, door, hands, com, support)


def _robot_state(bus: dict, robot_profile: str, odometry: dict, estimate: DoorEstimate | None, opening: str,
                 door: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray, list[np.ndarray]]:
    """Hand–handle distances, CoM and its margin, sampled every SAMPLE_PERIOD_S of sim time."""
    profile = load_profile(robot_profile)
    kinematics = RobotKinematics(profile)
    known = set(kinematics.joint_names)
    feet = {(m.header.stamp.sec, m.header.stamp.nanosec): path_to_footsteps(m) for _, m in bus[Topics.FOOT_POSES.name]}
    hands: dict[str, list] = {side.value: [] for side in profile.arms}
    com, support, next_sample = [], [], -math.inf
    for _, msg in bus[Topics.JOINT_STATES.name]:
        key = (msg.header.stamp.sec, msg.header.stamp.nanosec)
        t = key[0] + key[1] * 1e-9
        if t < next_sample or key not in odometry:
            continue
        next_sample = t + SAMPLE_PERIOD_S - 1e-6  # stamps are whole nanoseconds
        base = odometry[key]
        q = kinematics.configuration({k: v for k, v in joint_state_to_positions(msg).items() if k in known})
        if estimate is not None and len(door):
            handle = handle_position(estimate, opening, float(np.interp(t, *door.T)))
            for side in profile.arms:
                tcp = (base @ kinematics.frame_pose(q, profile.tcp_frame(side)))[:3, 3]
                hands[side.value].append((t, float(np.linalg.norm(tcp - handle))))
        if key in feet:
            soles = [planar_pose(sole.x, sole.y, sole.yaw) for sole in feet[key]]
            polygon = support_polygon(soles, profile.walking.foot_length, profile.walking.foot_width)
            centre = (base @ np.append(kinematics.center_of_mass(q), 1.0))[:2]
            com.append((t, centre[0], centre[1], signed_margin(centre, polygon)))
            support.append(polygon)
    return ({side: np.array(values).reshape(-1, 2) for side, values in hands.items()},
            np.array(com).reshape(-1, 4), support)
