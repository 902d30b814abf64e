"""How low the robot walks: the pelvis below its standing height, per walk, from the door.

The walker takes a crouch per walk (:meth:`~door_sim_bridge.walking.controller.WalkingController.walk`:
the CoM goes to the new height over the walk's first double support and stays there standing
after it). A profile asks for it in three ways, the lowest winning (:class:`CrouchRules`):

* ``opening_crouch``: every walk (a tall robot, Atlas v4, whose shoulders are far above any lever);
* ``push_passage_crouch`` (:class:`PassageCrouch`): the walk through a push door whose lever
  would ride in the notch between pelvis and torso (through a narrow one, a rise instead: a
  negative crouch, the pelvis *above* its standing height, when no other rule crouches);
* ``low_lever_crouch`` (:class:`LowLeverCrouch`): the walk to a door whose lever is below the
  arm's upright reach, so that the arm opens it without twisting and bending the torso.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from door_contract.vocabulary import DoorOpening, WalkGoal
from door_robot.errors import RobotModelError

__all__ = ["MAX_CROUCH", "MAX_RISE", "PASSAGE_WALKS", "CrouchRules", "LowLeverCrouch", "PassageCrouch", "crouch_problem",
           "walking_height"]

MAX_CROUCH = 0.15
"""m the pelvis may go below its standing height in a walk: the most a profile may ask for and
the walker takes (TALOS's knees bend 0.34 rad more for 0.10 m)."""
MAX_RISE = 0.04
"""m the pelvis may go above its standing height in a walk (a crouch of −MAX_RISE): TALOS stands
with its knees bent 0.86 rad and walked 0.04 m higher through narrow push doors (17 of 19 on the
passage rig, stop 42); 0.06 m higher it fell in all 3 passages tried, 5.6–40 s into the walk."""


def crouch_problem(crouch: object) -> str:
    """Why ``crouch`` (m below the standing height; negative: above) cannot be walked, or "":
    a finite number within [−MAX_RISE, MAX_CROUCH]."""
    if not isinstance(crouch, (int, float)) or isinstance(crouch, bool) or not math.isfinite(crouch):
        return f"crouch {crouch!r} is not a finite number of metres"
    if not -MAX_RISE <= crouch <= MAX_CROUCH:
        return f"crouch {crouch:.3f} m is outside [{-MAX_RISE}, {MAX_CROUCH}] m (negative: above the standing height)"
    return ""


def walking_height(crouch: float) -> str:
    """``crouch`` in words for a log line: "0.040 m above the standing height"."""
    return f"{abs(crouch):.3f} m {'below' if crouch >= 0.0 else 'above'} the standing height"


PASSAGE_WALKS = frozenset({WalkGoal.DOORWAY, WalkGoal.THROUGH})
"""The walks of a passage: a push door's lever rides along the back in both."""


@dataclass(frozen=True)
class PassageCrouch:
    """How low the robot walks through a push door whose lever meets its pelvis.

    Passing a push door sideways, the robot's back holds the leaf open, and the lever on the
    leaf's near side rides along the back. At TALOS's walking height a lever at 1.00–1.04 m
    lies in the notch between the pelvis's collision hull (its top 3.5 cm above the base) and
    the torso's, and the pelvis, rising ~1 cm at each step, lifts it against its stop: 1–7 kN,
    and the robot falls. Walking ``crouch`` m lower puts the notch below such a lever, which
    then slides on the torso's back. Measured on the passage rig (stop 36, walked from 2.5 m,
    the detector's error): four such doors 0.91–0.97 m wide passed 2 of 16 times upright, 13 of
    16 at 0.08 m; two narrower ones (0.81, 0.85 m) 7 of 8 upright and 2 of 8 at 0.08 m — doors
    narrower than ``min_door_width`` are not crouched through (the knees reach forward into the
    closing leaf and the posts).

    Through those narrow doors the robot walks ``narrow_rise`` m *higher* instead when the lever
    is at most ``narrow_rise_top``: the notch rises above the lever, which slides on the pelvis's
    back. Upright, the lever hooked the pelvis as the body swayed back at a side-step and dragged
    the leaf to its stop: narrow push doors hinged left went through 9 of 18 times, and 0 of 3 at
    0.86 m with a 1.00 m lever (stop 41; the right hinge's 12 of 12 is luck of the sway's phase).
    0.04 m higher (stop 42, walked from 2.5 m, the detector's error): 0.86 m / 1.00 m 3 of 3 per
    hinge, 0.82 m / 1.02 m 3 of 3 (upright 2 of 3) — but 0.855 m / 1.035 m 0 of 3 (upright 2 of
    3): a lever that high meets the risen notch, hence ``narrow_rise_top``.
    """

    lever_heights: tuple[float, float]  # m above the floor: levers in this band meet the notch
    crouch: float  # m below the standing height, for such doors
    min_door_width: float = 0.0  # m: narrower leaves are not crouched through
    narrow_rise: float = 0.0  # m above the standing height through a narrower leaf (0: upright)
    narrow_rise_top: float = 0.0  # m above the floor: the highest lever a narrower leaf is risen for

    def __post_init__(self) -> None:
        low, high = self.lever_heights
        if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
            raise RobotModelError(f"push_passage_crouch: lever_heights must be increasing positive metres, "
                                  f"got {self.lever_heights}")
        if not (math.isfinite(self.crouch) and 0.0 < self.crouch <= MAX_CROUCH):
            raise RobotModelError(f"push_passage_crouch: crouch must be within (0, {MAX_CROUCH}] m, got {self.crouch!r}")
        if not (math.isfinite(self.min_door_width) and self.min_door_width >= 0.0):
            raise RobotModelError(f"push_passage_crouch: min_door_width must be finite and ≥ 0 m, "
                                  f"got {self.min_door_width!r}")
        if not (math.isfinite(self.narrow_rise) and 0.0 <= self.narrow_rise <= MAX_RISE):
            raise RobotModelError(f"push_passage_crouch: narrow_rise must be within [0, {MAX_RISE}] m, "
                                  f"got {self.narrow_rise!r}")
        if self.narrow_rise > 0.0 and not low <= self.narrow_rise_top <= high:
            raise RobotModelError(f"push_passage_crouch: narrow_rise_top must be within lever_heights "
                                  f"{self.lever_heights}, got {self.narrow_rise_top!r}")

    def for_walk(self, goal: WalkGoal, opening: DoorOpening, lever_height: float, door_width: float) -> float:
        """The crouch (m) of a passage walk (:data:`PASSAGE_WALKS`: a wide door's walk to the
        doorway and the one on from there alike) through a push door whose lever (``lever_height``,
        m above the floor) is in the band: :attr:`crouch` when the leaf is at least
        :attr:`min_door_width` wide, −:attr:`narrow_rise` (a rise) when it is narrower and the
        lever at most :attr:`narrow_rise_top`; else 0 (upright)."""
        low, high = self.lever_heights
        if goal not in PASSAGE_WALKS or opening is not DoorOpening.PUSH or not low <= lever_height <= high:
            return 0.0
        if door_width >= self.min_door_width:
            return self.crouch
        return -self.narrow_rise if lever_height <= self.narrow_rise_top else 0.0


@dataclass(frozen=True)
class LowLeverCrouch:
    """How low the robot walks to a door whose lever is below the arm's upright reach.

    TALOS reaches a low lever by twisting and bending its torso (the approach's IK, posture
    cost and all): placed at the stand pose of a 0.90 m pull door hinged right, the torso is
    turned 0.76 rad towards a lever at 0.85 m and 0.33 rad towards one at 1.00 m, and after the
    turn and the pull of a 0.86 m lever it stood at (−0.85, +0.43) rad of yaw and pitch against
    (−0.10, −0.09) for a 0.95 m one. The joints both arms share stay where the opening left
    them while the other hand blocks a pull door (the block, the release, the walk to the
    doorway, the tuck): bent so, the head pushed the leaf to 1.75 rad in the doorway, the leaf
    came back onto the upper arm in the tuck (0.8–1.2 kN) and the robot fell in 3 of 6 passages
    of seed 10 trial 13's door (lever 0.86 m; 0 of 2 at 0.95 m). Six of the eight doors that
    failed in the Monte-Carlo campaigns of stops 37–39 had levers below 0.89 m (a sixth of the
    range), push and pull alike. Walking to such a door ``reach_height`` − lever lower puts the
    lever where the arm meets a ``reach_height`` lever upright: on the passage rig that door went
    through 3 of 3 times, the leaf touching only the grippers (≤ 143 N). Only the walk to the
    door is lowered: the passages' walks stand up again (crouched, the knees reach forward, and a
    sideways passage's depth is what meets the posts of a narrow door). ``openings`` says which
    doors: TALOS opens a push door standing sideways with its torso at its pitch limit whatever
    the lever's height, and crouched the grasp missed (2.0 cm off) in 3 of 5 push doors with
    levers at 0.86–0.87 m and one of the other two fell, where upright 2 of 2 went through.
    """

    reach_height: float  # m above the floor: the lowest lever the arm opens with the torso near upright
    max_crouch: float = MAX_CROUCH  # m: the most it crouches for a lever
    openings: frozenset[DoorOpening] = frozenset(DoorOpening)  # the doors it crouches to

    def __post_init__(self) -> None:
        if not (math.isfinite(self.reach_height) and self.reach_height > 0.0):
            raise RobotModelError(f"low_lever_crouch: reach_height must be a positive number of metres, "
                                  f"got {self.reach_height!r}")
        if not (math.isfinite(self.max_crouch) and 0.0 < self.max_crouch <= MAX_CROUCH):
            raise RobotModelError(f"low_lever_crouch: max_crouch must be within (0, {MAX_CROUCH}] m, "
                                  f"got {self.max_crouch!r}")
        if not self.openings:
            raise RobotModelError("low_lever_crouch: openings must name at least one of push, pull")

    def for_walk(self, goal: WalkGoal, opening: DoorOpening, lever_height: float) -> float:
        """The crouch (m) of a walk to ``goal``: reach_height − ``lever_height`` (m above the
        floor), within [0, max_crouch], for the walk to a door of one of :attr:`openings`
        (:attr:`WalkGoal.STAND`), else 0."""
        if goal is not WalkGoal.STAND or opening not in self.openings:
            return 0.0
        return min(self.max_crouch, max(0.0, self.reach_height - lever_height))


@dataclass(frozen=True)
class CrouchRules:
    """A robot's crouches (its profile's): the lowest of them is the walk's; a passage's rise
    (a negative crouch) only when none of them crouches."""

    opening: float = 0.0  # m below the standing height of every walk (``opening_crouch``)
    push_passage: PassageCrouch | None = None  # through a push door whose lever meets the pelvis
    low_lever: LowLeverCrouch | None = None  # to a door whose lever is below the arm's upright reach

    def __post_init__(self) -> None:
        if problem := crouch_problem(self.opening):
            raise RobotModelError(f"opening_crouch must be within [0, {MAX_CROUCH}] m: {problem}")

    def for_walk(self, goal: WalkGoal, opening: DoorOpening, door: tuple[float, float] | None) -> float:
        """How far below its standing height the pelvis walks to ``goal`` (m), for the door's
        (lever height, width) in m: :attr:`opening` alone when the door is not known."""
        if door is None:
            return self.opening
        lever_height, width = door
        passage = self.push_passage.for_walk(goal, opening, lever_height, width) if self.push_passage else 0.0
        low = self.low_lever.for_walk(goal, opening, lever_height) if self.low_lever else 0.0
        deepest = max(self.opening, passage, low)
        return deepest if deepest > 0.0 else passage  # no rule crouches: the passage's rise, or 0
