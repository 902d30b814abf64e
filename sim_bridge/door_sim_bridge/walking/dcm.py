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

[Englsberger 2015]: docs/REFERENCES.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["CentreOfMassMotion", "DcmFeedback"]


@dataclass(frozen=True, eq=False)
class CentreOfMassMotion:
    """The measured whole-body CoM (odom, m) and its velocity (m/s)."""

    position: np.ndarray
    velocity: np.ndarray

    def dcm(self, omega: float) -> np.ndarray:
        """ξ = c + ċ/ω (xy)."""
        capture: np.ndarray = (self.position + self.velocity / omega)[:2]
        return capture


class DcmFeedback:
    """Δc of the module docstring for one walk at a time (state: the offset ``b``)."""

    def __init__(self, gain: float, limit: float) -> None:
        self.gain, self.limit = gain, limit
        self._bias: np.ndarray | None = None

    def start(self) -> None:
        """A new walk: its first error is the model's offset."""
        self._bias = None

    def shift(self, measured: CentreOfMassMotion, planned: CentreOfMassMotion, omega: float) -> np.ndarray:
        """The CoM target's shift (xy, m) for the measured and the planned CoM motion."""
        error = measured.dcm(omega) - planned.dcm(omega)
        if self._bias is None:
            self._bias = error
        shift: np.ndarray = np.clip(-self.gain * (error - self._bias), -self.limit, self.limit)
        return shift
