"""ROS 2 node ``/sim_bridge``: the PyBullet world standing in for the robot."""

from __future__ import annotations

from rclpy.node import Node

from door_contract.node_support import Heartbeat, declare_parameters, run_node
from door_sim_bridge.parameters import BRIDGE_PARAMETERS, NODE_NAME


class SimBridgeNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, BRIDGE_PARAMETERS)
        self.heartbeat = Heartbeat(self)
        self.get_logger().info(f"ready; robot {self.parameters['robot_profile']}, "
                               f"{self.parameters['physics_rate']:.0f} Hz physics")


def main(args: list[str] | None = None) -> int:
    return run_node(SimBridgeNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
