"""ROS 2 node ``/trajectory_optimizer``: door motions as optimised joint trajectories."""

from __future__ import annotations

from rclpy.node import Node

from door_contract.node_support import Heartbeat, declare_parameters, run_node
from door_trajopt.parameters import NODE_NAME, OPTIMIZER_PARAMETERS


class TrajectoryOptimizerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, OPTIMIZER_PARAMETERS)
        self.heartbeat = Heartbeat(self)
        self.get_logger().info(f"ready; backend {self.parameters['backend']}")


def main(args: list[str] | None = None) -> int:
    return run_node(TrajectoryOptimizerNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
