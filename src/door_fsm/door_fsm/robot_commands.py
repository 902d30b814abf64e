"""What the supervisor node sends the robot, stamped: executions, the head search's looks, stops.

ROS glue of ``/fsm_supervisor`` (it publishes), kept apart from the node's wiring. Every command
carries a unique stamp from the node's clock (sim time under ``use_sim_time``): the sim bridge
answers an execution with an ExecutionOutcome whose request id is that stamp. A stop is
ros2_control's: an empty trajectory holds the arm, an empty footstep path ends the walk
(:mod:`door_contract.converters.stop`).
"""

from __future__ import annotations

from nav_msgs.msg import Path
from rclpy.node import Node
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.stop import stop_messages
from door_contract.node_support import create_contract_publisher
from door_contract.stamps import UniqueStamps, time_msg_of_ns
from door_contract.topics import Topics

__all__ = ["RobotCommands"]


class RobotCommands:
    """Publishers of ``/arm_controller/joint_trajectory`` and ``/footstep_plan``, and their stamps."""

    def __init__(self, node: Node) -> None:
        self._node, self._stamps = node, UniqueStamps()
        self._arm = create_contract_publisher(node, Topics.ARM_TRAJECTORY)
        self._feet = create_contract_publisher(node, Topics.FOOTSTEP_PLAN)

    def next_stamp(self) -> int:
        """A stamp (ns, node clock) no earlier command had."""
        return self._stamps.next(self._node.get_clock().now().nanoseconds)

    def send(self, command: Path | JointTrajectory, stamp: int | None = None) -> int:
        """Publish ``command`` stamped ``stamp`` (default: the next); returns the stamp."""
        stamp = self.next_stamp() if stamp is None else stamp
        command.header.stamp = time_msg_of_ns(stamp)
        (self._feet if isinstance(command, Path) else self._arm).publish(command)
        return stamp

    def hold_arm(self) -> None:
        """Stop the running joint trajectory (a look, an arm motion): the joints hold."""
        self._arm.publish(stop_messages(time_msg_of_ns(self.next_stamp()))[0])

    def stop(self) -> None:
        """Stop every execution now (the empty pair)."""
        trajectory, path = stop_messages(time_msg_of_ns(self.next_stamp()))
        self._arm.publish(trajectory)
        self._feet.publish(path)
