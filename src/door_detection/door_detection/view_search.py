"""Active perception: where to look next while no door is confirmed (beyond [Banerjee 2015]).

[Banerjee 2015]'s detector looked where the robot stood; a door partly out of the head camera's
view (one edge beyond the image border) gave "no pair of vertical lines" forever. The
search here turns the head first — TALOS has a 2-DOF neck — then the body, in place:

* **views** (:func:`plan_views`): pans 0, +s, −s, +2s, −2s, … (s = ``pan_step``, within the
  neck's limits and ``max_pan``) at the home tilt, then the same pans at each extra tilt
  offset, then body turns of ±k·``body_turn_step`` (k = 1 … ``max_body_turns``, left
  first) with the pan sweep repeated at the home tilt. Neighbouring pans must overlap by a
  door's angular span, so that some view holds both edges: s ≤ FOV_h − span, the span of a
  1.0 m door at 1 m being 1.02 rad with its frame (:func:`pan_step_for`).
* **moving on** (:class:`ViewSearch`): a view is kept until a door is confirmed, or
  ``empty_frames_per_view`` frames taken there (after the head settled) gave no estimate at
  all, or ``frames_per_view`` gave estimates that never confirmed; the frames from all views
  are voted on together in ``odom`` (:class:`~door_detection.voting.Voter`).

Angles are "look" angles: pan > 0 looks left, tilt > 0 looks down, body yaw > 0 turns left,
all relative to the search's start; :class:`NeckAxis` maps them onto joint angles, and
:func:`neck_of` finds the neck joints in the URDF (:mod:`door_detection.neck`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from door_contract.ranges import FieldRange, check_fields, check_in_range
from door_detection.errors import DetectionError

__all__ = ["Neck", "NeckAxis", "SearchStep", "View", "ViewSearch", "ViewSearchOptions", "head_move_time",
           "option_range", "pan_step_for", "plan_views"]


@dataclass(frozen=True)
class NeckAxis:
    """One neck joint: its URDF name, limits (rad) and speed limit (rad/s), and ``sign`` =
    joint angle per radian of look (+1 or −1: which way the joint turns the view left or down)."""

    joint: str
    lower: float
    upper: float
    sign: float
    velocity: float = math.inf

    def __post_init__(self) -> None:
        if not self.lower <= self.upper or self.sign not in (-1.0, 1.0) or not self.velocity > 0.0:
            raise DetectionError(f"neck joint {self.joint}: limits [{self.lower}, {self.upper}], sign "
                                 f"{self.sign} and speed {self.velocity} rad/s are not a joint")

    def joint_angle(self, look: float) -> float:
        """The joint angle of a look angle, clipped to the limits."""
        return min(max(self.sign * look, self.lower), self.upper)

    def look(self, joint_angle: float) -> float:
        """The look angle of a joint angle."""
        return self.sign * joint_angle

    def look_range(self) -> tuple[float, float]:
        """Smallest and largest look angle the limits allow."""
        ends = sorted((self.look(self.lower), self.look(self.upper)))
        return ends[0], ends[1]


@dataclass(frozen=True)
class Neck:
    """The neck's pan (look left) and tilt (look down) joints; either may be missing."""

    pan: NeckAxis | None
    tilt: NeckAxis | None


@dataclass(frozen=True)
class View:
    """Where to look: ``pan`` (rad, left), ``tilt`` (rad, down) and ``body_yaw`` (rad, left of
    the start heading; a turn in place)."""

    pan: float
    tilt: float
    body_yaw: float = 0.0

    def joint_targets(self, neck: Neck) -> dict[str, float]:
        """Neck joint targets (rad, within limits) of this view."""
        targets = {}
        if neck.pan is not None:
            targets[neck.pan.joint] = neck.pan.joint_angle(self.pan)
        if neck.tilt is not None:
            targets[neck.tilt.joint] = neck.tilt.joint_angle(self.tilt)
        return targets


def head_move_time(neck: Neck, start: View, end: View) -> float:
    """Shortest time (s) for the neck to go from ``start`` to ``end`` at its joints' speed
    limits: max over joints of |Δq|/q̇_max (a joint trajectory must not be faster)."""
    times = [abs(axis.joint_angle(b) - axis.joint_angle(a)) / axis.velocity
             for axis, a, b in ((neck.pan, start.pan, end.pan), (neck.tilt, start.tilt, end.tilt)) if axis is not None]
    return max(times, default=0.0)


@dataclass(frozen=True)
class ViewSearchOptions:
    """How the search looks around; validated on construction."""

    empty_frames_per_view: int = 2
    """Frames without any door estimate after which a view is left (head settled), [1, 100]:
    the door is not (wholly) in it."""
    frames_per_view: int = 10
    """Frames after which a view is left when its estimates never confirm a door, [1, 100].
    Two agreeing frames confirm a clear door (``DetectionOptions.vote_min_agreeing``); noisy
    depth takes more, up to the vote's window of 10."""
    pan_step: float = 0.3
    """Between neighbouring pans (rad), (0, π]. The graph's head camera sees 1.31 rad across
    (640 px, f = 416 px); a 1.00 m door and its 6 cm jambs 1 m away span 1.02 rad, so 0.3 rad
    steps keep a view with the whole door (:func:`pan_step_for`; 0.45 rad missed it there)."""
    max_pan: float = 1.2
    """Largest pan used (rad), [0, π] (TALOS's neck: ±1.31 rad)."""
    tilt_offsets: tuple[float, ...] = (0.3,)
    """Tilts tried after the home tilt's sweep, as offsets from it (rad, > 0 down): a near door's
    handle below the view."""
    body_turn_step: float = 0.8
    """Body turn in place between sweeps once the head's sweeps are done (rad), (0, π]."""
    max_body_turns: int = 2
    """Body turns tried each way (left first), [0, 4]."""

    def __post_init__(self) -> None:
        check_fields(self, _VIEW_SEARCH_RANGES, DetectionError, integers=_VIEW_SEARCH_COUNTS)
        for offset in self.tilt_offsets:
            check_in_range("tilt_offsets", offset, TILT_OFFSET_RANGE, DetectionError)


