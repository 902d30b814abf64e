"""Time stamps as plain seconds (float) in the cores, ``builtin_interfaces/Time`` on the bus."""

from __future__ import annotations

from builtin_interfaces.msg import Time

Stamp = float  # seconds


def to_time_msg(seconds: Stamp) -> Time:
    whole = int(seconds // 1)
    return Time(sec=whole, nanosec=int(round((seconds - whole) * 1e9)) % 1_000_000_000)


def from_time_msg(stamp: Time) -> Stamp:
    return stamp.sec + stamp.nanosec * 1e-9


def stamp_ns(stamp: Time) -> int:
    """A stamp as integer nanoseconds: how an executed message and its outcome are matched."""
    return stamp.sec * 1_000_000_000 + stamp.nanosec
