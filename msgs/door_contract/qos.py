"""QoS profiles of the contract as plain values, turned into ``rclpy`` profiles on demand.

Kept ROS-free so the contract can be read (and documented) without rclpy; nodes call
:meth:`QosSpec.to_profile`.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the contract stays ROS-free at run time: rclpy is imported where a profile is made
    from collections.abc import Sequence

    from rclpy.qos import QoSProfile

__all__ = ["CLOCK", "EVENTS", "LATCHED", "REQUESTS", "SENSOR", "SERVICE", "TF_STREAM", "Durability", "QosSpec",
           "Reliability", "matching_subscription"]


class Reliability(str, Enum):
    RELIABLE = "reliable"
    BEST_EFFORT = "best_effort"


class Durability(str, Enum):
    VOLATILE = "volatile"
    TRANSIENT_LOCAL = "transient_local"


@dataclass(frozen=True)
class QosSpec:
    """History depth, reliability and durability of one topic."""

    depth: int = 10
    reliability: Reliability = Reliability.RELIABLE
    durability: Durability = Durability.VOLATILE

    def to_profile(self) -> QoSProfile:
        """The rclpy profile (rclpy imported here, lazily: the contract stays ROS-free)."""
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        return QoSProfile(
            history=HistoryPolicy.KEEP_LAST,
            depth=self.depth,
            reliability=ReliabilityPolicy[self.reliability.name],
            durability=DurabilityPolicy[self.durability.name],
        )


#: Commands and events: every message matters.
EVENTS = QosSpec(depth=10)
#: Requests, outcomes, cancels and operator commands: every one answered, so a burst of
#: hundreds is queued, not overwritten (issue #12: depth 10 let 77 of 100 requests vanish).
REQUESTS = QosSpec(depth=1000)
#: Sensor streams between processes: RELIABLE (BEST_EFFORT lost ~15 % of VGA frames here).
SENSOR = QosSpec(depth=5)
#: Latest-value topics a late joiner must still receive (state, approval request).
LATCHED = QosSpec(depth=1, durability=Durability.TRANSIENT_LOCAL)
#: /tf: as tf2_ros broadcasts it, reliable with a deep queue (many frames per message).
TF_STREAM = QosSpec(depth=100)
#: /clock: many small messages, only the newest matters.
CLOCK = QosSpec(depth=1, reliability=Reliability.BEST_EFFORT)
#: Service requests and responses: every call answered, a burst of hundreds queued.
SERVICE = QosSpec(depth=1000)


SUBSCRIPTION_DEPTH = 100


def matching_subscription(offered: Sequence[QoSProfile], fallback: QoSProfile) -> QoSProfile:
    """A subscription that receives from every publisher offering ``offered`` (what rosbag2's
    recorder and Foxglove's bridge subscribe with): best effort if any publisher is best
    effort, transient local only if every publisher is (then a latched message published
    before the subscriber joined still arrives), a deep queue. ``fallback`` when nobody offers.
    """
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    if not offered:
        return fallback
    best_effort = any(p.reliability == ReliabilityPolicy.BEST_EFFORT for p in offered)
    latched = all(p.durability == DurabilityPolicy.TRANSIENT_LOCAL for p in offered)
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=max(SUBSCRIPTION_DEPTH, fallback.depth),
                      reliability=ReliabilityPolicy.BEST_EFFORT if best_effort else ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE)
