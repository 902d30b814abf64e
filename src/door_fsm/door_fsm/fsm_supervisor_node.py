"""ROS 2 node ``/fsm_supervisor``: the door task's state machine (seed 001 Fig. 3)."""

from __future__ import annotations

from rclpy.node import Node

from door_contract.node_support import Heartbeat, declare_parameters, run_node
from door_fsm.parameters import NODE_NAME, SUPERVISOR_PARAMETERS


class FsmSupervisorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, SUPERVISOR_PARAMETERS)
        self.heartbeat = Heartbeat(self)
        self.get_logger().info(f"ready; autonomy {self.parameters['autonomy']}")


def main(args: list[str] | None = None) -> int:
    return run_node(FsmSupervisorNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
