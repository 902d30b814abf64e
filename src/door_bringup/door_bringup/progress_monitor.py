"""Feeds the main job's progress line from the bus (node-side glue over :mod:`door_bringup.progress`).

It follows no 50–100 Hz stream of its own (rclpy's executor costs a fraction of a millisecond
per message, which the graph's CPU budget feels): the base position and the sim time come from
the /odom messages the operator already receives (:meth:`ProgressMonitor.odom`, the header
stamp is sim time), the state from /door_task/state, and the door angle from the FSM's planning
requests (the angle it plans with, updated at each request).
"""

from __future__ import annotations

import json
import sys
import time
from typing import Any

from nav_msgs.msg import Odometry
from rclpy.node import Node
from std_msgs.msg import String

from door_bringup.progress import ProgressPrinter, TaskProgress
from door_contract.errors import ContractError
from door_contract.node_support import create_contract_subscription
from door_contract.stamps import from_time_msg
from door_contract.topics import Topics
from door_contract.vocabulary import TaskState

__all__ = ["ProgressMonitor"]


class ProgressMonitor:
    def __init__(self, node: Node, period_s: float = 0.5) -> None:
        self.progress = TaskProgress()
        self.printer = ProgressPrinter(lambda text: (sys.stdout.write(text), sys.stdout.flush()), sys.stdout.isatty())
        self._started, self._period, self._next = time.monotonic(), period_s, 0.0
        create_contract_subscription(node, Topics.TASK_STATE, self._on_state)
        for topic in (Topics.FOOTSTEP_REQUEST, Topics.MOTION_REQUEST):
            create_contract_subscription(node, topic, self._on_request)

    def _set(self, **changes: Any) -> None:
        self.progress = self.progress.update(**changes)

    def _on_state(self, msg: String) -> None:
        try:
            self._set(state=TaskState.of_label(msg.data))
        except ContractError:
            return  # no state's label: the line keeps the last one (it shows, it does not judge)

    def _on_request(self, msg: String) -> None:
        try:
            angle = json.loads(msg.data).get("door_angle")
        except (ValueError, AttributeError, RecursionError):
            return  # the FSM's own messages; a broken one only leaves the line as it was
        if isinstance(angle, (int, float)):
            self._set(door_angle=float(angle))

    def odom(self, msg: Odometry) -> None:
        """The base position and the sim time (the message's stamp), from the operator's /odom."""
        self._set(sim_s=from_time_msg(msg.header.stamp),
                  base_xy=(msg.pose.pose.position.x, msg.pose.pose.position.y))

    def tick(self) -> None:
        """Show the line (call from the spin loop; shown every ``period_s``)."""
        now = time.monotonic() - self._started
        if now >= self._next:
            self._next = now + self._period
            self.printer.show(self.progress.update(wall_s=now))

    def say(self, text: str) -> None:
        """Print a line of its own (the in-place progress line is cleared first)."""
        self.printer.interrupt()
        print(text, flush=True)
