"""Grasping the lever handle: a fixed constraint between hand and handle, and slipping.

Closing a hand attaches it only when its TCP is within ``grasp_distance`` of the handle's
grasp point (position only, as the DRC teams' compliant hands tolerated orientation errors).
The constraint is created at the hand's and handle's *current* relative pose, so it starts
without a jerk. It is the world's :class:`~door_sim_bridge.world.config.GraspModel`: a point
the hand may turn about (compliant, the default) or a slider locked in orientation (rigid). PyBullet expresses constraint frames relative to each link's centre of mass,
not its URDF frame: both frames are computed from the links' centre-of-mass poses.

Each physics step the constraint's reaction force is read (``getConstraintState``: the solver's
impulse over the step, in N); a force above ``grasp_break_force`` for ``grasp_break_steps``
consecutive steps removes the constraint and records a slip — the paper's failure mode where
the hand slides off the lever. The hand links never collide with the handle (the lever lies
between the fingers); they still collide with the leaf.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pybullet

from door_contract.vocabulary import Side
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import GraspModel
from door_sim_bridge.world.door import DoorPart, SimDoor
from door_sim_bridge.world.robot import SimRobot
from door_sim_bridge.world.transforms import invert, position_quaternion

__all__ = ["GraspController", "GraspResult"]

SOLVER_FORCE_MARGIN = 5.0
"""The constraint's own force cap, × the break force, so the solver never saturates first."""


@dataclass(frozen=True)
class GraspResult:
    """Outcome of a close/open request: success, TCP-to-grasp-point distance (m) and why."""

    success: bool
    distance_m: float
    message: str


@dataclass
class _HandState:
    """Mutable per-hand bookkeeping of the grasp controller (private)."""

    constraint: int | None = None
    over_limit_steps: int = 0
    slipped: bool = False
    peak_force: float = 0.0


class GraspController:
    """Attaches and releases the hands, and detects slips."""

    def __init__(self, client: PhysicsClient, robot: SimRobot, door: SimDoor, grasp_distance: float,
                 break_force: float, break_steps: int, model: GraspModel = GraspModel.COMPLIANT) -> None:
        self._client = client
        self._robot = robot
        self._door = door
        self._distance = grasp_distance
        self._break_force = break_force
        self._break_steps = break_steps
        self._model = model
        self._hands = {side: _HandState() for side in robot.profile.arms}
        self._disable_hand_handle_collisions()

    def _disable_hand_handle_collisions(self) -> None:
        handle = self._door.link_index(DoorPart.HANDLE)
        for side in self._hands:
            for link in self._robot.hand_links(side):
                self._client.setCollisionFilterPair(self._robot.body, self._door.body, link, handle, 0)

    # ------------------------------------------------------------------ requests
    def distance(self, side: Side) -> float:
        """Distance (m) from the ``side`` TCP to the handle grasp point."""
        tcp = self._robot.tcp_pose(side)[:3, 3]
        return float(np.linalg.norm(tcp - self._door.handle_grasp_pose()[:3, 3]))

    def close(self, side: Side) -> GraspResult:
        """Attach the ``side`` hand to the handle if its TCP is within the grasp distance."""
        distance = self.distance(side)
        hand = self._hands[side]
        if hand.constraint is not None:
            return GraspResult(True, distance, f"{side.value} hand already holds the handle")
        if distance > self._distance:
            return GraspResult(False, distance, f"{side.value} hand is {distance:.3f} m from the handle "
                                                f"grasp point (closing needs ≤ {self._distance:.3f} m)")
        hand.constraint = self._attach(side)
        hand.over_limit_steps, hand.slipped, hand.peak_force = 0, False, 0.0
        return GraspResult(True, distance, f"{side.value} hand closed on the handle at {distance:.3f} m")

    def open(self, side: Side) -> GraspResult:
        """Release the ``side`` hand (success also when it held nothing)."""
        hand = self._hands[side]
        distance = self.distance(side)
        if hand.constraint is None:
            return GraspResult(True, distance, f"{side.value} hand was already open")
        self._client.removeConstraint(hand.constraint)
        hand.constraint = None
        return GraspResult(True, distance, f"{side.value} hand opened")

    def _attach(self, side: Side) -> int:
        """Constraint at the TCP, expressed in both links' centre-of-mass frames.

        Compliant (:attr:`GraspModel.COMPLIANT`): a point-to-point constraint, the TCP held
        at its point on the lever in all three directions and free to turn about it; forces
        pass, torques do not. The motion library plans the closed chain of turn and swing
        on the *estimated* lever axis and hinge: with the estimate 1 cm or 1.5° off, the hand's
        planned orientation drifts from the lever's by a few degrees over the turn, and a
        rigid grip made the wrist fight the lever (held 0.1-0.25 rad off its goal: the motion
        failed in 7 of 10 rig doors opened sideways, 5 of 10 facing). Padded, underactuated
        fingers give way there; the wrist then follows its plan.

        Rigid (:attr:`GraspModel.RIGID`): fingers locked on the bar in every direction but
        one, the bar sliding along its length inside the hand (the TCP's x axis, along the
        lever when the hand grasps as the motion library places it): a prismatic constraint.
        """
        hand_link = self._robot.link_index(self._robot.profile.arm(side).tcp_parent_frame)
        handle_link = self._door.link_index(DoorPart.HANDLE)
        joint_frame = self._robot.tcp_pose(side)
        hand_com = self._robot.link_com_pose(hand_link)
        handle_com = self._door.link_com_pose(DoorPart.HANDLE)
        parent_position, parent_orientation = position_quaternion(invert(hand_com) @ joint_frame)
        child_position, child_orientation = position_quaternion(invert(handle_com) @ joint_frame)
        kind = pybullet.JOINT_POINT2POINT if self._model is GraspModel.COMPLIANT else pybullet.JOINT_PRISMATIC
        constraint: int = self._client.createConstraint(
            self._robot.body, hand_link, self._door.body, handle_link, kind,
            [1.0, 0.0, 0.0], parent_position, child_position, parent_orientation, child_orientation)
        self._client.changeConstraint(constraint, maxForce=SOLVER_FORCE_MARGIN * self._break_force)
        return constraint

    # ------------------------------------------------------------------ per physics step
    def check_slips(self) -> list[Side]:
        """After a physics step: release every hand whose grasp force stayed over the limit."""
        slipped = []
        for side, hand in self._hands.items():
            if hand.constraint is None:
                continue
            force = self.constraint_force(side)
            hand.peak_force = max(hand.peak_force, force)
            hand.over_limit_steps = hand.over_limit_steps + 1 if force > self._break_force else 0
            if hand.over_limit_steps >= self._break_steps:
                self._client.removeConstraint(hand.constraint)
                hand.constraint, hand.slipped = None, True
                slipped.append(side)
        return slipped

    def constraint_force(self, side: Side) -> float:
        """Magnitude (N) of the linear reaction force of the ``side`` grasp (0 when open)."""
        constraint = self._hands[side].constraint
        if constraint is None:
            return 0.0
        forces = self._client.getConstraintState(constraint)
        return float(np.linalg.norm(forces[:3]))

    def peak_force(self, side: Side) -> float:
        """Largest reaction force (N) of the ``side`` grasp since it was last closed."""
        return self._hands[side].peak_force

    def holding(self, side: Side) -> bool:
        return self._hands[side].constraint is not None

    def slipped(self, side: Side) -> bool:
        """True when the last grasp of ``side`` ended in a slip (reset by the next close)."""
        return self._hands[side].slipped
