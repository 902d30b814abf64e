"""What the physical robot's sensors would report: foot contacts, door forces, falls.

* **Centre of pressure** of the soles on the floor: the normal-force-weighted mean of the
  contact points (the measured ZMP on flat ground).
* **External wrench** from the door: every contact between a robot link and the door's body
  (leaf, frame, handle), normal and friction forces, plus the hands' wrist force sensors. Summed into one force and a force-weighted point of application — what the
  stabiliser feeds forward (:mod:`door_sim_bridge.walking.stabilizer`).
* **Centre of mass** of the whole robot and its velocity: the mass-weighted mean of the links'
  inertial frames (what a state estimator gives a real robot's DCM feedback).
* **Sole contact**: the floor's normal force on one sole and how deep the sole has sunk into
  the floor (a rigid floor that lets a sole sink centimetres is a constraint solver short of
  convergence: the lift-off dip of issue #11).
* **Falls**: the base below a fraction of its nominal height, or tilted too far.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import pybullet

from door_sim_bridge.walking.dcm import CentreOfMassMotion
from door_sim_bridge.walking.stabilizer import ContactWrench
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import FallConfig

__all__ = ["SoleContact", "centre_of_mass_motion", "centre_of_pressure", "contact_forces", "fall_reason", "floor_links",
           "make_floor", "net_wrench", "sole_contact", "tilt"]

MIN_SUPPORT_FORCE = 1.0  # N of floor contact below which the robot is in the air


def make_floor(client: PhysicsClient, friction: float) -> int:
    """An infinite static plane z = 0 that collides, and is invisible: the scene's floor is
    visual only and carries the floor colour. (PyBullet draws a body without a visual shape
    by its collision shape, a plane in a checker texture, which would cover that colour.)"""
    shape = client.createCollisionShape(pybullet.GEOM_PLANE)
    floor: int = client.createMultiBody(0.0, shape)
    client.changeDynamics(floor, -1, lateralFriction=friction)
    client.changeVisualShape(floor, -1, rgbaColor=[0.5, 0.5, 0.5, 0.0])  # alpha 0: not drawn
    return floor


def centre_of_pressure(client: PhysicsClient, robot: int, floor: int) -> np.ndarray | None:
    """(x, y) of the robot's floor contacts, weighted by normal force; None in the air."""
    contacts = client.getContactPoints(bodyA=robot, bodyB=floor)
    total = sum(contact[9] for contact in contacts)
    if total < MIN_SUPPORT_FORCE:
        return None
    centre: np.ndarray = sum(contact[9] * np.array(contact[5][:2]) for contact in contacts) / total
    return centre


def centre_of_mass_motion(client: PhysicsClient, robot: int, masses: np.ndarray) -> CentreOfMassMotion:
    """The robot's CoM (odom, m) and velocity (m/s) from its link ``masses`` (kg, the base's
    first, then by link index) and the positions and velocities of the links' inertial frames."""
    links = range(client.getNumJoints(robot))
    position, _ = client.getBasePositionAndOrientation(robot)
    velocity, _ = client.getBaseVelocity(robot)
    positions, velocities = [np.array(position)], [np.array(velocity)]
    for state in client.getLinkStates(robot, list(links), computeLinkVelocity=1):
        positions.append(np.array(state[0]))
        velocities.append(np.array(state[6]))
    total = float(masses.sum())
    return CentreOfMassMotion(masses @ np.array(positions) / total, masses @ np.array(velocities) / total)


@dataclass(frozen=True)
class SoleContact:
    """The floor under one sole."""

    load: float  # N, sum of the normal forces
    sinking: float  # m, the deepest penetration of the sole into the floor (0: on or above it)
    points: int  # contact points


def sole_contact(client: PhysicsClient, robot: int, floor: int, link: int) -> SoleContact:
    """The floor's contact with ``link`` (a sole's carrier link): PyBullet's contact distance
    is negative where the bodies overlap."""
    contacts = client.getContactPoints(bodyA=robot, bodyB=floor, linkIndexA=link)
    depth = min((contact[8] for contact in contacts), default=0.0)
    return SoleContact(float(sum(contact[9] for contact in contacts)), float(max(0.0, -depth)), len(contacts))


def floor_links(client: PhysicsClient, robot: int, floor: int) -> set[int]:
    """Links of the robot touching the floor."""
    return {contact[3] for contact in client.getContactPoints(bodyA=robot, bodyB=floor)}


def contact_forces(client: PhysicsClient, robot: int, other: int) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """(robot link, force on the robot, point) of every contact between ``robot`` and ``other``.

    PyBullet's contact normal is on B pointing towards A (the robot), so the normal force
    pushes the robot along it; the two friction forces act along their directions on A.
    """
    forces = []
    for contact in client.getContactPoints(bodyA=robot, bodyB=other):
        force = (contact[9] * np.array(contact[7]) + contact[10] * np.array(contact[11])
                 + contact[12] * np.array(contact[13]))
        forces.append((contact[3], force, np.array(contact[5])))
    return forces


def net_wrench(forces: Iterable[tuple[np.ndarray, np.ndarray]]) -> ContactWrench:
    """One force and its force-weighted point of application (the moment about that point is
    dropped: what the static feed-forward needs is the force and roughly where it acts)."""
    items = [(np.asarray(f, dtype=float), np.asarray(p, dtype=float)) for f, p in forces]
    if not items:
        return ContactWrench.none()
    total = sum((force for force, _ in items), np.zeros_like(items[0][0]))
    weights = np.array([np.linalg.norm(force) for force, _ in items])
    if weights.sum() < 1e-9:
        return ContactWrench.none()
    point = sum(w * p for w, (_, p) in zip(weights, items)) / weights.sum()
    return ContactWrench(total, point)


def tilt(base_pose: np.ndarray) -> float:
    """Angle (rad) between the base's z axis and the vertical."""
    return math.acos(min(1.0, max(-1.0, float(base_pose[2, 2]))))


def fall_reason(base_pose: np.ndarray, nominal_height: float, options: FallConfig) -> str | None:
    """Why the robot counts as fallen, or None."""
    height = float(base_pose[2, 3])
    if height < options.height_fraction * nominal_height:
        return f"base at {height:.2f} m (below {options.height_fraction:g} × {nominal_height:.2f} m)"
    if tilt(base_pose) > options.max_tilt:
        return f"base tilted {math.degrees(tilt(base_pose)):.0f}° (more than {math.degrees(options.max_tilt):.0f}°)"
    return None
