"""The door estimates a planner has heard, so a request can name the one the operator approved."""

from __future__ import annotations

from collections import OrderedDict

from door_contract.payloads import DoorEstimate


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

    def pick(self, stamp: float) -> DoorEstimate | None:
        """The estimate with ``stamp`` (within 1 µs); the latest one when ``stamp`` < 0."""
        if stamp < 0:
            return self.latest
        return next((e for s, e in self._by_stamp.items() if abs(s - stamp) < 1e-6), None)
