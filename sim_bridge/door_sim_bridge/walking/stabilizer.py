"""Balance against the door: a CoM offset from the measured hand/body forces and the CoP.

**Feed-forward (static moment balance).** A force F applied to the robot at p (the hand on
the handle, the arm or body against the leaf) moves the centre of pressure q of a robot
standing still with its CoM at c. Moments about q balance (flat ground, quasi-static) when

    m g (c − q)ₓᵧ + p_z Fₓᵧ − (pₓᵧ − qₓᵧ) F_z = 0,

so a forward push moves the CoP forward, and leaning the CoM by
Δc_ff = −[p_z Fₓᵧ − (pₓᵧ − rₓᵧ) F_z] / (m g) keeps it at the reference point r
(ENVIRONMENT.md: a standing TALOS held 100 N at a hand with this lean, and fell without it).

**Feedback (CoP admittance).** What the feed-forward misses (an unmeasured shove, a model
error) shows as the measured CoP staying away from the reference. The CoP error is first
low-passed (time constant ``cop_filter_s``: a robot rocking from foot to foot after a walk
averages out, a sustained push does not — fed back unfiltered, the rocking grew until it
fell); the part of the filtered error beyond a dead band ``cop_deadband`` is integrated
into the offset with gain ``cop_gain`` (1/s), and the offset leaks back towards the
feed-forward with time constant ``leak_time_s`` when the error is inside the band.

**Smoothing.** The feed-forward passes through two cascaded first-order low-passes (time
constant ``force_filter_s`` each: a critically damped second-order filter). A CoM offset that
jumps, or ramps at the rate limit and stops, asks the feet for a ZMP impulse of
(z_c / g)·Δv: a hand force counted from the first tick of a walk (30 N at the hand, 3.4 cm of
lean at 0.2 m/s) put the ZMP on the stance foot's toe and TALOS tipped over it; filtered,
the lean's acceleration stays bounded and the contact chatter of fingertips on a leaf
(0-40 N from tick to tick) averages out. The force is first clipped to ``max_force``: a body
striking the leaf reads 2 kN for a tick, and that spike alone, filtered, leaned the robot
4 cm for half a second after the contact had ended. While walking the clip is
``max_walking_force``, lower: a hand pushing a leaf open while side-stepping loses it without
warning (the leaf swings on and away), and the lean against its 55 N then outlasted the force
by the filter's half second: the robot tipped towards the door, swung back and toppled over
its trailing foot (9 of 12 falls of the sideways push passage on the rig, 1-2 s after the
contact ended); at 40 N the same doors went through.

Both only act on what exceeds the dead bands: small door forces (a handle's return spring, a
closer) leave the body still, so a hand on the handle follows its plan exactly — leaning
against a latched door through the hand would otherwise feed itself. The offset is clamped
to ``max_offset`` and rate-limited to ``max_rate``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_sim_bridge.validation import FieldRange, check_ranges

__all__ = ["ContactWrench", "Stabilizer", "StabilizerOptions", "beyond", "clipped", "feed_forward_offset"]


@dataclass(frozen=True)
class StabilizerOptions:
    """Gains and limits of the CoM offset (SI units)."""

    force_deadband: float = 0.03  # m of predicted CoP shift the feed-forward ignores standing
    cop_deadband: float = 0.06  # m of CoP error the feedback ignores (a last resort near the sole edges)
    cop_gain: float = 0.5  # 1/s, integral gain on the CoP error beyond the dead band
    cop_filter_s: float = 0.5  # s, low-pass time constant of the CoP error
    leak_time_s: float = 2.0  # s, the feedback offset decays with this time constant
    max_offset: float = 0.10  # m, |CoM offset| per axis
    max_rate: float = 0.20  # m/s, change of the offset
    walking_feedback: bool = False  # CoP feedback while walking (the measured CoP is noisy then)
    force_filter_s: float = 0.25  # s, time constant of each of the two low-passes on the feed-forward
    max_force: float = 100.0  # N, the measured force is clipped to this magnitude before the feed-forward
    max_walking_force: float = 40.0  # N, the same while walking (a pushed leaf escapes the hand)
    # CoM target shift per m of DCM error while walking (door_sim_bridge.walking.dcm). Rig, push
    # left walked there from 2.5 m, 4 doors: 0 → 0/4 through, 0.5 → 1/4 (prototype), 1.5 → 3/4
    # (prototype) and 2/4 (this module), 2.5 → fell on the first (issue #11, stop 27). The
    # narrow push doors that fell in the full-range campaigns (0.80 m, side-stepping with the
    # back on the leaf: the closer pushes the robot towards the latch, the feedback leans it back
    # onto a leaf that then gives way), same rig doors (stop 30): 1.5 → 0/6 through, 0.75 → 6/8,
    # 0.5 → 2/4; shift clipped to 0.02 m at 1.5 → 0/4. Pull doors at 0.75: 4/4.
    dcm_gain: float = 0.75
    max_dcm_shift: float = 0.04  # m per axis

    def __post_init__(self) -> None:
        check_ranges(self, {"force_deadband": FieldRange(0.0, 0.2, "m"), "cop_deadband": FieldRange(0.0, 0.2, "m"),
                            "cop_gain": FieldRange(0.0, 50.0, "1/s"), "cop_filter_s": FieldRange(0.0, 10.0, "s"),
                            "force_filter_s": FieldRange(0.0, 10.0, "s"), "max_force": FieldRange(0.0, 5000.0, "N"),
                            "max_walking_force": FieldRange(0.0, 5000.0, "N"),
                            "dcm_gain": FieldRange(0.0, 10.0, ""), "max_dcm_shift": FieldRange(0.0, 0.2, "m"),
                            "leak_time_s": FieldRange(0.05, 100.0, "s"), "max_offset": FieldRange(0.0, 0.2, "m"),
                            "max_rate": FieldRange(0.001, 5.0, "m/s")})


@dataclass(frozen=True, eq=False)
class ContactWrench:
    """The net external force on the robot (N, world axes) and its application point (m)."""

    force: np.ndarray
    point: np.ndarray

    @staticmethod
    def none() -> ContactWrench:
        return ContactWrench(np.zeros(3), np.zeros(3))


def feed_forward_offset(wrench: ContactWrench, reference: np.ndarray, weight: float) -> np.ndarray:
    """Δc_ff (xy, m) of the module docstring; ``weight`` = m g (N)."""
    force, point = wrench.force, wrench.point
    moment_arm = point[2] * force[:2] - (point[:2] - reference[:2]) * force[2]
    offset: np.ndarray = -moment_arm / weight
    return offset


def clipped(wrench: ContactWrench, limit: float) -> ContactWrench:
    """``wrench`` with its force scaled down to at most ``limit`` (N) in magnitude."""
    magnitude = float(np.linalg.norm(wrench.force))
    if magnitude <= limit:
        return wrench
    return ContactWrench(wrench.force * (limit / magnitude), wrench.point)


def beyond(value: np.ndarray, band: float) -> np.ndarray:
    """The part of each component of ``value`` outside [−band, band]."""
    excess: np.ndarray = value - np.clip(value, -band, band)
    return excess


class Stabilizer:
    """The CoM offset, updated once per control tick (state: the feedback integral)."""

    def __init__(self, options: StabilizerOptions, weight: float) -> None:
        self.options = options
        self._weight = weight
        self.reset()

    def reset(self) -> None:
        self._feedback = np.zeros(2)
        self._cop_error = np.zeros(2)
        self._feed_forward = (np.zeros(2), np.zeros(2))
        self.offset = np.zeros(2)

    def update(self, dt: float, reference: np.ndarray, wrench: ContactWrench, cop: np.ndarray | None,
               walking: bool) -> np.ndarray:
        """New CoM offset (xy, m) for the ZMP ``reference`` (xy), the external ``wrench`` and the
        measured ``cop`` (xy, None in the air)."""
        options = self.options
        limit = options.max_walking_force if walking else options.max_force
        ff = feed_forward_offset(clipped(wrench, limit), reference, self._weight)
        if not walking:  # on one foot the polygon is too small to leave part of a force uncompensated
            ff = beyond(ff, options.force_deadband)
        ff = self._smoothed(ff, dt)
        if cop is not None and (options.walking_feedback or not walking):
            smoothing = min(1.0, dt / options.cop_filter_s) if options.cop_filter_s > 0.0 else 1.0
            self._cop_error += smoothing * (np.asarray(cop[:2]) - reference[:2] - self._cop_error)
            self._feedback -= options.cop_gain * beyond(self._cop_error, options.cop_deadband) * dt
        self._feedback *= max(0.0, 1.0 - dt / options.leak_time_s)
        target = np.clip(ff + self._feedback, -options.max_offset, options.max_offset)
        step = np.clip(target - self.offset, -options.max_rate * dt, options.max_rate * dt)
        self.offset = self.offset + step
        return self.offset

    def _smoothed(self, ff: np.ndarray, dt: float) -> np.ndarray:
        """``ff`` through the two cascaded low-passes (unfiltered when ``force_filter_s`` is 0)."""
        tau = self.options.force_filter_s
        if tau <= 0.0:
            return ff
        alpha = min(1.0, dt / tau)
        first, second = self._feed_forward
        first = first + alpha * (ff - first)
        second = second + alpha * (first - second)
        self._feed_forward = (first, second)
        return second
