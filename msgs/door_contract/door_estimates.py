"""The door estimates a planner has heard, so a request can name the one the operator approved."""

from __future__ import annotations

from collections import OrderedDict

from door_contract.payloads import DoorEstimate, decode


class DoorEstimateHistory:
    """The last ``size`` estimates by stamp; :meth:`pick` finds the approved one."""

    def __init__(self, size: int = 200) -> None:
        self._by_stamp: OrderedDict[float, DoorEstimate] = OrderedDict()
        self._size = size

    def add(self, estimate: DoorEstimate) -> None:
        self._by_stamp[estimate.stamp] = estimate
        while len(self._by_stamp) > self._size:
            self._by_stamp.popitem(last=False)

    @property
    def latest(self) -> DoorEstimate | None:
        return next(reversed(self._by_stamp.values()), None)

    def pick(self, stamp: float, carried: str = "") -> DoorEstimate | None:
        """The estimate a request names: the one it carries (JSON), else the one with
        ``stamp`` (within 1 µs), else — for ``stamp`` < 0 — the latest one."""
        if carried:
            return decode(DoorEstimate, carried)
        if stamp < 0:
            return self.latest
        return next((e for s, e in self._by_stamp.items() if abs(s - stamp) < 1e-6), None)
