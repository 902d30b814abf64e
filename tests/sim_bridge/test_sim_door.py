"""The door's physics: latch, handle, closer spring, wind; ground truth and forces."""

import numpy as np
import pytest

from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world import DoorConfig, DoorPart, DoorWorld, EventKind, WindConfig, WorldConfig

PUSH_FORCE = 100.0  # N
SECOND = 240  # physics steps at the default rate


def _opening_force(world: DoorWorld) -> np.ndarray:
    """100 N along the door's opening direction (push: away from the robot, pull: towards it)."""
    normal_towards_robot = world.handle_grasp_pose()[:3, 0]
    sign = -1.0 if world.config.door.opening is DoorOpening.PUSH else 1.0
    return sign * PUSH_FORCE * normal_towards_robot


def _turn_handle(world: DoorWorld, steps: int) -> None:
    """Press the lever down with 40 N at the grasp point (~2.6 N·m, past the return spring)."""
    world.apply_door_force([0.0, 0.0, -40.0], world.handle_grasp_pose()[:3, 3], DoorPart.HANDLE, steps)


@pytest.mark.parametrize("opening", list(DoorOpening))
@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_latch_handle_and_closer_cycle(opening, hinge_side):
    with DoorWorld(WorldConfig(door=DoorConfig(opening=opening, hinge_side=hinge_side))) as world:
        grasp_point = world.handle_grasp_pose()[:3, 3]
        # latched: a 100 N push at the handle for 1 s does not open it
        world.apply_door_force(_opening_force(world), grasp_point, DoorPart.LEAF, SECOND)
        world.step(SECOND)
        state = world.door_state()
        assert state.latched and state.hinge_angle < np.radians(1.0)
        # handle turned past 30 deg, then the same push opens it beyond 10 deg
        _turn_handle(world, SECOND // 2)
        world.step(SECOND // 4)
        assert world.door_state().handle_angle > world.config.door.latch_release_angle
        assert not world.door_state().latched
        world.apply_door_force(_opening_force(world), grasp_point, DoorPart.LEAF, SECOND // 4)
        world.step(SECOND // 2)
        assert world.door_state().hinge_angle > np.radians(10.0)
        # released: the closer brings it back within 2 deg and the latch catches
        world.step(4 * SECOND)
        state = world.door_state()
        assert state.latched and state.hinge_angle < np.radians(2.0)
        assert state.handle_angle < 0.05
        kinds = [event.kind for event in world.events()]
        assert kinds == [EventKind.LATCH_RELEASED, EventKind.LATCH_ENGAGED]


def test_handle_returns_and_door_stays_latched_without_a_turn():
    with DoorWorld() as world:
        world.apply_door_force([0.0, 0.0, -10.0], world.handle_grasp_pose()[:3, 3], DoorPart.HANDLE, SECOND)
        world.step(SECOND)
        pressed = world.door_state().handle_angle
        assert 0.0 < pressed < world.config.door.latch_release_angle  # 0.66 N·m: not far enough
        world.step(SECOND)
        assert world.door_state().handle_angle < 0.01 and world.door_state().latched


def test_ground_truth_follows_the_leaf():
    with DoorWorld() as world:
        truth = world.door_ground_truth()
        np.testing.assert_allclose(truth.normal, [-1.0, 0.0, 0.0], atol=1e-9)
        np.testing.assert_allclose(truth.corners[:, 0], 0.0, atol=1e-9)
        width = np.linalg.norm(truth.corners[1] - truth.corners[0])
        assert width == pytest.approx(0.914)
        grasp = world.handle_grasp_pose()
        assert grasp[2, 3] == pytest.approx(0.91)
        np.testing.assert_allclose(grasp[:3, 0], truth.normal, atol=1e-9)
        np.testing.assert_allclose(grasp[:3, 2], [0.0, 0.0, 1.0], atol=1e-9)
        # the lever points towards the hinge (+y for a left-hinged door), the grasp point lies on it
        assert grasp[1, 3] > truth.corners[1, 1]
        _turn_handle(world, SECOND)
        world.apply_door_force(_opening_force(world), grasp[:3, 3], DoorPart.LEAF, SECOND // 2)
        world.step(SECOND // 2)
        angle = world.door_state().hinge_angle
        opened = world.door_ground_truth()
        expected_normal = [-np.cos(angle), -np.sin(angle), 0.0]  # left-hinged push door
        np.testing.assert_allclose(opened.normal, expected_normal, atol=1e-6)
        np.testing.assert_allclose(opened.hinge_point, truth.hinge_point, atol=1e-6)


def test_wind_opens_an_unlatched_door_reproducibly():
    def run(seed: int) -> float:
        wind = WindConfig(amplitude=3.0, frequency=0.5, bias=4.0)
        config = WorldConfig(door=DoorConfig(wind=wind, latch_release_angle=0.1), seed=seed)
        with DoorWorld(config) as world:
            _turn_handle(world, 2 * SECOND)
            world.step(2 * SECOND)
            return world.door_state().hinge_angle

    first = run(3)
    assert first > 0.05
    assert run(3) == first
    assert run(4) != first


def test_door_force_is_validated():
    with DoorWorld() as world:
        with pytest.raises(SimulationError):
            world.apply_door_force([np.nan, 0.0, 0.0], [0.0, 0.0, 1.0])
        with pytest.raises(SimulationError):
            world.apply_door_force([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], steps=0)
