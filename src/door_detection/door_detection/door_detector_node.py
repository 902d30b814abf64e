"""ROS 2 node ``/door_detector``: door and handle estimates from the head RGB-D camera."""

from __future__ import annotations

from rclpy.node import Node

from door_contract.node_support import Heartbeat, declare_parameters, run_node
from door_detection.parameters import DETECTOR_PARAMETERS, NODE_NAME


class DoorDetectorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        self.parameters = declare_parameters(self, DETECTOR_PARAMETERS)
        self.heartbeat = Heartbeat(self)
        self.get_logger().info(f"ready; voting over {self.parameters['vote_frames']} frames")


def main(args: list[str] | None = None) -> int:
    return run_node(DoorDetectorNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
