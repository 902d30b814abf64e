"""What the stance leg did in the moments before a fall: the passage rig's ``--trace-falls``.

Every traced fall of issue #11 began with a *pelvis dip*: as a swing foot lifts, the stance leg
gives way and the pelvis drops centimetres in a fraction of a second. :class:`FallTrace`
samples the physical robot every few physics steps over the last seconds and, after a fall,
reports the samples around the first dip: the pelvis height, where the CoM stands in each
sole's frame (the LIPM's lateral offset at lift-off), each sole's load and how deep it has sunk
into the floor, the leg joint nearest its torque limit and the one furthest from its target.
Soft motors far from their limits point at the constraint solver, saturated ones at the
demand (see :class:`door_sim_bridge.world.ContactSolver`).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from door_contract.vocabulary import Side
from door_sim_bridge.world import DoorWorld

__all__ = ["FallTrace", "FallTraceError", "StanceSample", "dip_onset", "leg_joints"]

DIP_DEPTH = 0.015
"""m the pelvis must fall below its highest point of the preceding :data:`DIP_LOOKBACK` to dip."""
DIP_LOOKBACK = 0.5
"""s over which a dip's depth is measured."""


class FallTraceError(RuntimeError):
    """A trace asked for with settings it cannot sample."""


@dataclass(frozen=True)
class StanceSample:
    """The legs at one instant (odom; the CoM in each sole's frame, x forward, y left)."""

    time: float  # s, sim time
    pelvis_height: float  # m, base frame above the floor
    com_in_sole: Mapping[Side, tuple[float, float]]  # m
    load: Mapping[Side, float]  # N of floor contact
    sinking: Mapping[Side, float]  # m below the floor
    strained: tuple[str, float]  # (leg joint, |effort| / its limit), the most strained
    lagging: tuple[str, float]  # (leg joint, target − position in rad), the furthest behind

    def line(self) -> str:
        soles = "  ".join(
            f"{side.value} {self.load[side]:5.0f} N sunk {1000 * self.sinking[side]:4.1f} mm "
            f"CoM ({self.com_in_sole[side][0]:+.3f}, {self.com_in_sole[side][1]:+.3f})" for side in Side)
        return (f"t {self.time:8.3f} s  pelvis {self.pelvis_height:.3f} m  {soles}  "
                f"strained {self.strained[0]} {100 * self.strained[1]:3.0f} %  "
                f"lagging {self.lagging[0]} {self.lagging[1]:+.3f} rad")


def dip_onset(samples: list[StanceSample], depth: float = DIP_DEPTH, lookback: float = DIP_LOOKBACK) -> float | None:
    """The time of the first sample ``depth`` m or more below the highest pelvis of the
    ``lookback`` s before it (None: the pelvis never dipped)."""
    for index, sample in enumerate(samples):
        highest = max(earlier.pelvis_height for earlier in samples[:index + 1]
                      if earlier.time >= sample.time - lookback)
        if highest - sample.pelvis_height >= depth:
            return sample.time
    return None


def leg_joints(world: DoorWorld) -> tuple[str, ...]:
    """The movable joints between the base and a sole, for any robot profile."""
    chains = set().union(*(world.robot.chain_to_root(world.robot.link_index(frame)) for frame in world.profile.feet.values()))
    return tuple(name for name in world.joint_names if world.robot.joint_link_index(name) in chains)


class FallTrace:
    """Samples ``world`` every ``every`` physics steps (call :meth:`step` after each), keeping
    ``window_s`` s; :meth:`report` reads the samples around the first dip."""

    def __init__(self, world: DoorWorld, every: int = 4, window_s: float = 6.0) -> None:
        if not isinstance(every, int) or every < 1 or not window_s > 0.0:
            raise FallTraceError(f"FallTrace needs every >= 1 step and window_s > 0 s, got {every!r}, {window_s!r}")
        self._world = world
        self._every = every
        self._steps = 0
        self._per_second = world.config.physics_rate / every  # samples
        self._samples: deque[StanceSample] = deque(maxlen=max(1, int(window_s * self._per_second)))
        self._legs = leg_joints(world)

    def step(self) -> None:
        self._steps += 1
        if self._steps % self._every == 0:
            self._samples.append(self.sample())

    def sample(self) -> StanceSample:
        world = self._world
        contacts = world.sole_contacts()
        com = world.centre_of_mass()
        com_in_sole = {}
        for side, frame in world.profile.feet.items():
            local = np.linalg.inv(world.link_pose(frame)) @ np.array([com[0], com[1], com[2], 1.0])
            com_in_sole[side] = (float(local[0]), float(local[1]))
        states, limits, targets = world.joint_states(), world.joint_limits(), world.joint_targets()
        position = dict(zip(states.names, states.positions))
        effort = dict(zip(states.names, states.efforts))
        strained = max(((name, abs(effort[name]) / max(limits[name].effort, 1.0)) for name in self._legs),
                       key=lambda item: item[1])  # a URDF effort of 0 counts as 1 N·m
        lagging = max(((name, targets[name] - position[name]) for name in self._legs), key=lambda item: abs(item[1]))
        return StanceSample(world.time, float(world.base_pose()[2, 3]), com_in_sole,
                            {side: contact.load for side, contact in contacts.items()},
                            {side: contact.sinking for side, contact in contacts.items()},
                            (strained[0], float(strained[1])), (lagging[0], float(lagging[1])))

    def report(self, before: float = 0.3, after: float = 0.2) -> tuple[str, ...]:
        """The samples from ``before`` s ahead of the first dip to ``after`` s past it, headed
        by the dip's time; the last samples when there was none."""
        samples = list(self._samples)
        onset = dip_onset(samples)
        if onset is None:
            last = max(1, int(after * self._per_second))
            return ("no pelvis dip in the samples kept; the last of them:", *(sample.line() for sample in samples[-last:]))
        return (f"pelvis dip at t = {onset:.3f} s (≥ {100 * DIP_DEPTH:.1f} cm in {DIP_LOOKBACK} s):",
                *(sample.line() for sample in samples if onset - before <= sample.time <= onset + after))
