"""Time stamps as plain seconds (float) in the cores, ``builtin_interfaces/Time`` on the bus."""

from __future__ import annotations

from builtin_interfaces.msg import Time

__all__ = ["Stamp", "UniqueStamps", "from_time_msg", "stamp_ns", "time_msg_of_ns", "to_time_msg"]

Stamp = float  # seconds


def to_time_msg(seconds: Stamp) -> Time:
    whole = int(seconds // 1)
    return Time(sec=whole, nanosec=int(round((seconds - whole) * 1e9)) % 1_000_000_000)


def from_time_msg(stamp: Time) -> Stamp:
    seconds: Stamp = stamp.sec + stamp.nanosec * 1e-9
    return seconds


def stamp_ns(stamp: Time) -> int:
    """A stamp as integer nanoseconds: how an executed message and its outcome are matched."""
    nanoseconds: int = stamp.sec * 1_000_000_000 + stamp.nanosec
    return nanoseconds


class UniqueStamps:
    """Stamps (ns) that strictly increase, for messages matched to their answer by stamp.

    Under ``use_sim_time`` the clock advances in /clock steps (10 ms) and reads 0 before the
    first one, so two messages sent in one step would share a stamp; each stamp here is at
    least 1 ns after the previous one.
    """

    def __init__(self) -> None:
        self._last = -1

    def next(self, now_ns: int) -> int:
        self._last = max(int(now_ns), self._last + 1)
        return self._last


def time_msg_of_ns(stamp: int) -> Time:
    """Integer nanoseconds as ``builtin_interfaces/Time`` (inverse of :func:`stamp_ns`)."""
    return Time(sec=stamp // 1_000_000_000, nanosec=stamp % 1_000_000_000)
