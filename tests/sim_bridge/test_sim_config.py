"""Configuration validation and the door's geometry convention (no physics)."""

import math

import numpy as np
import pytest

from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world import CameraConfig, DoorConfig, ExecutionConfig, StanceConfig, WindConfig, WorldConfig
from door_sim_bridge.world.door import DoorLayout, door_urdf


def test_defaults_are_the_drc_door_and_valid():
    config = WorldConfig()
    assert (config.door.width, config.door.height) == (0.914, 2.083)
    assert config.door.handle_height == 0.91 and config.door.lever_length == 0.11
    assert math.isclose(config.door.latch_release_angle, 0.52)
    assert config.stance.distance == 1.2 and config.physics_rate == 240.0
    assert (config.camera.width, config.camera.height, config.camera.vertical_fov_deg) == (640, 480, 60.0)
    assert config.camera.depth_noise_coefficient == 0.0 and config.camera.colour_noise_sigma == 0.0
    assert not config.door.wind.enabled
    assert config.grasp_distance == 0.02


@pytest.mark.parametrize("make, field, allowed", [
    (lambda: DoorConfig(width=0.2), "DoorConfig.width", "[0.5, 1.5] m"),
    (lambda: DoorConfig(closer_stiffness=float("nan")), "DoorConfig.closer_stiffness", "[0, 200]"),
    (lambda: DoorConfig(handle_height=2.0), "DoorConfig.handle_height", "m"),
    (lambda: DoorConfig(latch_release_angle=1.2), "DoorConfig.latch_release_angle", "rad"),
    (lambda: StanceConfig(distance=-1.0), "StanceConfig.distance", "[0.3, 8] m"),
    (lambda: CameraConfig(width=0), "CameraConfig.width", "[16, 4096]"),
    (lambda: CameraConfig(far=0.15), "CameraConfig.far", "m"),
    (lambda: WorldConfig(physics_rate=10.0), "WorldConfig.physics_rate", "[60, 2000] Hz"),
    (lambda: WorldConfig(seed=-1), "WorldConfig.seed", "[0, 2147483647]"),
    (lambda: WorldConfig(seed=1.5), "WorldConfig.seed", "integer"),
    (lambda: WorldConfig(solver_iterations=0), "WorldConfig.solver_iterations", "[1, 10000] sweeps"),
    (lambda: WorldConfig(solver_iterations=50.5), "WorldConfig.solver_iterations", "integer"),
    (lambda: WorldConfig(contact_solver="dantzig"), "WorldConfig.contact_solver", "sequential_impulse, dantzig"),
    (lambda: WindConfig(amplitude=-1.0), "WindConfig.amplitude", "[0, 100] N·m"),
    (lambda: ExecutionConfig(step_duration=0.0), "ExecutionConfig.step_duration", "s"),
    (lambda: DoorConfig(opening="push"), "DoorConfig.opening", "push, pull"),
])
def test_a_bad_value_names_the_field_and_its_range(make, field, allowed):
    with pytest.raises(SimulationError) as error:
        make()
    assert field in str(error.value) and allowed in str(error.value)
    assert not isinstance(error.value, ValueError)  # the package's own error, never a bug's ValueError


def test_any_scene_colours_are_accepted_and_only_unrenderable_ones_refused():
    """Alike colours render (a white leaf on a white wall, a dark-grey handle over a grey
    floor: scenes for the detector, not configuration errors); a colour outside RGB [0, 1]
    and a light without a direction cannot be rendered and are refused, naming the field."""
    white = DoorConfig(door_colour=(1.0, 1.0, 1.0), wall_colour=(1.0, 1.0, 1.0), frame_colour=(0.92, 0.92, 0.9),
                       handle_colour=(0.25, 0.25, 0.25), floor_colour=(0.3, 0.3, 0.3))
    assert white.door_colour == white.wall_colour
    with pytest.raises(SimulationError, match="DoorConfig.handle_colour"):
        DoorConfig(handle_colour=(1.2, 0.0, 0.0))
    with pytest.raises(SimulationError, match="DoorConfig.floor_colour"):
        DoorConfig(floor_colour=(0.3, 0.3))
    with pytest.raises(SimulationError, match="CameraConfig.light_direction .* no direction"):
        CameraConfig(light_direction=(0.0, 0.0, 0.0))
    with pytest.raises(SimulationError, match="CameraConfig.light_direction"):
        CameraConfig(light_direction=(1.0, float("nan"), 0.0))
    assert CameraConfig(light_direction=(0.0, -2.0, 1.0)).light_direction == (0.0, -2.0, 1.0)


