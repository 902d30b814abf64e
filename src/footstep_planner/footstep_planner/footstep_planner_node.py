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
legs) is built by :mod:`footstep_planner.requests`, what is proposed from a plan (footsteps,
markers, summary) by :mod:`footstep_planner.proposal`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from rclpy.node import Node
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import footsteps_to_path
from door_contract.converters.markers import shapes_to_marker_array
from door_contract.errors import ContractError
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
from door_contract.vocabulary import DoorOpening, WalkGoal
from door_robot.errors import RobotModelError
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Stance
from footstep_planner.goals import replan_needed
from footstep_planner.parameters import NODE_NAME, PLANNER_PARAMETERS
from footstep_planner.plan import PlanResult
from footstep_planner.proposal import contract_footsteps, footstep_shapes, walked_length
from footstep_planner.requests import (
    GoalSettings,
    Snapshot,
    WalkPlanners,
    WalkProblem,
    options_for_problem,
    passage_angle,
    planner_options,
    problem_for_request,
)

__all__ = ["FootstepPlannerNode", "main"]


BAD_INPUT = (FootstepPlannerError, ContractError)
"""What a request's planning raises for bad input (answered REJECTED, e.g. ``RequestRefused``);
anything else is a bug."""


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
        self.planners = WalkPlanners()  # tables built once per options
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
        problem = problem_for_request(request, snapshot, self.options, self.settings)
        if request.goal is WalkGoal.THROUGH and request.opening is DoorOpening.PUSH:
            angle = passage_angle(request.door_angle, self.settings)
            if self.passage_angle is not None and replan_needed(self.passage_angle, angle):
                self.get_logger().info(f"door angle changed {self.passage_angle:.2f} → {angle:.2f} rad: re-planning")
            self.passage_angle = angle
        options = options_for_problem(problem, request.goal, self.options)
        result, relaxed_from = self.planners.plan(problem, options, request.attempt)
        if relaxed_from:
            self.get_logger().warning(f"{relaxed_from}: planned once more without safety margins")
        return Solved(problem, result)

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
        self.marker_pub.publish(shapes_to_marker_array(footstep_shapes(placements, self.options.foot_length,
                                                                       self.options.foot_width)))
        length = walked_length(start, problem.legs[-1].goal)
        self._answer(request.request_id, request.goal, OutcomeStatus.SUCCESS, "", result.planning_time,
                     {"stamp_ns": stamp_ns(path.header.stamp), "steps": len(result.plan.steps), "length_m": round(length, 3),
                      "expansions": result.expansions})

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


main = node_main(FootstepPlannerNode, __name__)
