"""The randomised doors of the Monte-Carlo: the intervals a trial is drawn from.

:data:`FULL` is [Banerjee 2015] Table II's working range widened to issue #13's: start 1.0–4.0 m
from the door, ±0.6 m aside, turned ±0.6 rad; doors 0.80–1.00 m wide with the lever at
0.85–1.10 m; wind on the hinge up to 3 N·m; depth noise k up to 0.005; and a random appearance
(leaf, frame, handle, wall and floor colours, each uniform in RGB). :data:`NARROW` is the earlier
campaign's (around the DRC door, no appearance change): the same seed draws the same doors with
it as before this module existed.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import StrEnum

import numpy as np

from door_bringup.door_task import TaskOptions
from door_sim_bridge.world_ranges import COLOUR_FIELDS

__all__ = ["FULL", "NARROW", "RangeSet", "TrialRanges", "ranges_named"]


@dataclass(frozen=True)
class TrialRanges:
    """Closed intervals (low, high) of each drawn quantity, SI units; ``appearance``: draw the
    scene's colours too."""

    distance: tuple[float, float]  # m, start to door plane
    lateral: tuple[float, float]  # m, start aside of the door's axis
    yaw: tuple[float, float]  # rad, start heading off the door's normal
    door_width: tuple[float, float]  # m, leaf
    handle_height: tuple[float, float]  # m, lever axis above the floor
    wind: tuple[float, float]  # N·m, amplitude of the wind torque on the hinge
    depth_noise: tuple[float, float]  # k of the depth camera's noise σ = k z²
    appearance: bool = False

    def draw(self, rng: np.random.Generator, base: TaskOptions) -> TaskOptions:
        """One door (the draws in the order the earlier campaigns made them, then the colours)."""
        options = replace(base, seed=int(rng.integers(0, 2**31 - 1)),
                          opening=str(rng.choice(["push", "pull"])), hinge=str(rng.choice(["left", "right"])),
                          distance=_uniform(rng, self.distance), lateral=_uniform(rng, self.lateral),
                          yaw=_uniform(rng, self.yaw), door_width=_uniform(rng, self.door_width),
                          handle_height=_uniform(rng, self.handle_height), wind=_uniform(rng, self.wind),
                          depth_noise=_uniform(rng, self.depth_noise))
        if not self.appearance:
            return options
        return replace(options, colours=tuple((part, _colour(rng)) for part in COLOUR_FIELDS))


def _uniform(rng: np.random.Generator, interval: tuple[float, float]) -> float:
    return float(rng.uniform(*interval))


def _colour(rng: np.random.Generator) -> tuple[float, float, float]:
    """RGB, each channel uniform in [0, 1]."""
    red, green, blue = (float(channel) for channel in rng.uniform(0.0, 1.0, 3))
    return red, green, blue


NARROW = TrialRanges(distance=(2.0, 3.5), lateral=(-0.3, 0.3), yaw=(-0.3, 0.3), door_width=(0.86, 0.96),
                     handle_height=(0.86, 0.98), wind=(0.0, 1.0), depth_noise=(0.0, 0.003))
FULL = TrialRanges(distance=(1.0, 4.0), lateral=(-0.6, 0.6), yaw=(-0.6, 0.6), door_width=(0.80, 1.00),
                   handle_height=(0.85, 1.10), wind=(0.0, 3.0), depth_noise=(0.0, 0.005), appearance=True)


class RangeSet(StrEnum):
    """The Monte-Carlo's ``--ranges``."""

    FULL = "full"
    NARROW = "narrow"


def ranges_named(name: RangeSet) -> TrialRanges:
    return FULL if name is RangeSet.FULL else NARROW
