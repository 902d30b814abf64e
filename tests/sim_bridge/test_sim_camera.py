"""Head RGB-D camera: intrinsics, metric depth on the door plane, noise and reproducibility."""

import math

import cv2
import numpy as np
import pytest

from door_sim_bridge.world import CameraConfig, DoorConfig, DoorWorld, StanceConfig, WorldConfig

STANCE = StanceConfig(distance=3.0, lateral_offset=0.3, yaw=-0.15)


@pytest.fixture(scope="module")
def frame_and_world():
    with DoorWorld(WorldConfig(stance=STANCE)) as world:
        yield world.render(), world


def _colour_mask(rgb: np.ndarray, colour: tuple[float, float, float], erode: int = 3,
                 tolerance: float = 45.0) -> np.ndarray:
    """Pixels of one scene colour (shading allowed), eroded away from edges and occluders."""
    close = np.all(np.abs(rgb.astype(int) - np.array(colour) * 255) < tolerance, axis=2).astype(np.uint8)
    return cv2.erode(close, np.ones((2 * erode + 1, 2 * erode + 1), np.uint8)).astype(bool)


def _points_in_odom(frame) -> np.ndarray:
    rows, cols = np.mgrid[0:frame.depth.shape[0], 0:frame.depth.shape[1]]
    points = frame.intrinsics.back_project(cols.astype(float), rows.astype(float), frame.depth)
    return points @ frame.camera_pose[:3, :3].T + frame.camera_pose[:3, 3]


def test_frame_shapes_and_intrinsics(frame_and_world):
    frame, world = frame_and_world
    assert frame.rgb.shape == (480, 640, 3) and frame.rgb.dtype == np.uint8
    assert frame.depth.shape == (480, 640) and frame.depth.dtype == np.float32
    focal = 240.0 / math.tan(math.radians(30.0))
    assert (frame.intrinsics.fx, frame.intrinsics.fy) == pytest.approx((focal, focal))
    assert (frame.intrinsics.width, frame.intrinsics.height) == (640, 480)
    np.testing.assert_allclose(frame.camera_pose, world.link_pose(world.profile.head_camera_frame))
    assert frame.time == world.time


def test_depth_back_projects_onto_the_door_plane_and_the_floor(frame_and_world):
    frame, world = frame_and_world
    points = _points_in_odom(frame)
    door = _colour_mask(frame.rgb, world.config.door.door_colour)
    assert door.sum() > 5000  # the door is in view
    assert np.abs(points[door][:, 0]).max() < 0.01  # x = 0 within 1 cm
    floor = _colour_mask(frame.rgb, world.config.door.floor_colour, tolerance=20.0)
    assert floor.sum() > 5000
    assert np.abs(points[floor][:, 2]).max() < 0.01  # z = 0
    # the handle is seen where the ground truth puts it
    handle = _colour_mask(frame.rgb, world.config.door.handle_colour, erode=0)
    grasp = world.handle_grasp_pose()[:3, 3]
    assert handle.sum() > 20
    assert np.linalg.norm(points[handle].mean(axis=0) - grasp) < 0.08


def test_nothing_beyond_far_is_nan():
    camera = CameraConfig(far=2.0, width=160, height=120)
    with DoorWorld(WorldConfig(stance=STANCE, camera=camera)) as world:
        depth = world.render().depth
    assert np.isnan(depth).mean() > 0.3  # the wall, 3 m away
    finite = depth[np.isfinite(depth)]
    assert finite.size > 0 and finite.max() < 2.0 and finite.min() > 0.1


def _noisy_world(seed: int, noise: bool = True) -> DoorWorld:
    camera = CameraConfig(width=320, height=240, depth_noise_coefficient=0.01 if noise else 0.0,
                          colour_noise_sigma=4.0 if noise else 0.0)
    return DoorWorld(WorldConfig(stance=STANCE, camera=camera, seed=seed))


def test_same_seed_gives_the_same_first_frame():
    with _noisy_world(7) as first, _noisy_world(7) as second, _noisy_world(8) as other:
        a, b, c = first.render(), second.render(), other.render()
    np.testing.assert_array_equal(a.rgb, b.rgb)
    np.testing.assert_array_equal(a.depth, b.depth)  # NaNs in the same places too
    assert not np.array_equal(a.rgb, c.rgb)


def test_depth_noise_grows_with_the_square_of_the_distance():
    with _noisy_world(1) as noisy, _noisy_world(1, noise=False) as clean:
        measured, truth = noisy.render().depth, clean.render().depth
    valid = np.isfinite(measured) & np.isfinite(truth)
    scaled = (measured[valid] - truth[valid]) / truth[valid] ** 2
    assert np.std(scaled) == pytest.approx(0.01, rel=0.1)
    near, far = valid & (truth < 2.5), valid & (truth > 3.5)
    assert np.std((measured - truth)[far]) > 2.0 * np.std((measured - truth)[near])


def test_large_frames_render():
    camera = CameraConfig(width=1024, height=544, vertical_fov_deg=45.0)
    with DoorWorld(WorldConfig(camera=camera, door=DoorConfig(opening=DoorConfig().opening))) as world:
        frame = world.render()
    assert frame.rgb.shape == (544, 1024, 3) and frame.intrinsics.cy == 271.0


def _leaf_level(light_direction: tuple[float, float, float]) -> float:
    """Median red level of the leaf's centre, straight on from 2 m, under one light."""
    camera = CameraConfig(width=160, height=120, light_direction=light_direction)
    with DoorWorld(WorldConfig(stance=StanceConfig(distance=2.0), camera=camera)) as world:
        rgb = world.render().rgb
    return float(np.median(rgb[50:70, 70:90, 0]))


def test_the_light_direction_shades_the_leaf():
    """TinyRenderer's shading 0.6 + 0.35·max(n·l, 0) of the leaf's red 0.55: lit head-on from
    the robot's side (n·l = 1) against lit from behind the wall (n·l < 0), and the default
    light (n·l = 0.43), which renders as it did before the light was a parameter."""
    red = 0.55 * 255
    assert _leaf_level((-1.0, 0.0, 0.0)) == pytest.approx(red * 0.95, abs=2.0)
    assert _leaf_level((1.0, 0.0, 0.2)) == pytest.approx(red * 0.60, abs=2.0)
    default = CameraConfig().light_direction
    assert _leaf_level(default) == pytest.approx(red * (0.6 + 0.35 * 50 / np.linalg.norm(default)), abs=2.0)


def test_the_physical_robots_floor_is_drawn_in_the_floor_colour():
    """The collision plane under the physical robot must not be drawn: PyBullet draws a body
    without a visual by its collision shape, a checker plane that covered the scene's floor
    colour in every physical world (and flickered with it where the two coincide)."""
    blue = (0.1, 0.1, 0.9)
    config = WorldConfig(door=DoorConfig(floor_colour=blue), stance=STANCE, camera=CameraConfig(head_pitch=0.6))
    with DoorWorld(config) as world:
        assert world.physical
        frame = world.render()
    floor = np.abs(_points_in_odom(frame)[..., 2]) < 0.005
    assert floor.sum() > 20000  # the head looks down at the floor
    in_colour = _colour_mask(frame.rgb, blue, erode=0, tolerance=30.0)
    assert in_colour[floor].mean() > 0.99
