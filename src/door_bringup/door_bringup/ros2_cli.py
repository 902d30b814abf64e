"""A small stand-in for ros2cli, which is not on PyPI: ``./ros2 run|topic|bag|launch``.

    ./ros2 run <package> <executable> [--ros-args ...]     what `ros2 run` starts
    ./ros2 topic pub [--times N] <topic> <type> '<yaml>'  e.g. /door_task/operator std_msgs/msg/String "{data: approve}"
    ./ros2 topic echo [--count N] <topic>
    ./ros2 bag play <bag> [...] / ./ros2 bag record <output> [...]
    ./ros2 launch                                          start the whole graph (door_bringup.door_task)

On a real ROS 2 install use the real ``ros2``; the executables and topics are the same.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any

import yaml

from door_bringup.workspace import Workspace, WorkspaceError, repository_root

__all__ = ["main"]


def set_fields(message: Any, values: dict) -> Any:
    """Fill a ROS message from a nested dict (what ``ros2 topic pub`` takes as YAML)."""
    for name, value in (values or {}).items():
        if not hasattr(message, name):
            raise ValueError(f"{type(message).__name__} has no field {name!r}")
        current = getattr(message, name)
        if isinstance(value, dict):
            set_fields(current, value)
        else:
            setattr(message, name, value)
    return message


def _exec(workspace: Workspace, package: str, executable: str, args: list[str]) -> int:
    path = workspace.executable(package, executable)
    os.execve(str(path), [str(path), *args], workspace.environment())
    return 0  # not reached


def _topic(args: list[str]) -> int:
    import rclpy

    from door_bringup.bags.player import qos_for
    from door_contract.network import keep_discovery_local
    from door_contract.topics import interface_class

    verb, rest = args[0], args[1:]
    count = 1
    if rest and rest[0] in ("--times", "--count"):
        count, rest = int(rest[1]), rest[2:]
    keep_discovery_local()
    rclpy.init()
    node = rclpy.create_node("ros2cli_stand_in")
    try:
        if verb == "pub":
            topic, type_name = rest[0], rest[1]
            msg_class = interface_class(type_name)
            publisher = node.create_publisher(msg_class, topic, qos_for(topic))
            message = set_fields(msg_class(), yaml.safe_load(rest[2]) if len(rest) > 2 else {})
            deadline = time.monotonic() + 5.0
            while publisher.get_subscription_count() == 0 and time.monotonic() < deadline:
                rclpy.spin_once(node, timeout_sec=0.05)  # give discovery a chance, bounded
            for _ in range(count):
                publisher.publish(message)
                print(f"publishing #{_ + 1}: {message}")
                rclpy.spin_once(node, timeout_sec=0.1)
        elif verb == "echo":
            topic = rest[0]
            names = dict(node.get_topic_names_and_types())
            deadline = time.monotonic() + 5.0
            while topic not in names and time.monotonic() < deadline:
                rclpy.spin_once(node, timeout_sec=0.1)
                names = dict(node.get_topic_names_and_types())
            if topic not in names:
                print(f"topic {topic} not found", file=sys.stderr)
                return 1
            received: list[object] = []

            def echo(message: object) -> None:
                received.append(message)
                print(message, "\n---", flush=True)
            node.create_subscription(interface_class(names[topic][0]), topic, echo, qos_for(topic))
            while len(received) < count:
                rclpy.spin_once(node, timeout_sec=0.1)
        else:
            print(f"unknown topic verb {verb!r}: use pub or echo", file=sys.stderr)
            return 2
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    workspace = Workspace(repository_root())
    os.environ.update({k: v for k, v in workspace.environment().items() if k not in os.environ})
    try:
        if len(argv) >= 3 and argv[0] == "run":
            return _exec(workspace, argv[1], argv[2], argv[3:])
        if len(argv) >= 2 and argv[0] == "bag" and argv[1] in ("play", "record"):
            return _exec(workspace, "door_bringup", f"bag_{argv[1]}", argv[2:])
        if argv and argv[0] == "launch":
            return _exec(workspace, "door_bringup", "door_task", argv[1:])
        if len(argv) >= 3 and argv[0] == "topic":
            return _topic(argv[1:])
    except WorkspaceError as error:
        print(error, file=sys.stderr)
        return 1
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
