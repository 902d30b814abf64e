"""QoS between a bag and the graph: what publishers offer is recorded; playing restores it.

As rosbag2 does (Jazzy's ``ros2 bag record`` / ``play``):

* the recorder stores every publisher's offered profile with its topic, and subscribes so as
  to match all of them (:func:`door_contract.qos.matching_subscription`: a latched message
  published before the recorder joined is still recorded);
* the player publishes a topic with the recorded reliability and durability when all the
  recorded offers agree (a latched ``/door_task/state`` stays latched: a late subscriber still
  gets the last state), else reliable and volatile. Depth: the recorded depth for transient
  local topics (what a late joiner receives), at least 100 otherwise (fast playback) and where
  the recording did not know it (depth 0: the real talker bags' ``/rosout``, transient local,
  was replayed at depth 1, and at 20× rate a loaded machine overwrote a line before it was
  acknowledged: stop 43's CI).

Values are rosbags' ``Qos`` tuples, whose enum values are rmw's, like rclpy's policies.
"""

from __future__ import annotations

from collections.abc import Sequence

from rclpy.duration import Duration
from rclpy.qos import DurabilityPolicy, HistoryPolicy, LivelinessPolicy, QoSProfile, ReliabilityPolicy
from rosbags.interfaces import Qos, QosDurability, QosHistory, QosLiveliness, QosReliability, QosTime

__all__ = ["offered_qos", "playback_profile"]

VOLATILE_DEPTH = 100


def _time(duration: Duration) -> QosTime:
    sec, nsec = divmod(duration.nanoseconds, 1_000_000_000)
    return QosTime(int(sec), int(nsec))


def offered_qos(profile: QoSProfile) -> Qos:
    """A publisher's profile (``get_publishers_info_by_topic``) as rosbag2 metadata stores it."""
    return Qos(QosHistory(int(profile.history)), int(profile.depth), QosReliability(int(profile.reliability)),
               QosDurability(int(profile.durability)), _time(profile.deadline), _time(profile.lifespan),
               QosLiveliness(int(profile.liveliness)), _time(profile.liveliness_lease_duration),
               bool(profile.avoid_ros_namespace_conventions))


def playback_profile(offers: Sequence[Qos], fallback: QoSProfile) -> QoSProfile:
    """The publisher that replays a topic recorded with ``offers`` (``fallback`` if none)."""
    if not offers:
        return fallback
    reliabilities = {o.reliability for o in offers}
    durabilities = {o.durability for o in offers}
    agree = len(reliabilities) == 1 and len(durabilities) == 1
    reliable = not agree or QosReliability.BEST_EFFORT not in reliabilities
    latched = agree and QosDurability.TRANSIENT_LOCAL in durabilities
    recorded_depth = max(o.depth for o in offers)
    depth = recorded_depth if latched and recorded_depth > 0 else max(VOLATILE_DEPTH, recorded_depth)
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE if reliable else ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
                      liveliness=LivelinessPolicy.AUTOMATIC)
