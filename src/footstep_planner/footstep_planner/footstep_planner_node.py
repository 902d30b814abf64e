"""ROS 2 node ``/footstep_planner``: A* footsteps to the stand pose and through the door.

A :class:`~door_contract.payloads.FootstepRequest` ("stand" or "through") is planned from
the robot's odometry and the last door estimate; the plan goes out on
``/footstep_planner/plan`` (even index = left foot) with markers, then a PlanningOutcome
with the plan's stamp. Bad or missing inputs and unreachable goals end in a failure
outcome with the planner's reason, within its deterministic expansion budget; the request's
``attempt`` (a repeat) makes the search differ from its predecessor. Every request whose id
can be read gets exactly one outcome; planning runs on a worker thread, the newest request
(or a cancel on ``/footstep_planner/cancel``) supersedes an older one
(:mod:`door_contract.planner_service`). The problem itself (options, door, start stance,
legs) is built by :mod:`footstep_planner.requests`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from rclpy.node import Node
from std_msgs.msg import String
from visualization_msgs.msg import Marker, MarkerArray

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import FootPlacement, footsteps_to_path
from door_contract.door_estimates import door_estimate_problem
from door_contract.errors import ContractError
from door_contract.frames import Frame
from door_contract.geometry import yaw_of
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    declare_parameters,
    node_main,
)
from door_contract.payloads import (
    DoorEstimate,
    FootstepRequest,
    OutcomeStatus,
    PlanningOutcome,
    encode,
    without_non_finite,
)
from door_contract.planner_desk import PlannerDesk
from door_contract.planner_inputs import PlannerInputs
from door_contract.planner_service import Finished
from door_contract.stamps import UniqueStamps, stamp_ns, time_msg_of_ns
from door_contract.topics import Topics
from door_contract.vocabulary import DoorOpening, Foot, WalkGoal
from door_robot.errors import RobotModelError
from footstep_planner.astar import FootstepPlanner
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import replan_needed
from footstep_planner.legs import plan_legs
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.parameters import NODE_NAME, PLANNER_PARAMETERS
from footstep_planner.plan import FootstepPlan, PlanResult
from footstep_planner.requests import (
    GoalSettings,
    WalkProblem,
    door_geometry_from_estimate,
    options_for_problem,
    passage_angle,
    planner_options,
    start_stance,
    walk_problem,
)

__all__ = ["FootstepPlannerNode", "door_geometry_from_estimate", "planner_options", "main"]


class RequestRefused(Exception):
    """A request the node cannot plan from its inputs (no odometry, no usable door estimate)."""


BAD_INPUT = (RequestRefused, FootstepPlannerError, ContractError)
"""What a request's planning raises for bad input (answered REJECTED); anything else is a bug."""


@dataclass(frozen=True)
class Snapshot:
    """The inputs a request is planned from, taken when it arrives (the measured state)."""

    base_pose: np.ndarray | None
    feet: list[FootPlacement] | None
    estimate: DoorEstimate | None
    planned_stance: Stance | None


@dataclass(frozen=True)
class Solved:
    problem: WalkProblem
    result: PlanResult


class FootstepPlannerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, PLANNER_PARAMETERS)
        with as_parameter_error("footstep planner options", FootstepPlannerError, RobotModelError):
            self.options = planner_options(self.parameters["robot_profile"], self.parameters)
        self.settings = GoalSettings.from_parameters(self.parameters)
        self.planners: dict[FootstepPlannerOptions, FootstepPlanner] = {}  # tables built once per options
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

    def _job_for(self, request: FootstepRequest, estimate: DoorEstimate | None) -> Callable[[], Solved]:
        """The planning job of ``request`` over the inputs as they are now (the measured state)."""
        snapshot = Snapshot(None if self.inputs.base_pose is None else self.inputs.base_pose.copy(),
                            self.inputs.feet, estimate, self.planned_stance)
        return lambda: self._solve(request, snapshot)

    def _solve(self, request: FootstepRequest, snapshot: Snapshot) -> Solved:
        """On the worker thread: the problem from the snapshot, then the search."""
        problem, goal = self._problem(request, snapshot)
        options = options_for_problem(problem, goal, self.options)
        return Solved(problem, self._plan(problem, options, request.attempt))

    def _deliver_one(self, finished: Finished) -> None:
        """On the executor thread: one outcome per finished request, and the plan if proposed."""
        request = finished.request
        settled = finished.answer_without_result(BAD_INPUT)
        if settled is not None:
            if settled[0] is OutcomeStatus.FAILURE:  # a bug: a failure outcome, not a dead node
                self.get_logger().error(f"request {request.request_id} crashed the planner: {finished.error!r}")
            self._answer(request.request_id, request.goal, *settled)
            return
        problem, result = finished.result.problem, finished.result.result
        start = problem.start
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
        goal = problem.legs[-1].goal
        length = float(np.hypot(goal.x - start.left.x / 2 - start.right.x / 2, goal.y - start.left.y / 2 - start.right.y / 2))
        self._answer(request.request_id, request.goal, OutcomeStatus.SUCCESS, "", result.planning_time,
                     {"stamp_ns": stamp_ns(path.header.stamp), "steps": len(result.plan.steps), "length_m": round(length, 3),
                      "expansions": result.expansions})

    def _plan(self, problem: WalkProblem, options: FootstepPlannerOptions, attempt: int) -> PlanResult:
        if options not in self.planners:
            self.planners[options] = FootstepPlanner(problem.world, options)
        planner = self.planners[options].with_world(problem.world)
        if len(problem.legs) > 1:
            return plan_legs(planner, problem.start, problem.legs, attempt)
        result, relaxed_from = planner.plan_from_within_margins(problem.start, problem.legs[0].goal, attempt)
        if relaxed_from:
            self.get_logger().warning(f"{relaxed_from}: planned once more without safety margins")
        return result

    def _problem(self, request: FootstepRequest, snapshot: Snapshot) -> tuple[WalkProblem, WalkGoal]:
        """Start stance, the legs to walk in order, and the obstacles, from the snapshot."""
        if snapshot.base_pose is None:
            raise RequestRefused("no valid odometry yet")
        estimate = snapshot.estimate
        if estimate is None:
            raise RequestRefused("no door estimate yet" if request.door_stamp < 0 else
                                 f"door estimate of stamp {request.door_stamp:.3f} s was not received")
        if door_estimate_problem(estimate):
            raise RequestRefused(door_estimate_problem(estimate))
        goal = request.goal  # the contract decoded goal and opening: unknown words were refused there
        pose = snapshot.base_pose
        body = Pose2D(float(pose[0, 3]), float(pose[1, 3]), yaw_of(pose))
        feet = None if snapshot.feet is None else _sole_poses(snapshot.feet)
        start = start_stance(body, self.options.nominal_foot_separation, feet, snapshot.planned_stance)
        door = door_geometry_from_estimate(estimate, request.opening, request.door_angle,
                                           self.settings.handle_standoff)
        if goal is WalkGoal.THROUGH and door.opening is DoorOpening.PUSH:
            angle = passage_angle(request.door_angle, self.settings)
            if self.passage_angle is not None and replan_needed(self.passage_angle, angle):
                self.get_logger().info(f"door angle changed {self.passage_angle:.2f} → {angle:.2f} rad: re-planning")
            self.passage_angle = angle
        return walk_problem(goal, door, start, self.options, self.settings), goal

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


def _sole_poses(feet: list[FootPlacement]) -> tuple[Pose2D, Pose2D]:
    """The measured (left, right) sole poses."""
    left, right = (Pose2D(f.x, f.y, f.yaw) for f in feet)
    return left, right


def contract_footsteps(start: Stance, plan: FootstepPlan) -> list[FootPlacement]:
    """The plan in the /footstep_plan convention: even index = left foot (a step in place first
    when the plan starts with the right foot)."""
    steps = list(plan.steps)
    if steps and steps[0].foot is Foot.RIGHT:
        steps.insert(0, start.left)
    return [FootPlacement(s.foot, s.x, s.y, s.yaw) for s in steps]


def footstep_markers(steps: list[FootPlacement], options: FootstepPlannerOptions) -> MarkerArray:
    markers = MarkerArray()
    markers.markers.append(Marker(action=Marker.DELETEALL))
    for index, step in enumerate(steps):
        marker = Marker(type=Marker.CUBE, action=Marker.ADD, id=index, ns="footsteps")
        marker.header.frame_id = Frame.ODOM.value
        marker.pose.position.x, marker.pose.position.y, marker.pose.position.z = step.x, step.y, 0.01
        marker.pose.orientation.z, marker.pose.orientation.w = math.sin(step.yaw / 2), math.cos(step.yaw / 2)
        marker.scale.x, marker.scale.y, marker.scale.z = options.foot_length, options.foot_width, 0.02
        left = step.foot is Foot.LEFT
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = (0.1, 0.4, 1.0, 0.8) if left else (1.0, 0.3, 0.1, 0.8)
        markers.markers.append(marker)
    return markers


main = node_main(FootstepPlannerNode, __name__)
