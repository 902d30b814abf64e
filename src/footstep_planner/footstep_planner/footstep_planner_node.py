"""ROS 2 node ``/footstep_planner``: A* footsteps to the stand pose and through the door.

A :class:`~door_contract.payloads.FootstepRequest` ("stand" or "through") is planned from
the robot's odometry and the last door estimate; the plan goes out on
``/footstep_planner/plan`` (even index = left foot) with markers, then a PlanningOutcome
with the plan's stamp. Bad or missing inputs and unreachable goals end in a failure
outcome with the planner's reason, within its expansion and time bounds. Every request
whose id can be read gets exactly one outcome; planning runs on a worker thread, the
newest request (or a cancel on ``/footstep_planner/cancel``) supersedes an older one
(:mod:`door_contract.planner_service`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from rclpy.node import Node
from std_msgs.msg import String
from visualization_msgs.msg import Marker, MarkerArray

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import Foot as ContractFoot
from door_contract.converters.footsteps import FootPlacement, footsteps_to_path
from door_contract.door_estimates import door_estimate_problem
from door_contract.geometry import yaw_of
from door_contract.errors import ContractError
from door_contract.frames import Frame
from door_contract.node_support import (Heartbeat, as_parameter_error, create_contract_publisher,
                                        declare_parameters, run_node)
from door_contract.planner_inputs import PlannerInputs
from door_contract.planner_desk import PlannerDesk
from door_contract.planner_service import Finished
from door_contract.stamps import UniqueStamps, stamp_ns, time_msg_of_ns
from door_contract.payloads import (DoorEstimate, FootstepRequest, OutcomeStatus, PlanningOutcome, encode,
                                    without_non_finite)
from door_contract.topics import Topics
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile
from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import DoorGeometry, DoorOpening, HingeSide, wall_obstacles
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Foot, Footstep, Pose2D, Stance
from footstep_planner.goals import (pull_passage_waypoints, replan_needed, stand_pose_for_opening,
                                   through_door_pose)
from footstep_planner.legs import plan_legs
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.parameters import NODE_NAME, PLANNER_PARAMETERS
from footstep_planner.plan import FootstepPlan, PlanResult
from footstep_planner.world import World


class RequestRefused(Exception):
    pass


@dataclass(frozen=True)
class Snapshot:
    """The inputs a request is planned from, taken when it arrives (the measured state)."""

    base_pose: np.ndarray | None
    feet: list | None
    estimate: DoorEstimate | None
    planned_stance: Stance | None


@dataclass(frozen=True)
class Solved:
    start: Stance
    waypoints: tuple[Pose2D, ...]
    result: PlanResult


STEP_LIMIT_MARGIN = 0.95  # plan within 95 % of the robot's step limits: the robot checks its own


def planner_options(profile_name: str, parameters: dict) -> FootstepPlannerOptions:
    """Planner options from the robot profile's walking limits and the node's parameters."""
    walking = load_profile(profile_name).walking
    return FootstepPlannerOptions(
        max_stride=walking.max_stride * STEP_LIMIT_MARGIN, max_side_step=walking.max_side_step * STEP_LIMIT_MARGIN,
        max_turn=walking.max_turn * STEP_LIMIT_MARGIN,
        nominal_foot_separation=walking.foot_separation,
        min_foot_separation=min(0.16, walking.foot_separation * 0.9),
        foot_length=walking.foot_length, foot_width=walking.foot_width,
        body_half_width=walking.body_width / 2.0, body_half_depth=walking.body_depth / 2.0,
        heuristic_weight=parameters["heuristic_weight"], max_expansions=parameters["max_expansions"],
        max_planning_time=parameters["max_planning_time"])


def door_geometry_from_estimate(estimate: DoorEstimate, opening: DoorOpening, angle: float,
                                handle_standoff: float) -> DoorGeometry:
    """The planner's door from a detector estimate (odom): the handle's face point fixes the
    door along the wall; the measured edges (``corners``: bottom-hinge, bottom-free, …) give
    the opening between the jambs and the handle's distance from the free edge. Without
    edges (operator-aided estimates) the DRC door's dimensions are assumed."""
    normal = np.asarray(estimate.normal[:2]) / np.linalg.norm(estimate.normal[:2])
    face = np.asarray(estimate.handle_position[:2]) - handle_standoff * normal
    dimensions = {}
    corners = np.asarray(estimate.corners, dtype=float)
    if corners.shape == (4, 3) and np.isfinite(corners).all():
        hinge, free = corners[0, :2], corners[1, :2]
        width = float(np.linalg.norm(free - hinge))
        handle_offset = width - float((face - hinge) @ (free - hinge)) / max(width, 1e-9)
        if 0.5 <= width <= 1.5 and 0.0 < handle_offset < width:
            dimensions = {"leaf_width": width, "clear_opening": width, "handle_offset": handle_offset}
    return DoorGeometry.from_handle(float(face[0]), float(face[1]), math.atan2(normal[1], normal[0]),
                                    HingeSide(estimate.hinge_side.value), opening, angle=angle, **dimensions)


class FootstepPlannerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, PLANNER_PARAMETERS)
        with as_parameter_error("footstep planner options", FootstepPlannerError, RobotModelError):
            self.options = planner_options(self.parameters["robot_profile"], self.parameters)
        self.passage_angle: float | None = None
        self.planned_stance: Stance | None = None  # where the last plan leaves the feet
        self.heartbeat = Heartbeat(self)
        self.inputs = PlannerInputs(self, self.heartbeat)
        self.plan_pub = create_contract_publisher(self, Topics.FOOTSTEP_PROPOSAL)
        self.outcome_pub = create_contract_publisher(self, Topics.FOOTSTEP_OUTCOME)
        self.marker_pub = create_contract_publisher(self, Topics.FOOTSTEP_MARKERS)
        self.stamps = UniqueStamps()
        self.desk = PlannerDesk(self, self.heartbeat, FootstepRequest, (Topics.FOOTSTEP_REQUEST, Topics.FOOTSTEP_CANCEL),
                                lambda r: self.inputs.doors.pick(r.door_stamp, r.door), self._job_for,
                                self._deliver_one, lambda rid, why: self._answer(rid, "?", OutcomeStatus.REJECTED, why))
        self.get_logger().info(f"ready: {self.parameters['robot_profile']} steps ≤ {self.options.max_stride} m, "
                               f"heuristic weight {self.options.heuristic_weight}")

    def _job_for(self, request: FootstepRequest, estimate: DoorEstimate | None):
        """The planning job of ``request`` over the inputs as they are now (the measured state)."""
        snapshot = Snapshot(None if self.inputs.base_pose is None else self.inputs.base_pose.copy(),
                            self.inputs.feet, estimate, self.planned_stance)
        return lambda: self._solve(request, snapshot)

    def _solve(self, request: FootstepRequest, snapshot: Snapshot) -> Solved:
        """On the worker thread: the problem from the snapshot, then the search."""
        start, waypoints, world = self._problem(request, snapshot)
        return Solved(start, waypoints, self._plan(world, start, waypoints, self._options_for(request.goal, len(waypoints))))

    def _deliver_one(self, finished: Finished) -> None:
        """On the executor thread: one outcome per finished request, and the plan if proposed."""
        request = finished.request
        if finished.dropped:
            self._answer(request.request_id, request.goal, OutcomeStatus.SUPERSEDED, finished.dropped)
            return
        if isinstance(finished.error, (RequestRefused, FootstepPlannerError, ContractError)):
            self._answer(request.request_id, request.goal, OutcomeStatus.REJECTED, str(finished.error))
            return
        if finished.error is not None:  # a bug must end in a failure outcome, not a dead node
            self.get_logger().error(f"request {request.request_id} crashed the planner: {finished.error!r}")
            self._answer(request.request_id, request.goal, OutcomeStatus.FAILURE, f"internal error: {finished.error!r}")
            return
        start, waypoints, result = finished.result.start, finished.result.waypoints, finished.result.result
        if not result.succeeded:
            self._answer(request.request_id, request.goal, OutcomeStatus.FAILURE,
                         f"{result.outcome.value}: {result.reason}", result.planning_time,
                         {"expansions": result.expansions})
            return
        self.planned_stance = result.plan.final_stance
        placements = contract_footsteps(start, result.plan)
        path = footsteps_to_path(placements)
        path.header.stamp = time_msg_of_ns(self.stamps.next(self.get_clock().now().nanoseconds))
        self.plan_pub.publish(path)
        self.marker_pub.publish(footstep_markers(placements, self.options))
        goal = waypoints[-1]
        length = float(np.hypot(goal.x - start.left.x / 2 - start.right.x / 2, goal.y - start.left.y / 2 - start.right.y / 2))
        self._answer(request.request_id, request.goal, OutcomeStatus.SUCCESS, "", result.planning_time,
                     {"stamp_ns": stamp_ns(path.header.stamp), "steps": len(result.plan.steps), "length_m": round(length, 3),
                      "expansions": result.expansions})

    def _options_for(self, goal: str, legs: int) -> FootstepPlannerOptions:
        """The stand pose is where the arm must reach the handle: the walk ends exactly on it
        (snap_to_goal; 4 cm and 3.8° off, within the search's goal tolerance, made a turn
        unreachable). So do the legs of a walk through waypoints (the pull door's turns
        sweep the door open). A plain passage keeps the search's tolerance."""
        return replace(self.options, snap_to_goal=True) if goal == "stand" or legs > 1 else self.options

    def _plan(self, world: World, start: Stance, waypoints: tuple[Pose2D, ...],
              options: FootstepPlannerOptions) -> PlanResult:
        if len(waypoints) > 1:
            return plan_legs(FootstepPlanner(world, options), start, waypoints)
        result, relaxed_from = FootstepPlanner(world, options).plan_from_within_margins(start, waypoints[0])
        if relaxed_from:
            self.get_logger().warning(f"{relaxed_from}: planned once more without safety margins")
        return result

    def _problem(self, request: FootstepRequest, snapshot: Snapshot) -> tuple[Stance, tuple[Pose2D, ...], World]:
        """Start stance, the body poses to walk through in order, and the obstacles."""
        if snapshot.base_pose is None:
            raise RequestRefused("no valid odometry yet")
        estimate = snapshot.estimate
        if estimate is None:
            raise RequestRefused("no door estimate yet" if request.door_stamp < 0 else
                                 f"door estimate of stamp {request.door_stamp:.3f} s was not received")
        if door_estimate_problem(estimate):
            raise RequestRefused(door_estimate_problem(estimate))
        if request.goal not in ("stand", "through"):
            raise RequestRefused(f"unknown goal {request.goal!r}; use 'stand' or 'through'")
        if request.opening not in ("push", "pull"):
            raise RequestRefused(f"unknown opening {request.opening!r}; use 'push' or 'pull'")
        pose = snapshot.base_pose
        body = Pose2D(float(pose[0, 3]), float(pose[1, 3]), yaw_of(pose))
        start = self._start_stance(body, snapshot)
        door = self._door_geometry(request, estimate)
        if request.goal == "stand":
            # the door is shut while the robot walks there; the stand pose itself keeps the
            # torso out of the pulled leaf's swing (the walking grippers would touch it)
            return start, (self._stand_pose(door),), World.from_door(door)
        if door.opening is DoorOpening.PULL:  # the other hand blocks the leaf; the walk sweeps it open
            return start, pull_passage_waypoints(door, self._stand_pose(door), self.parameters["beyond_door"]), \
                World(wall_obstacles(door))
        angle = max(request.door_angle, self.parameters["passage_door_angle"])
        if self.passage_angle is not None and replan_needed(self.passage_angle, angle):
            self.get_logger().info(f"door angle changed {self.passage_angle:.2f} → {angle:.2f} rad: re-planning")
        self.passage_angle = angle
        door = door.with_angle(angle)
        return start, (through_door_pose(door, self.parameters["beyond_door"]),), World.from_door(door)

    def _stand_pose(self, door: DoorGeometry) -> Pose2D:
        reach = self.parameters["stand_reach_pull" if door.opening is DoorOpening.PULL else "stand_reach"]
        return stand_pose_for_opening(door, self.options, reach=reach,
                                      handle_offset=self.parameters["stand_handle_offset"],
                                      sweep_half_depth=self.parameters["pull_sweep_half_depth"],
                                      pull_sweep_angle=self.parameters["pull_sweep_angle"],
                                      beyond_latch=self.parameters["pull_stand_beyond_latch"])

    def _start_stance(self, body: Pose2D, snapshot: Snapshot) -> Stance:
        """The feet: measured (/feet) when the robot reports them; else where the last plan
        left them if the base stands at that stance's midpoint (the plan was walked); else
        the nominal stance around the base."""
        feet = snapshot.feet
        if feet is not None:
            left, right = feet
            return Stance(Footstep(left.x, left.y, left.yaw, Foot.LEFT), Footstep(right.x, right.y, right.yaw, Foot.RIGHT))
        planned = snapshot.planned_stance
        if planned is not None:
            middle = planned.body_pose
            if math.hypot(middle.x - body.x, middle.y - body.y) < 0.03 and \
                    abs(math.remainder(middle.yaw - body.yaw, math.tau)) < 0.05:
                return planned
        return Stance.nominal(body, self.options.nominal_foot_separation)

    def _door_geometry(self, request: FootstepRequest, estimate: DoorEstimate) -> DoorGeometry:
        return door_geometry_from_estimate(estimate, DoorOpening(request.opening), request.door_angle,
                                           self.parameters["handle_standoff"])

    def _answer(self, request_id: int, goal: str, status: OutcomeStatus, reason: str,
                planning_time: float = 0.0, details: dict | None = None) -> None:
        outcome = PlanningOutcome(request_id, status, reason, planning_time, without_non_finite(details or {}))
        self.outcome_pub.publish(String(data=encode(outcome)))
        line = f"request {request_id} ({goal}): {status.value} in {planning_time * 1000:.1f} ms"
        if status is OutcomeStatus.SUCCESS:  # rclpy forbids one call site logging at two severities
            self.get_logger().info(line)
        else:
            self.get_logger().warning(f"{line}: {reason}")
        self.heartbeat.update(Health.OK if status is OutcomeStatus.SUCCESS else Health.WARN,
                              f"last: {goal} {status.value}", last_planning_ms=round(planning_time * 1000, 2))

    def destroy_node(self) -> None:
        self.desk.close()
        super().destroy_node()