_VIEW_SEARCH_RANGES = {
    "empty_frames_per_view": FieldRange(1, 100, "frames"), "frames_per_view": FieldRange(1, 100, "frames"),
    "max_body_turns": FieldRange(0, 4, "turns"), "pan_step": FieldRange(1e-3, math.pi, "rad"),
    "max_pan": FieldRange(0.0, math.pi, "rad"), "body_turn_step": FieldRange(1e-3, math.pi, "rad"),
}
"""The interval of every numeric :class:`ViewSearchOptions` field."""
_VIEW_SEARCH_COUNTS = ("empty_frames_per_view", "frames_per_view", "max_body_turns")
TILT_OFFSET_RANGE = FieldRange(-math.pi / 2, math.pi / 2, "rad")
"""Each of :attr:`ViewSearchOptions.tilt_offsets`."""


def option_range(name: str) -> FieldRange:
    """The allowed interval of :class:`ViewSearchOptions` field ``name``: what a node parameter
    configuring that option takes as its range."""
    return _VIEW_SEARCH_RANGES[name]


def pan_step_for(horizontal_fov: float, door_span: float) -> float:
    """The largest pan step (rad) that keeps a door of angular span ``door_span`` (rad) whole in
    some view of a camera seeing ``horizontal_fov`` (rad) across: FOV − span (two views a step
    apart together see every door position within it whole)."""
    if not 0.0 < door_span < horizontal_fov:
        raise DetectionError(f"a door spanning {door_span:.2f} rad never fits a {horizontal_fov:.2f} rad view")
    return horizontal_fov - door_span


def _pans(neck: Neck, options: ViewSearchOptions, home_pan: float) -> list[float]:
    if neck.pan is None:
        return [home_pan]
    low, high = neck.pan.look_range()
    low, high = max(low, -options.max_pan), min(high, options.max_pan)
    pans = [home_pan]
    for k in range(1, int(2 * options.max_pan / options.pan_step) + 2):
        for sign in (1.0, -1.0):
            pan = home_pan + sign * k * options.pan_step
            if low - 1e-9 <= pan <= high + 1e-9:
                pans.append(pan)
    return pans


def plan_views(neck: Neck, home: View, options: ViewSearchOptions | None = None) -> tuple[View, ...]:
    """Every view of the search, in order (see the module docstring); ``home`` first."""
    opts = options if options is not None else ViewSearchOptions()
    pans = _pans(neck, opts, home.pan)
    views = [View(pan, home.tilt, home.body_yaw) for pan in pans]
    if neck.tilt is not None:
        low, high = neck.tilt.look_range()
        for offset in opts.tilt_offsets:
            tilt = min(max(home.tilt + offset, low), high)
            if abs(tilt - home.tilt) > 1e-6:
                views += [View(pan, tilt, home.body_yaw) for pan in pans]
    for k in range(1, opts.max_body_turns + 1):
        for sign in (1.0, -1.0):
            yaw = home.body_yaw + sign * k * opts.body_turn_step
            views += [View(pan, home.tilt, yaw) for pan in pans]
    return tuple(views)


class SearchStep(Enum):
    """What the caller does after a frame: keep looking, move to the next view, stop."""

    STAY = "stay"
    MOVE = "move"
    CONFIRMED = "confirmed"
    EXHAUSTED = "exhausted"


class ViewSearch:
    """Steps through planned views: after each frame taken at the current view (head settled),
    :meth:`after_frame` says whether to stay, move to :attr:`view`, or stop."""

    def __init__(self, views: tuple[View, ...], options: ViewSearchOptions | None = None) -> None:
        if not views:
            raise DetectionError("a view search needs at least one view")
        self._views = views
        self._options = options if options is not None else ViewSearchOptions()
        self._index = 0
        self._frames = self._empty = 0

    @property
    def view(self) -> View | None:
        """The view to look from now (None once exhausted)."""
        return self._views[self._index] if self._index < len(self._views) else None

    @property
    def index(self) -> int:
        return self._index

    def after_frame(self, detected: bool, confirmed: bool) -> SearchStep:
        """Count a frame at the current view: ``detected``, it gave a door estimate;
        ``confirmed``, the vote (over every view's frames) now has a door."""
        if confirmed:
            return SearchStep.CONFIRMED
        if self.view is None:
            return SearchStep.EXHAUSTED
        self._frames += 1
        self._empty += 0 if detected else 1
        if self._empty < self._options.empty_frames_per_view and self._frames < self._options.frames_per_view:
            return SearchStep.STAY
        self._index, self._frames, self._empty = self._index + 1, 0, 0
        return SearchStep.MOVE if self.view is not None else SearchStep.EXHAUSTED
