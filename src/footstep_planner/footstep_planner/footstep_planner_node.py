"""ROS 2 node ``/footstep_planner``: A* footsteps to the stand pose and through the door.

A :class:`~door_contract.payloads.FootstepRequest` ("stand" or "through") is planned from
the robot's odometry and the last door estimate; the plan goes out on
``/footstep_planner/plan`` (even index = left foot) with markers, then a PlanningOutcome
with the plan's stamp. Bad or missing inputs and unreachable goals end in a failure
outcome with the planner's reason, within its deterministic expansion budget; the request's
``attempt`` (a repeat) makes the search differ from its predecessor. Every request whose id
can be read gets exactly one outcome; planning runs on a worker thread, the newest request
(or a cancel on ``/footstep_planner/cancel``) supersedes an older one
(:mod:`door_contract.planner_service`). What is planned and answered for a request is
:mod:`footstep_planner.walk_service` (the problem itself: :mod:`footstep_planner.requests`).
"""

from __future__ import annotations

from collections.abc import Callable

from rclpy.node import Node
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import footsteps_to_path
from door_contract.converters.markers import shapes_to_marker_array
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    declare_parameters,
    node_main,
)
from door_contract.payloads import DoorEstimate, FootstepRequest, OutcomeStatus, encode
from door_contract.planner_desk import PlannerDesk
from door_contract.planner_inputs import PlannerInputs
from door_contract.planner_service import Finished
from door_contract.stamps import time_msg_of_ns
from door_contract.topics import Topics
from door_robot.errors import RobotModelError
from door_robot.profile import STANCE_FIELDS
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.parameters import NODE_NAME, PLANNER_PARAMETERS
from footstep_planner.requests import GoalSettings, Snapshot, planner_options
from footstep_planner.walk_service import Answer, Solved, WalkService

__all__ = ["FootstepPlannerNode", "main"]


class FootstepPlannerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, PLANNER_PARAMETERS)
        with as_parameter_error("footstep planner options", FootstepPlannerError, RobotModelError):
            options = planner_options(p["robot_profile"], p)
            settings = GoalSettings.for_robot(p["robot_profile"], p)
        for name in sorted(STANCE_FIELDS):
            if getattr(settings, name) != p[name]:
                self.get_logger().info(f"{name} {getattr(settings, name):.2f} m from the {p['robot_profile']} profile's "
                                       f"stance (parameter: {p[name]:.2f} m, TALOS's)")
        self.service = WalkService(options, settings)
        self.heartbeat = Heartbeat(self)
        self.inputs = PlannerInputs(self, self.heartbeat)
        self.plan_pub = create_contract_publisher(self, Topics.FOOTSTEP_PROPOSAL)
        self.outcome_pub = create_contract_publisher(self, Topics.FOOTSTEP_OUTCOME)
        self.marker_pub = create_contract_publisher(self, Topics.FOOTSTEP_MARKERS)
        self.desk = PlannerDesk(self, self.heartbeat, FootstepRequest, (Topics.FOOTSTEP_REQUEST, Topics.FOOTSTEP_CANCEL),
                                lambda r: self.inputs.doors.pick(r.door_stamp, r.door), self._job_for,
                                self._deliver_one,
                                lambda rid, why: self._answer(rid, "?", Answer(OutcomeStatus.REJECTED, why)))
        self.get_logger().info(f"ready: {p['robot_profile']} steps ≤ {options.max_stride} m, "
                               f"heuristic weight {options.heuristic_weight}")

    def _job_for(self, request: FootstepRequest, estimate: DoorEstimate | None) -> Callable[[], Solved]:
        """The planning job of ``request`` over the inputs as they are now (the measured state)."""
        snapshot = self.service.snapshot(self.inputs.base_pose, self.inputs.feet, estimate)
        return lambda: self._solve(request, snapshot)

    def _solve(self, request: FootstepRequest, snapshot: Snapshot) -> Solved:
        """On the worker thread."""
        solved = self.service.solve(request, snapshot)
        if solved.angle_change is not None:
            self.get_logger().info("door angle changed {:.2f} → {:.2f} rad: re-planning".format(*solved.angle_change))
        if solved.relaxed_from:
            self.get_logger().warning(f"{solved.relaxed_from}: planned once more without safety margins")
        return solved

    def _deliver_one(self, finished: Finished) -> None:
        """On the executor thread: one outcome per finished request, and the plan if proposed."""
        request = finished.request
        answer = self.service.answer(finished, self.get_clock().now().nanoseconds)
        if answer.bug:  # a failure outcome, not a dead node
            self.get_logger().error(f"request {request.request_id} crashed the planner: {answer.bug}")
        if answer.footsteps:
            path = footsteps_to_path(list(answer.footsteps))
            path.header.stamp = time_msg_of_ns(answer.stamp_ns)
            self.plan_pub.publish(path)
            self.marker_pub.publish(shapes_to_marker_array(list(answer.shapes)))
        self._answer(request.request_id, request.goal, answer)

    def _answer(self, request_id: int, goal: str, answer: Answer) -> None:
        self.outcome_pub.publish(String(data=encode(answer.outcome(request_id))))
        status, milliseconds = answer.status, answer.planning_time_s * 1000
        line = f"request {request_id} ({goal}): {status.value} in {milliseconds:.1f} ms"
        answered = status in (OutcomeStatus.SUCCESS, OutcomeStatus.SKIPPED)  # a skip is no walk, not a fault
        if status is OutcomeStatus.SUCCESS:  # rclpy forbids one call site logging at two severities
            self.get_logger().info(line)
        elif answered:
            self.get_logger().info(f"{line}: {answer.reason}")
        else:
            self.get_logger().warning(f"{line}: {answer.reason}")
        self.heartbeat.update(Health.OK if answered else Health.WARN,
                              f"last: {goal} {status.value}", last_planning_ms=round(milliseconds, 2))

    def destroy_node(self) -> None:
        self.desk.close()
        super().destroy_node()


main = node_main(FootstepPlannerNode, __name__)
