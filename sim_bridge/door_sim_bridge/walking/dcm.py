"""Feedback of the divergent component of motion (DCM) while walking.

The pattern generator plans the CoM c(t) of a linear inverted pendulum of height z_c; its
unstable part is the DCM (capture point) ξ = c + ċ/ω, ω = √(g/z_c), which obeys
ξ̇ = ω (ξ − p) for the ZMP p [Englsberger 2015]. The walking controller tracks the
planned CoM open loop through position-controlled joints; when the measured robot falls behind
the pattern (at a lift-off the stance leg gives way, and the measured CoM runs off towards the
swing side while the planned one turns back: issue #11), its DCM diverges from the planned DCM
exponentially. The feedback moves the CoM task's target against the error,

    Δc = −k · (ξ_measured − ξ_planned − b),

clipped to ``limit`` per axis: accelerating the CoM the other way puts the ZMP on the side of
the error, which drives ξ back (ξ̇ − ξ̇_planned = ω (e − Δp)). ``b`` is the error at the
walk's first tick, held for the walk: the simulated robot's CoM stands ~2 cm from the model's,
and that offset is the model's, not a fall.

The same error, less ``b``, tells when a walk was knocked off its pattern: walks that pass a door
stay within 4 cm of it, while a blow that fells the robot puts the capture point more than
:data:`PATTERN_DEPARTURE` from it seconds before the base tilts (:class:`PatternDeparture`, named
in a fall's reason).

[Englsberger 2015]: docs/REFERENCES.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PATTERN_DEPARTURE", "CentreOfMassMotion", "DcmFeedback", "PatternDeparture"]

PATTERN_DEPARTURE = 0.08
"""Capture-point error (m, the walk's first error taken out) past which a walk has left its
pattern. Walks through doors that passed stayed within 3.7 cm (push) and 2.9 cm (pull), the
offset included; a lever striking the pelvis (~2 kN) put a walk 16 cm off within 0.2 s, and the
robot fell 2 s later (passage rig, stop 34)."""


@dataclass(frozen=True, eq=False)
class CentreOfMassMotion:
    """The measured whole-body CoM (odom, m) and its velocity (m/s)."""

    position: np.ndarray
    velocity: np.ndarray

    def dcm(self, omega: float) -> np.ndarray:
        """ξ = c + ċ/ω (xy)."""
        capture: np.ndarray = (self.position + self.velocity / omega)[:2]
        return capture


@dataclass(frozen=True)
class PatternDeparture:
    """When a walk's capture point first left its pattern by more than :data:`PATTERN_DEPARTURE`."""

    walk_time: float
    """Seconds into the walk."""

    def __str__(self) -> str:
        return (f"the last walk's capture point left its pattern (by {100.0 * PATTERN_DEPARTURE:.0f} cm) "
                f"{self.walk_time:.1f} s into the walk")


class DcmFeedback:
    """Δc of the module docstring for one walk at a time (state: the offset ``b``, and the
    walk's :class:`PatternDeparture` once there is one)."""

    def __init__(self, gain: float, limit: float) -> None:
        self.gain, self.limit = gain, limit
        self._bias: np.ndarray | None = None
        self.departure: PatternDeparture | None = None

    def start(self) -> None:
        """A new walk: its first error is the model's offset, and it has not left its pattern."""
        self._bias, self.departure = None, None

    def shift(self, measured: CentreOfMassMotion, planned: CentreOfMassMotion, omega: float,
              walk_time: float) -> np.ndarray:
        """The CoM target's shift (xy, m) for the measured and the planned CoM motion at
        ``walk_time`` (s into the walk)."""
        error = measured.dcm(omega) - planned.dcm(omega)
        if self._bias is None:
            self._bias = error
        drift = error - self._bias
        if self.departure is None and float(np.linalg.norm(drift)) > PATTERN_DEPARTURE:
            self.departure = PatternDeparture(walk_time)
        shift: np.ndarray = np.clip(-self.gain * drift, -self.limit, self.limit)
        return shift
