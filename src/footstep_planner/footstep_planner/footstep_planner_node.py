"""ROS 2 node ``/footstep_planner``: A* footsteps to the stand pose and through the door."""

from __future__ import annotations

from rclpy.node import Node

from door_contract.node_support import Heartbeat, declare_parameters, run_node
from footstep_planner.parameters import NODE_NAME, PLANNER_PARAMETERS


class FootstepPlannerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, PLANNER_PARAMETERS)
        self.heartbeat = Heartbeat(self)
        self.get_logger().info(f"ready; heuristic weight {self.parameters['heuristic_weight']}")


def main(args: list[str] | None = None) -> int:
    return run_node(FootstepPlannerNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
