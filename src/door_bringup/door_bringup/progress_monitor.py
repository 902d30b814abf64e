"""Feeds the main job's progress line from the bus (node-side glue over :mod:`door_bringup.progress`):
/clock, /door_task/state, /odom and the simulated hinge on /sim/door_joint_states."""

from __future__ import annotations

import sys
import time

from rclpy.node import Node

from door_bringup.progress import ProgressPrinter, TaskProgress
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.errors import ContractError
from door_contract.node_support import create_contract_subscription
from door_contract.stamps import from_time_msg
from door_contract.topics import Topics
from door_sim_bridge.world.door import HINGE_JOINT


class ProgressMonitor:
    def __init__(self, node: Node, period_s: float = 0.5) -> None:
        self.progress = TaskProgress()
        self.printer = ProgressPrinter(lambda text: (sys.stdout.write(text), sys.stdout.flush()), sys.stdout.isatty())
        self._started, self._period, self._next = time.monotonic(), period_s, 0.0
        sub = lambda topic, callback: create_contract_subscription(node, topic, callback)
        sub(Topics.CLOCK, lambda m: self._set(sim_s=from_time_msg(m.clock)))
        sub(Topics.TASK_STATE, lambda m: self._set(state=m.data))
        sub(Topics.ODOM, lambda m: self._set(base_xy=(m.pose.pose.position.x, m.pose.pose.position.y)))
        sub(Topics.DOOR_JOINT_STATES, self._on_door)

    def _set(self, **changes) -> None:
        self.progress = self.progress.update(**changes)

    def _on_door(self, msg) -> None:
        try:
            self._set(door_angle=joint_state_to_positions(msg).get(HINGE_JOINT))
        except ContractError:
            pass

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
