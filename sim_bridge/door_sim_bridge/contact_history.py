"""What struck the robot before it fell: the robot–door contact forces of the last few seconds.

A fall in the graph was a line "base tilted 35°" and nothing else; the passage rig, which
steps the world itself, prints the hardest contacts, but a fall that only the graph shows
(Monte-Carlo seed 5, trial 12: a pull door, 23 s into the walk on after the tuck; the rig did
not reproduce it) left nothing to go on. The simulation loop records every step's contacts
here and a fall's outcome names the hardest of its last :data:`WINDOW` seconds.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass

from door_sim_bridge.errors import SimulationError

__all__ = ["WINDOW", "ContactHistory", "ContactPeak"]

WINDOW = 3.0
"""Seconds of simulated time kept (a fall takes about 1 s from the first tilt to 34°)."""


@dataclass(frozen=True)
class ContactPeak:
    """The hardest normal force (N) of one ``"<robot link> | <door link>"`` pair, and when (s)."""

    pair: str
    force: float
    time: float

    def __str__(self) -> str:
        return f"{self.pair} {self.force:.0f} N at t = {self.time:.2f} s"


class ContactHistory:
    """The robot–door contacts (:meth:`DoorWorld.door_contact_forces`) of the last ``window``
    seconds of simulated time."""

    def __init__(self, window: float = WINDOW) -> None:
        if not 0.0 < window < float("inf"):
            raise SimulationError(f"contact history window must be a positive finite time (s), got {window}")
        self.window = window
        self._samples: deque[tuple[float, Mapping[str, float]]] = deque()

    def record(self, time: float, forces: Mapping[str, float]) -> None:
        """One step's forces at ``time`` (s); samples older than the window are forgotten."""
        if forces:
            self._samples.append((time, dict(forces)))
        while self._samples and self._samples[0][0] < time - self.window:
            self._samples.popleft()

    def peaks(self, count: int = 3) -> tuple[ContactPeak, ...]:
        """The ``count`` pairs that pressed hardest in the window, hardest first."""
        hardest: dict[str, ContactPeak] = {}
        for time, forces in self._samples:
            for pair, force in forces.items():
                if pair not in hardest or force > hardest[pair].force:
                    hardest[pair] = ContactPeak(pair, force, time)
        return tuple(sorted(hardest.values(), key=lambda peak: -peak.force)[:count])

    def summary(self) -> str:
        """``"hardest robot–door contacts in the last 3 s: … N at t = … s, …"``, or that there was none."""
        peaks = self.peaks()
        if not peaks:
            return f"no robot–door contact in the last {self.window:g} s"
        return f"hardest robot–door contacts in the last {self.window:g} s: " + ", ".join(map(str, peaks))