@pytest.mark.parametrize("opening", list(DoorOpening))
@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_door_geometry_follows_the_convention(opening, hinge_side):
    door = DoorConfig(opening=opening, hinge_side=hinge_side)
    geometry = DoorLayout.from_config(door)
    side = hinge_side.sign
    assert geometry.hinge_origin[1] == pytest.approx(side * door.width / 2)
    assert geometry.hinge_origin[0] == pytest.approx(door.thickness if opening is DoorOpening.PUSH else 0.0)
    # a positive hinge rotation moves the latch edge towards +x (push) or -x (pull)
    latch_edge = geometry.face_corners[1]
    velocity = np.cross(geometry.hinge_axis, latch_edge)
    assert np.sign(velocity[0]) == (1.0 if opening is DoorOpening.PUSH else -1.0)
    # the lever points to the hinge side, and a positive turn presses its tip down
    assert geometry.lever_direction[1] == side
    assert np.cross(geometry.handle_axis, geometry.lever_direction)[2] < 0
    # grasp frame: x towards the robot (-x), z up, right-handed
    rotation = geometry.grasp_in_handle[:3, :3]
    np.testing.assert_allclose(rotation[:, 0], [-1, 0, 0])
    np.testing.assert_allclose(rotation[:, 2], [0, 0, 1])
    assert np.linalg.det(rotation) == pytest.approx(1.0)
    # the robot-side face is the door plane x = 0
    face = geometry.face_corners + geometry.hinge_origin
    np.testing.assert_allclose(face[:, 0], 0.0, atol=1e-12)
    assert "door_hinge" in door_urdf(door) and "door_handle" in door_urdf(door)


def test_the_bridge_maps_its_appearance_parameters_onto_the_world():
    from door_contract.parameters import validate_all
    from door_sim_bridge.parameters import BRIDGE_PARAMETERS
    from door_sim_bridge.world_parameters import world_config

    white = [1.0, 1.0, 1.0]
    config = world_config(validate_all(BRIDGE_PARAMETERS, {"door_colour": white, "wall_colour": white,
                                                           "light_direction": [0.0, -1.0, 1.0]}))
    assert config.door.door_colour == config.door.wall_colour == (1.0, 1.0, 1.0)
    assert config.camera.light_direction == (0.0, -1.0, 1.0)
    defaults = world_config(validate_all(BRIDGE_PARAMETERS, {}))
    assert defaults.door == DoorConfig(width=0.914, handle_height=0.91)
    assert defaults.camera.light_direction == CameraConfig().light_direction
    with pytest.raises(SimulationError, match="DoorConfig.handle_colour"):
        world_config(validate_all(BRIDGE_PARAMETERS, {"handle_colour": [0.5, 2.0, 0.5]}))


def test_the_bridge_maps_its_grasp_model_onto_the_world_and_refuses_an_unknown_one():
    from door_contract.errors import ParameterRangeError
    from door_contract.parameters import validate_all
    from door_sim_bridge.parameters import BRIDGE_PARAMETERS
    from door_sim_bridge.world import GraspModel
    from door_sim_bridge.world_parameters import world_config

    assert world_config(validate_all(BRIDGE_PARAMETERS, {})).grasp_model is GraspModel.COMPLIANT
    rigid = world_config(validate_all(BRIDGE_PARAMETERS, {"grasp_model": "rigid"}))
    assert rigid.grasp_model is GraspModel.RIGID
    with pytest.raises(ParameterRangeError, match="grasp_model"):
        validate_all(BRIDGE_PARAMETERS, {"grasp_model": "ball"})


def test_the_bridge_maps_its_contact_solver_onto_the_world_and_refuses_an_unknown_one():
    from door_contract.errors import ParameterRangeError
    from door_contract.parameters import validate_all
    from door_sim_bridge.parameters import BRIDGE_PARAMETERS
    from door_sim_bridge.world import ContactSolver
    from door_sim_bridge.world_parameters import world_config

    default = world_config(validate_all(BRIDGE_PARAMETERS, {}))
    assert (default.contact_solver, default.solver_iterations) == (WorldConfig().contact_solver,
                                                                   WorldConfig().solver_iterations)
    direct = world_config(validate_all(BRIDGE_PARAMETERS, {"contact_solver": "dantzig", "solver_iterations": 80}))
    assert (direct.contact_solver, direct.solver_iterations) == (ContactSolver.DANTZIG, 80)
    with pytest.raises(ParameterRangeError, match="contact_solver"):
        validate_all(BRIDGE_PARAMETERS, {"contact_solver": "pgs"})
    with pytest.raises(ParameterRangeError, match="solver_iterations"):
        validate_all(BRIDGE_PARAMETERS, {"solver_iterations": 0})
