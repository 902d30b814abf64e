"""``bag_play``: publish a rosbag2 bag's messages with their original timing (like ``ros2 bag play``).

    bag_play BAG [--rate 2.0] [--clock] [--topics /a /b] [--wait-for-subscribers 5]

Messages are published as the serialized CDR bytes stored in the bag (no decode/encode),
with the QoS the bag recorded for each topic (transient-local topics stay transient local,
:mod:`door_bringup.bags.qos`); topics recorded without QoS get the contract's QoS for the
graph's own topics and reliable depth-100 otherwise. Each message is first checked to
deserialize as its type, and one that does not is reported, skipped and counted.
``--clock`` publishes /clock with the bag's time before each message, so nodes running
with ``use_sim_time`` replay exactly. Failures end with one line and the exit code of
:mod:`door_bringup.bags.exit_codes` (no traceback).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import rclpy
from rclpy.duration import Duration
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import QoSProfile
from rclpy.serialization import deserialize_message
from rosgraph_msgs.msg import Clock

from door_bringup.bags.exit_codes import BagExit, exit_code_for
from door_bringup.bags.qos import playback_profile
from door_bringup.bags.storage import BagError, BagMessage, read_messages, recorded_qos
from door_contract.network import keep_discovery_local
from door_contract.stamps import to_time_msg
from door_contract.topics import Topics, TopicSpec, interface_class

__all__ = ["BagPlayer", "PlaybackOptions", "PlaybackOptionsError", "main", "playback_offsets", "qos_for"]


@dataclass(frozen=True)
class PlaybackOptions:
    rate: float = 1.0                   # × original speed
    publish_clock: bool = False
    topics: tuple[str, ...] | None = None
    wait_for_subscribers_s: float = 0.0  # wait (bounded) until each topic has a subscriber
    wait_for_all_acked_s: float = 0.0  # after the last message, wait (bounded) until every one is acknowledged

    def __post_init__(self) -> None:
        if not (self.rate > 0.0 and self.rate < float("inf")):
            raise PlaybackOptionsError(f"--rate must be a finite number > 0, got {self.rate:g}")
        if not self.wait_for_subscribers_s >= 0.0:
            raise PlaybackOptionsError(f"--wait-for-subscribers must be ≥ 0 s, got {self.wait_for_subscribers_s:g}")
        if not (self.wait_for_all_acked_s >= 0.0 and self.wait_for_all_acked_s < float("inf")):
            raise PlaybackOptionsError(f"--wait-for-all-acked must be finite and ≥ 0 s, got {self.wait_for_all_acked_s:g}")


class PlaybackOptionsError(Exception):
    """Playback options out of range; the message names the option."""


def playback_offsets(timestamps_ns: Iterable[int], rate: float) -> list[float]:
    """Wall-clock seconds after the start at which each message is due: (tᵢ − t₀) / rate."""
    stamps = list(timestamps_ns)
    return [(t - stamps[0]) * 1e-9 / rate for t in stamps] if stamps else []


def qos_for(topic: str) -> QoSProfile:
    """The contract's reliability and durability for ``topic``, with a deep queue: a recorder
    must not lose a message published right before another (a latched depth-1 topic
    such as /door_task/approval_request is set and cleared within milliseconds)."""
    spec: TopicSpec | None = next((t for t in Topics.all() if t.name == topic), None)
    if spec is None:
        return QoSProfile(depth=100)
    profile = spec.qos.to_profile()
    profile.depth = max(profile.depth, 100)
    return profile


class BagPlayer(Node):
    def __init__(self, messages: list[BagMessage], options: PlaybackOptions,
                 offers: dict | None = None) -> None:
        super().__init__("bag_player")
        self.messages, self.options = messages, options
        self.published = self.skipped = 0
        self.publishers_by_topic, self.classes_by_topic = {}, {}
        for topic, type_name in sorted({(m.topic, m.type_name) for m in messages}):
            try:
                self.classes_by_topic[topic] = interface_class(type_name)
                self.publishers_by_topic[topic] = self.create_publisher(
                    self.classes_by_topic[topic], topic,
                    playback_profile((offers or {}).get(topic, []), qos_for(topic)))
            except (ImportError, AttributeError, ValueError):
                self.get_logger().warning(f"skipping {topic}: message type {type_name} is not installed")
        self.clock_publisher = self.create_publisher(Clock, Topics.CLOCK.name, Topics.CLOCK.qos.to_profile()) \
            if options.publish_clock else None

    def wait_for_subscribers(self) -> None:
        deadline = time.monotonic() + self.options.wait_for_subscribers_s
        while time.monotonic() < deadline:
            if all(p.get_subscription_count() > 0 for p in self.publishers_by_topic.values()):
                return
            rclpy.spin_once(self, timeout_sec=0.05)

    def _deserializes(self, message: BagMessage) -> bool:
        """Whether the stored bytes are a valid message of their type (else reported, counted)."""
        try:
            deserialize_message(message.data, self.classes_by_topic[message.topic])
            return True
        except Exception as error:  # rclpy raises several types for bad CDR
            self.skipped += 1
            self.get_logger().warning(f"message at {message.timestamp_ns} ns on {message.topic} does not "
                                      f"deserialize as {message.type_name} ({type(error).__name__}); skipped")
            return False

    def play(self) -> int:
        """Publish every message at its due time; returns how many were published."""
        self.wait_for_subscribers()
        offsets = playback_offsets((m.timestamp_ns for m in self.messages), self.options.rate)
        start = time.monotonic()
        for message, offset in zip(self.messages, offsets):
            delay = start + offset - time.monotonic()
            if delay > 0:
                time.sleep(delay)  # pacing the playback itself, not synchronising a test
            publisher = self.publishers_by_topic.get(message.topic)
            if publisher is None or not self._deserializes(message):
                continue
            if self.clock_publisher is not None:
                seconds = message.timestamp_ns * 1e-9
                self.clock_publisher.publish(Clock(clock=to_time_msg(seconds)))
            publisher.publish(message.data)
            self.published += 1
        self.wait_for_all_acked()
        return self.published

    def wait_for_all_acked(self) -> bool:
        """Wait (at most ``wait_for_all_acked_s``) until every reliable subscriber has
        acknowledged every message, as ``ros2 bag play --wait-for-all-acked`` does: a player that
        exits at once can take its last messages with it from a subscriber slow to read them (a
        loaded machine). Best-effort topics count as acknowledged. Whether all were."""
        deadline = time.monotonic() + self.options.wait_for_all_acked_s
        acked = True
        for publisher in self.publishers_by_topic.values():
            remaining = deadline - time.monotonic()
            if remaining <= 0.0:
                return False
            acked = publisher.wait_for_all_acked(Duration(nanoseconds=int(remaining * 1e9))) and acked
        return acked


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Play a rosbag2 bag (sqlite3 or mcap).",
                                     epilog="exit codes: see door_bringup.bags.exit_codes")
    parser.add_argument("bag", type=Path)
    parser.add_argument("--rate", type=float, default=1.0)
    parser.add_argument("--clock", action="store_true", help="publish /clock from the bag's time")
    parser.add_argument("--topics", nargs="+", default=None)
    parser.add_argument("--wait-for-subscribers", type=float, default=0.0, metavar="SECONDS")
    parser.add_argument("--wait-for-all-acked", type=float, default=0.0, metavar="SECONDS",
                        help="after the last message, wait up to SECONDS until reliable subscribers acknowledged all")
    args, ros_args = parser.parse_known_args(argv)
    try:
        options = PlaybackOptions(args.rate, args.clock, tuple(args.topics) if args.topics else None,
                                  args.wait_for_subscribers, args.wait_for_all_acked)
        messages = list(read_messages(args.bag, options.topics))
        offers = recorded_qos(args.bag) if args.bag.is_dir() else {}
    except PlaybackOptionsError as error:
        print(f"bag_play: {error}", file=sys.stderr)
        return BagExit.USAGE
    except BagError as error:
        print(f"bag_play: {error}", file=sys.stderr)
        return exit_code_for(error)
    return _play(messages, options, args.bag, ros_args, offers)


def _play(messages: list[BagMessage], options: PlaybackOptions, bag: Path, ros_args: list[str],
          offers: dict | None = None) -> int:
    keep_discovery_local()
    rclpy.init(args=ros_args)
    player = BagPlayer(messages, options, offers)
    try:
        count = player.play()
        skipped = f"; skipped {player.skipped} that did not deserialize" if player.skipped else ""
        player.get_logger().info(f"played {count} of {len(messages)} messages from {bag}{skipped}")
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        player.destroy_node()
        rclpy.try_shutdown()
    return BagExit.SKIPPED_MESSAGES if player.skipped else BagExit.OK


if __name__ == "__main__":
    sys.exit(main())
