"""``bag_record``: record topics into a rosbag2 bag (like ``ros2 bag record``).

    bag_record OUTPUT [--storage sqlite3|mcap] [--compression none|zstd] [--topics /a /b]
                                                                   (default: every topic)

Subscribes with raw (serialized) callbacks, so messages are stored byte-identical; new
topics are picked up while recording as soon as a publisher offers them (as ``ros2 bag record``
does), each with the QoS its publishers offer (stored in the bag, so a player restores
transient-local topics; :mod:`door_bringup.bags.qos`). Its heartbeat on ``/diagnostics`` names,
for every latched topic, a digest of the last message it wrote (:func:`recorded_key`,
:func:`message_digest`), so whoever stops it can first wait until a latched message (the FSM's
terminal state) is in the bag. Ctrl-C / SIGTERM writes what is still queued (:data:`DRAIN_S`) and
closes the bag cleanly. An output that exists or cannot be created ends with one line and exit code 7
(:mod:`door_bringup.bags.exit_codes`); ``--compression zstd`` without ``--storage mcap`` is a
usage error (2).
"""

from __future__ import annotations

import argparse
import sys
import zlib
from collections.abc import Callable
from pathlib import Path

from rclpy.node import Node
from rclpy.qos import DurabilityPolicy
from rclpy.serialization import deserialize_message, serialize_message
from rclpy.subscription import Subscription

from door_bringup.bags.exit_codes import exit_code_for
from door_bringup.bags.player import qos_for
from door_bringup.bags.qos import offered_qos
from door_bringup.bags.storage import BagError, BagWriter, Compression, StorageFormat
from door_contract.converters.diagnostics import Health
from door_contract.node_support import Heartbeat, run_node
from door_contract.qos import matching_subscription
from door_contract.topics import interface_class

__all__ = ["BagRecorder", "main", "message_digest", "recorded_key"]

DRAIN_S = 2.0
"""s the recorder goes on writing what is queued after Ctrl-C / SIGTERM: it is stopped right after
the graph, whose last messages (a fall's outcome, the FAILED state) were still queued and lost."""


def recorded_key(topic: str) -> str:
    """The recorder's heartbeat key for the digest of the last message written on ``topic``."""
    return f"recorded {topic}"


def message_digest(message: object) -> str:
    """CRC-32 of ``message`` serialized by rclpy, as the recorder's heartbeat reports it. The
    recorder deserializes what it received first: the publisher's CDR padding bytes are not
    rclpy's, so the received bytes of an equal message need not be equal."""
    return f"{zlib.crc32(serialize_message(message)):08x}"


class BagRecorder(Node):
    def __init__(self, writer: BagWriter, output: Path, storage: StorageFormat,
                 topics: tuple[str, ...] | None) -> None:
        super().__init__("bag_recorder")
        self.writer = writer
        self.wanted = set(topics) if topics else None
        self.subscriptions_by_topic: dict[str, Subscription] = {}
        self.latched_topics: set[str] = set()
        self.count = 0
        self.heartbeat = Heartbeat(self, period_s=0.5)
        self.discover()
        self.create_timer(0.2, self.discover)
        self.get_logger().info(f"recording to {output} ({storage.value})")

    def discover(self) -> None:
        for topic, types in self.get_topic_names_and_types():
            if topic in self.subscriptions_by_topic or (self.wanted and topic not in self.wanted):
                continue
            try:
                msg_type = interface_class(types[0])
            except (ImportError, AttributeError, ValueError):
                continue
            offered = [info.qos_profile for info in self.get_publishers_info_by_topic(topic)]
            if not offered:
                continue  # known only from a subscriber so far: recorded once a publisher offers its QoS
            self.writer.add_topic(topic, types[0], [offered_qos(profile) for profile in offered])
            if all(profile.durability == DurabilityPolicy.TRANSIENT_LOCAL for profile in offered):
                self.latched_topics.add(topic)
            self.subscriptions_by_topic[topic] = self.create_subscription(
                msg_type, topic, self._writer_for(topic, types[0], msg_type), matching_subscription(offered, qos_for(topic)),
                raw=True)

    def _writer_for(self, topic: str, type_name: str, msg_type: type) -> Callable[[bytes], None]:
        def write(data: bytes) -> None:
            self.writer.write(topic, type_name, self.get_clock().now().nanoseconds, data)
            self.count += 1
            latest = ({recorded_key(topic): message_digest(deserialize_message(data, msg_type))}
                      if topic in self.latched_topics else {})
            self.heartbeat.update(Health.OK, "recording", recorded=self.count, **latest)
        return write

    def destroy_node(self) -> None:
        self.writer.close()
        self.get_logger().info(f"recorded {self.count} messages")
        super().destroy_node()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Record topics to a rosbag2 bag.")
    parser.add_argument("output", type=Path)
    parser.add_argument("--storage", choices=[s.value for s in StorageFormat], default="sqlite3")
    parser.add_argument("--compression", choices=[c.value for c in Compression], default="none",
                        help="zstd: compressed mcap chunks (mcap only)")
    parser.add_argument("--topics", nargs="+", default=None)
    args, ros_args = parser.parse_known_args(argv)
    if args.compression != "none" and args.storage != "mcap":
        parser.error("--compression zstd needs --storage mcap")
    try:  # created before the node, so a bad output is one line and exit code 7, not a traceback
        writer = BagWriter(args.output, StorageFormat(args.storage), Compression(args.compression))
    except BagError as error:
        print(f"bag_record: {error}", file=sys.stderr)
        return exit_code_for(error)
    return run_node(lambda: BagRecorder(writer, args.output, StorageFormat(args.storage),
                                        tuple(args.topics) if args.topics else None), ros_args, drain_s=DRAIN_S)


if __name__ == "__main__":
    sys.exit(main())