def contract_footsteps(start: Stance, plan: FootstepPlan) -> list[FootPlacement]:
    """The plan in the /footstep_plan convention: even index = left foot (a step in place first
    when the plan starts with the right foot)."""
    steps = list(plan.steps)
    if steps and steps[0].foot is Foot.RIGHT:
        steps.insert(0, start.left)
    return [FootPlacement(ContractFoot.LEFT if s.foot is Foot.LEFT else ContractFoot.RIGHT, s.x, s.y, s.yaw)
            for s in steps]


def footstep_markers(steps: list[FootPlacement], options: FootstepPlannerOptions) -> MarkerArray:
    markers = MarkerArray()
    markers.markers.append(Marker(action=Marker.DELETEALL))
    for index, step in enumerate(steps):
        marker = Marker(type=Marker.CUBE, action=Marker.ADD, id=index, ns="footsteps")
        marker.header.frame_id = Frame.ODOM.value
        marker.pose.position.x, marker.pose.position.y, marker.pose.position.z = step.x, step.y, 0.01
        marker.pose.orientation.z, marker.pose.orientation.w = math.sin(step.yaw / 2), math.cos(step.yaw / 2)
        marker.scale.x, marker.scale.y, marker.scale.z = options.foot_length, options.foot_width, 0.02
        left = step.foot is ContractFoot.LEFT
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = (0.1, 0.4, 1.0, 0.8) if left else (1.0, 0.3, 0.1, 0.8)
        markers.markers.append(marker)
    return markers


def main(args: list[str] | None = None) -> int:
    return run_node(FootstepPlannerNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
