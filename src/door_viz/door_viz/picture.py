"""The picture of what the FSM is offered, kept up to date from the proposals (ROS-free).

Each layer (door, swing, footsteps, hand paths) holds the shapes of the latest proposal of
its kind; :meth:`ProposalPicture.shapes` is the whole picture, which the node publishes as one
latched MarkerArray (a viewer that connects late sees all of it).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.marker_shapes import MarkerShape
from door_contract.payloads import DoorEstimate
from door_viz.proposals import door_shapes, footstep_shapes, hand_path_shapes, swing_shapes

__all__ = ["ProposalPicture", "SoleSize"]


@dataclass(frozen=True)
class SoleSize:
    length: float  # m
    width: float  # m


class ProposalPicture:
    def __init__(self, sole: SoleSize) -> None:
        self.sole = sole
        self.door: DoorEstimate | None = None
        self.opening: str | None = None  # "push" | "pull", from the FSM's requests
        self.door_angle = 0.0  # rad, as the FSM's last request stated it
        self._layers: dict[str, list[MarkerShape]] = {"door": [], "door_swing": [], "footsteps": [], "hand_path": []}

    def show_door(self, estimate: DoorEstimate) -> None:
        self.door = estimate
        self._layers["door"] = door_shapes(estimate)
        self._redraw_swing()

    def show_request(self, opening: str, door_angle: float) -> None:
        """What a planning request says about the door: how it opens and how far it is open."""
        self.opening, self.door_angle = opening, door_angle
        self._redraw_swing()

    def show_footsteps(self, steps: Sequence[FootPlacement]) -> None:
        self._layers["footsteps"] = footstep_shapes(steps, self.sole.length, self.sole.width)

    def show_hand_paths(self, paths: Mapping[str, np.ndarray]) -> None:
        self._layers["hand_path"] = hand_path_shapes(paths)

    def _redraw_swing(self) -> None:
        if self.door is not None and self.opening is not None:
            self._layers["door_swing"] = swing_shapes(self.door, self.opening, self.door_angle)

    def shapes(self) -> list[MarkerShape]:
        return [shape for layer in self._layers.values() for shape in layer]
