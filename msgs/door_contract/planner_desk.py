"""The request desk both planner nodes share (rclpy glue over :mod:`door_contract.planner_service`).

It receives requests on the planner's request topic, refuses the ones it can refuse at once
(invalid, a door angle out of range, a door that does not decode) under their id, hands
the rest with a snapshot of the node's inputs to the :class:`PlanningWorker`, serves
cancels, and calls the node back on its executor thread for every finished request.
Text without a readable id is logged and counted (``unanswerable`` on /diagnostics).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rclpy.node import Node
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.door_estimates import door_angle_problem
from door_contract.errors import ContractError
from door_contract.node_support import Heartbeat, create_contract_subscription
from door_contract.payloads import DoorEstimate, PlanningCancel, decode
from door_contract.planner_service import Finished, PlanningWorker, decode_request
from door_contract.topics import TopicSpec

__all__ = ["PlannerDesk", "Submit"]

Submit = Callable[[Any, DoorEstimate | None], Callable[[], Any]]  # (request, door) → the planning job


class PlannerDesk:
    def __init__(self, node: Node, heartbeat: Heartbeat, payload_type: type, topics: tuple[TopicSpec, TopicSpec],
                 pick_door: Callable[[Any], DoorEstimate | None], job_for: Submit,
                 deliver: Callable[[Finished], None], refuse: Callable[[int, str], None]) -> None:
        """``topics``: (request, cancel). ``job_for(request, door)`` snapshots the node's inputs
        and returns the job; ``deliver`` answers a finished request; ``refuse(id, reason)``
        answers one REJECTED."""
        self._node, self._heartbeat, self._type = node, heartbeat, payload_type
        self._pick_door, self._job_for, self._deliver, self._refuse = pick_door, job_for, deliver, refuse
        self.unanswerable = 0
        self.worker = PlanningWorker(node.create_guard_condition(self._deliver_finished).trigger,
                                     f"{node.get_name()} planning")
        create_contract_subscription(node, topics[0], self._on_request)
        create_contract_subscription(node, topics[1], self._on_cancel)

    def _on_request(self, msg: String) -> None:
        request, request_id, problem = decode_request(self._type, msg.data)
        if request is not None:
            problem = door_angle_problem(request.door_angle) or ""
        if not problem:
            try:
                door = self._pick_door(request)
            except ContractError as error:
                problem = f"door: {error}"
        if problem:
            self.refuse(request_id, problem)
            return
        self.worker.submit(request, self._job_for(request, door))

    def refuse(self, request_id: int | None, problem: str) -> None:
        if request_id is None:  # nothing to answer to: say so, and count it
            self.unanswerable += 1
            self._node.get_logger().warning(f"{self._type.__name__} without a readable id ignored: {problem}")
            self._heartbeat.update(Health.WARN, "unanswerable request", unanswerable=self.unanswerable)
            return
        self._refuse(request_id, problem)

    def _on_cancel(self, msg: String) -> None:
        try:
            cancel = decode(PlanningCancel, msg.data)
        except ContractError as error:
            self._node.get_logger().warning(f"cancel rejected: {error}")
            return
        result = self.worker.cancel(cancel.request_id, cancel.reason)
        self._node.get_logger().info(f"cancel {cancel.request_id}: {result.value}")

    def _deliver_finished(self) -> None:
        for finished in self.worker.take_finished():
            self._deliver(finished)

    def close(self) -> None:
        self.worker.close()

