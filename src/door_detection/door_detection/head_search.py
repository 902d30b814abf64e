"""The head search as the detector node runs it in the graph: frames in, neck moves out.

:class:`~door_detection.view_search.ViewSearch` says when to leave a view; this drives it
from the frames the detector gets and the neck joints the robot reports. A search starts at
the first frame without a confirmed door, from the head's pose then (its home view), and
asks for a neck move (:class:`LookCommand`) each time a view is used up. A frame counts for a
view only once the neck is there (within ``settle_tolerance`` of the view's targets), or,
for a neck that cannot quite reach, anyway after ``max_settle_frames`` frames taken once the
move's own duration is over (frame stamps, robot clock). Counting those frames from the move's
start instead left a view before the head got there whenever the move outlasted them: at the
standing camera's 8 Hz, 6 frames are 0.75 s, a pan from +0.6 to −0.6 rad takes 2.4 s, and the
search moved on while the head swept past the door (Monte-Carlo: two doors 0.4–0.5 rad aside
never confirmed in three 60 s searches; whether frames were dropped under load decided it).
A confirmed door ends the search where the head is; a search out of views looks home and
starts over.

The detector only asks: the FSM supervisor sends a move to the robot while DETECT_DOOR waits
for an estimate and at no other time, so a paused, stopped or walking robot's head never
moves for it. Body turns (:func:`~door_detection.view_search.plan_views`'s turns in place) are
not asked for here: the graph's views are the neck's (``max_body_turns`` = 0).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from door_contract.converters.trajectory import JointPath
from door_contract.ranges import FieldRange, check_fields
from door_detection.errors import DetectionError
from door_detection.neck import neck_of
from door_detection.view_search import (
    Neck,
    SearchStep,
    View,
    ViewSearch,
    ViewSearchOptions,
    head_move_time,
    plan_views,
)

if TYPE_CHECKING:  # Pinocchio is imported only by the caller that builds the kinematics
    from door_robot.kinematics import RobotKinematics

__all__ = ["HeadSearch", "HeadSearchOptions", "LookCommand", "head_search_of", "home_view"]


@dataclass(frozen=True)
class LookCommand:
    """Move the neck joints ``joint_names`` to ``goal`` (rad) in ``duration`` (s)."""

    joint_names: tuple[str, ...]
    goal: tuple[float, ...]
    duration: float

    def as_path(self) -> JointPath:
        """The move as a one-point joint path (the robot starts it from where the joints are)."""
        return JointPath(np.array([self.duration]), self.joint_names, np.array([self.goal]))

    def __str__(self) -> str:
        targets = ", ".join(f"{name} {value:.2f}" for name, value in zip(self.joint_names, self.goal))
        return f"looking at {targets} rad in {self.duration:.1f} s"


@dataclass(frozen=True)
class HeadSearchOptions:
    """How the graph's head search waits for the neck; validated on construction."""

    views: ViewSearchOptions = ViewSearchOptions(max_body_turns=0)
    """The views and when to leave one (the neck's only)."""
    settle_tolerance: float = 0.02
    """rad within which every neck joint must be of its target for a frame to count, (0, 0.5]."""
    max_settle_frames: int = 6
    """Frames after a move's duration that count anyway when the neck has not settled, [1, 100]."""
    speed_scale: float = 0.5
    """Fraction of the neck joints' speed limits a move uses, (0, 1]."""

    def __post_init__(self) -> None:
        check_fields(self, _HEAD_SEARCH_RANGES, DetectionError, integers=("max_settle_frames",))


_HEAD_SEARCH_RANGES = {
    "settle_tolerance": FieldRange(0.0, 0.5, "rad", low_open=True),
    "max_settle_frames": FieldRange(1, 100, "frames"),
    "speed_scale": FieldRange(0.0, 1.0, "", low_open=True),
}
"""The interval of every numeric :class:`HeadSearchOptions` field."""


def home_view(neck: Neck, joints: Mapping[str, float]) -> View:
    """The view the neck joints ``joints`` (rad, by name) look in (a missing joint: 0)."""
    pan = neck.pan.look(joints.get(neck.pan.joint, 0.0)) if neck.pan is not None else 0.0
    tilt = neck.tilt.look(joints.get(neck.tilt.joint, 0.0)) if neck.tilt is not None else 0.0
    return View(pan, tilt)


class HeadSearch:
    """Where the head looks while no door is confirmed (see the module docstring)."""

    def __init__(self, neck: Neck, options: HeadSearchOptions | None = None) -> None:
        if neck.pan is None and neck.tilt is None:
            raise DetectionError("a head search needs a neck with a pan or a tilt joint")
        self.neck, self.options = neck, options or HeadSearchOptions()
        self._moving_neck = Neck(*(None if axis is None else replace(axis, velocity=axis.velocity * self.options.speed_scale)
                                   for axis in (neck.pan, neck.tilt)))  # the speed limits a move uses
        self._search: ViewSearch | None = None
        self._home: View | None = None
        self._unsettled = 0
        self._arrival = -math.inf  # robot-clock time (s) the last move asked for should be over

    @property
    def searching(self) -> bool:
        return self._search is not None

    @property
    def view(self) -> View | None:
        """The view being looked from (None: not searching)."""
        return None if self._search is None else self._search.view

    def after_frame(self, stamp: float, joints: Mapping[str, float] | None, detected: bool,
                    confirmed: bool) -> LookCommand | None:
        """After the frame taken at ``stamp`` (s, robot clock): ``detected``, it gave an estimate;
        ``confirmed``, the vote has a door; ``joints``, the neck's measured positions (None: not
        known yet, nothing is asked). Returns the neck move to ask for, if any."""
        if confirmed:
            self._search = None
            return None
        if joints is None:
            return None
        if self._search is None:
            self._home = home_view(self.neck, joints)
            self._search = ViewSearch(plan_views(self.neck, self._home, self.options.views), self.options.views)
            self._unsettled = 0
        view = self._search.view
        if view is not None and not self._settled(view, joints):
            if stamp < self._arrival:  # still moving as asked: the frame shows the way there
                return None
            self._unsettled += 1
            if self._unsettled < self.options.max_settle_frames:
                return None
        step = self._search.after_frame(detected, False)
        if step is SearchStep.STAY:
            return None
        self._unsettled = 0
        following = self._search.view
        if following is None:  # out of views: back home, and a new search from there
            following, self._search = self._home or View(0.0, 0.0), None
        look = self._look(home_view(self.neck, joints), following)
        self._arrival = stamp + look.duration
        return look

    def _settled(self, view: View, joints: Mapping[str, float]) -> bool:
        targets = view.joint_targets(self.neck)
        return all(abs(joints.get(name, target) - target) <= self.options.settle_tolerance
                   for name, target in targets.items())

    def _look(self, start: View, goal: View) -> LookCommand:
        targets = goal.joint_targets(self.neck)
        duration = max(head_move_time(self._moving_neck, start, goal), 0.1)
        return LookCommand(tuple(targets), tuple(targets.values()), duration)


def head_search_of(kinematics: RobotKinematics, max_pan: float) -> HeadSearch | None:
    """The head search of a robot (its neck found in the URDF, :func:`~door_detection.neck.neck_of`)
    panning at most ``max_pan`` (rad); None for a robot without a neck."""
    neck = neck_of(kinematics)
    if neck.pan is None and neck.tilt is None:
        return None
    return HeadSearch(neck, HeadSearchOptions(views=ViewSearchOptions(max_pan=max_pan, max_body_turns=0)))
