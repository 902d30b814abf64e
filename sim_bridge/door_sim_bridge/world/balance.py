"""The physical robot's low-level control loop, as the simulated hardware runs it.

Before every physics step it measures (sole poses, the centre of pressure on the floor, the
door's forces on the robot), lets the walking controller compute joint targets (legs from
balance, upper body from the commands) and sends them to the position motors. After the
step it checks for a fall; a fallen robot's motors go slack and stay so.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.vocabulary import Foot, Side
from door_sim_bridge.walking.controller import BalanceMode, Measurement, WalkingController
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import WorldConfig
from door_sim_bridge.world.hardware import (
    centre_of_mass_motion,
    centre_of_pressure,
    contact_forces,
    fall_reason,
    net_wrench,
)
from door_sim_bridge.world.robot import SimRobot

__all__ = ["BalanceLoop"]

FOOT_OF_SIDE = {Side.LEFT: Foot.LEFT, Side.RIGHT: Foot.RIGHT}


class BalanceLoop:
    """Walking controller + sensors + motors of the physical robot (one per world)."""

    def __init__(self, client: PhysicsClient, robot: SimRobot, floor: int, door_body: int,
                 config: WorldConfig, holding: Callable[[Side], bool], leaf_closed: Callable[[], bool]) -> None:
        self._client, self._robot, self._floor, self._door = client, robot, floor, door_body
        self._config, self._holding, self._leaf_closed = config, holding, leaf_closed
        self.controller = WalkingController(robot.urdf_text, robot.profile, config.gait, config.stabilizer,
                                            config.time_step)
        self.fall: str | None = None
        self.controller.start(robot.joint_positions(), robot.base_pose())

    # ------------------------------------------------------------------ per physics step
    def measure(self) -> Measurement:
        soles = {FOOT_OF_SIDE[side]: self._robot.link_pose(link) for side, link in self._robot.profile.feet.items()}
        # the CoM's motion feeds only the walking DCM feedback: not measured standing
        walking = self.controller.mode is BalanceMode.WALKING
        centre_of_mass = (centre_of_mass_motion(self._client, self._robot.body, self._robot.link_masses)
                          if walking else None)
        return Measurement(soles, centre_of_pressure(self._client, self._robot.body, self._floor),
                           net_wrench(self._door_forces()), self._robot.base_pose()[:3, :3], centre_of_mass)

    def _door_forces(self) -> list[tuple[np.ndarray, np.ndarray]]:
        """Forces on the robot the stabiliser may lean against: every link's contacts with the
        door's body but the hands'; a hand's wrist sensor (at the TCP) while it holds the
        handle, or while walking with the hand on the door (the blocking hand on the leaf, the
        fingers pushing a leaf open).

        Nor, standing, a hand holding the handle of a closed leaf (turning it): the arm's joints
        are held relative to the pelvis, so a lean drags the hand and presses it harder against
        the lever; at the end of a pull door's turn the force rose, the robot leant towards it,
        and the pelvis ran 10 cm towards the door in 1.5 s (the lean's clip, 100 N, stopped it;
        the turn failed). A closed leaf holds no more than its lever's spring.

        Not a hand pressing a latched door while standing: leaning against it presses the
        hand harder, the force grows, the lean with it (seen: 118 N and a 10 cm lean off a
        mis-placed approach). The CoP feedback still catches what that leaves out. Nor a hand
        in the air while walking: its sensor then reads the hand's inertia (20-40 N at each
        landing), and leaning against that tipped the robot forward past the doorway.
        """
        hands = {side: self._robot.hand_links(side) for side in self._robot.profile.arms}
        every_hand = set().union(*hands.values())
        contacts = contact_forces(self._client, self._robot.body, self._door)
        body = [(force, point) for link, force, point in contacts if link not in every_hand]
        touching = {side for side, links in hands.items() if any(link in links for link, _, _ in contacts)}
        gravity, walking = self._config.gravity, self.walking
        return body + [(self._robot.wrist_force(side, gravity), self._robot.tcp_pose(side)[:3, 3])
                       for side in hands if (walking and side in touching)
                       or (self._holding(side) and (walking or not self._leaf_closed()))]

    def control(self) -> None:
        """Set this step's joint targets (nothing once fallen)."""
        if self.fall is None:
            self._robot.set_joint_targets(self.controller.tick(self.measure()))

    def check_fall(self) -> str | None:
        """After a step: the reason when the robot has just fallen (once), else None; it says
        when the last walk was knocked off its pattern, if it was (a blow, rather than a drift)."""
        if self.fall is not None:
            return None
        reason = fall_reason(self._robot.base_pose(), self._robot.profile.base_height, self._config.fall)
        if reason is not None:
            departure = self.controller.pattern_departure
            self.fall = reason if departure is None else f"{reason}; {departure}"
            self._robot.go_limp()
        return self.fall

    # ------------------------------------------------------------------ commands
    def set_upper_body(self, targets: Mapping[str, float]) -> None:
        self.controller.set_upper_body(targets)

    def walk(self, steps: Sequence[FootPlacement], crouch: float = 0.0) -> float:
        """Start walking ``steps``, the pelvis ``crouch`` m below its standing height; the walk's
        duration in s (0: nothing to walk)."""
        return self.controller.walk(steps, self.measure().soles, crouch)

    def stop_walking(self) -> None:
        self.controller.stop()

    @property
    def walking(self) -> bool:
        """Stepping, or settling over the feet after the last step (a plan made from the
        pose while settling would miss by the settling motion, up to ~10 cm)."""
        return self.controller.mode is BalanceMode.WALKING or self.controller.settling

    def centre_of_mass(self) -> np.ndarray:
        """The controller model's CoM (odom, m)."""
        return np.array(self.controller.robot.com_world())
