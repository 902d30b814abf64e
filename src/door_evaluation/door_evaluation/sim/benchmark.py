"""Benchmark of the simulation bridge: physics real-time factor and camera frame rates.

``python -m door_evaluation.sim.benchmark`` prints one row per figure: the seed papers' figure
(none exists for the simulator: "n/a"), our target, what this machine achieves and the ratio
ours / target (≥ 1 meets the target). Times are CPU seconds of this process (one core), so
other programs running on the machine do not distort them. Targets: the physics (robot +
door, 240 Hz, no camera) at least 5× faster than real time, so a Monte-Carlo campaign and the
real-time node both have headroom — standing, with an arm moving, walking (the walking
controller's pattern and IK every tick, the DCM feedback), and walking with the graph's head
camera rendering at its 2 Hz (also under the other physics settings tried against the
lift-off dip of issue #11: 400 solver sweeps, 480 Hz, the direct solver); the head camera at least at the bridge's default
publishing rate (``CameraConfig.frame_rate_hz``) at the MultiSense SL's 1024×544 and at VGA.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.payloads import OutcomeStatus
from door_contract.vocabulary import Foot, Side
from door_sim_bridge.execution import FootstepExecution, TrajectoryExecution
from door_sim_bridge.world import (
    CameraConfig,
    ContactSolver,
    DoorPart,
    DoorWorld,
    RobotVisuals,
    StanceConfig,
    WorldConfig,
)

__all__ = ["WALK_STANCE", "main", "physics_walking", "straight_walk"]

PHYSICS_SECONDS = 10.0  # simulated seconds per physics measurement
WALK_STRIDES, WALK_STRIDE = 6, 0.2  # the walking measurement's plan (strides, m)
WALK_STANCE = StanceConfig(distance=3.0)  # far enough from the door for the walk
GRAPH_CAMERA_HZ = 2.0  # the graph's head camera rate (params/sim_bridge.yaml camera_rate)
CAMERA_FRAMES = 10
RTF_TARGET = 5.0


@dataclass(frozen=True)
class BenchmarkRow:
    """One line of the results table."""

    figure: str
    paper: str
    target: float
    ours: float
    unit: str

    @property
    def ratio(self) -> float:
        return self.ours / self.target


def _timed(action: Callable[[], object]) -> float:
    """CPU seconds of this process spent in ``action`` (one core; other load does not count)."""
    start = time.process_time()
    action()
    return time.process_time() - start


def physics_idle(world: DoorWorld) -> float:
    """Real-time factor holding the nominal posture next to a latched door."""
    steps = int(PHYSICS_SECONDS * world.config.physics_rate)
    begin = world.time
    wall = _timed(lambda: world.step(steps))
    return (world.time - begin) / wall


def physics_busy(world: DoorWorld) -> float:
    """Real-time factor with an arm trajectory running and the unlatched door swinging."""
    steps = int(PHYSICS_SECONDS * world.config.physics_rate)
    joints = world.profile.arm(Side.LEFT).joints[2:6]
    start = np.array([world.joint_positions()[name] for name in joints])
    times = np.linspace(1.0, PHYSICS_SECONDS, 10)
    offsets = 0.3 * np.sin(times / 2.0)[:, None] ** 2 * np.array([-1.0, 1.0, 1.0, -1.0])  # away from limits
    execution = TrajectoryExecution(world, times, joints, start + offsets)
    if execution.done:
        raise RuntimeError(f"benchmark trajectory rejected: {execution.result}")
    grasp = world.handle_grasp_pose()[:3, 3]
    world.apply_door_force([0.0, 0.0, -40.0], grasp, DoorPart.HANDLE, steps)
    world.apply_door_force(-80.0 * world.handle_grasp_pose()[:3, 0], grasp, DoorPart.LEAF, steps // 4)
    begin = world.time
    wall = _timed(lambda: execution.advance(steps))
    return (world.time - begin) / wall


def straight_walk(world: DoorWorld, strides: int = WALK_STRIDES, stride: float = WALK_STRIDE) -> list[FootPlacement]:
    """``strides`` strides of ``stride`` m straight ahead, the trailing foot brought alongside."""
    feet = world.foot_placements()
    plan = []
    for index in range(strides + 1):
        foot = Foot.LEFT if index % 2 == 0 else Foot.RIGHT
        sole = feet[foot]
        advance = stride * min(index + 1, strides)
        plan.append(FootPlacement(foot, sole.x + advance * math.cos(sole.yaw), sole.y + advance * math.sin(sole.yaw),
                                  sole.yaw))
    return plan


def physics_walking(world: DoorWorld, camera_hz: float = 0.0, strides: int = WALK_STRIDES) -> float:
    """Real-time factor walking :func:`straight_walk` of ``strides`` (the walking pattern planned
    at its first tick included), rendering a head-camera frame every ``1 / camera_hz`` simulated
    s (0: none)."""
    execution = FootstepExecution(world, straight_walk(world, strides))
    if execution.done:
        raise RuntimeError(f"benchmark walk rejected: {execution.result}")
    begin, rendered = world.time, 0

    def walk() -> None:
        nonlocal rendered
        while not execution.command():
            world.step()
            if camera_hz > 0.0 and world.time - begin >= rendered / camera_hz:
                world.render()
                rendered += 1

    wall = _timed(walk)
    if execution.result is None or execution.result.status is not OutcomeStatus.SUCCESS:
        raise RuntimeError(f"benchmark walk did not succeed: {execution.result}")
    return (world.time - begin) / wall


def camera_rate(width: int, height: int, visuals: RobotVisuals = RobotVisuals.ARMS) -> float:
    """Rendered RGB-D frames per CPU second (TinyRenderer, one core)."""
    camera = CameraConfig(width=width, height=height, vertical_fov_deg=45.0 if width > 640 else 60.0,
                          robot_visuals=visuals)
    with DoorWorld(WorldConfig(camera=camera)) as world:
        world.render()  # warm-up
        return CAMERA_FRAMES / _timed(lambda: [world.render() for _ in range(CAMERA_FRAMES)])


PHYSICS_VARIANTS = (("400 solver sweeps", WorldConfig(solver_iterations=400)),
                    ("480 Hz", WorldConfig(physics_rate=480.0)),
                    ("direct (Dantzig) solver", WorldConfig(contact_solver=ContactSolver.DANTZIG)))
"""Other physics than the default, each measured idle (``sim_bridge`` parameters of the same names)."""


def run() -> list[BenchmarkRow]:
    frame_rate = CameraConfig().frame_rate_hz
    with DoorWorld() as world:
        idle, busy = physics_idle(world), physics_busy(world)
    rows = [BenchmarkRow("physics real-time factor, robot + door, 240 Hz, idle", "n/a", RTF_TARGET,
                         idle, "×"),
            BenchmarkRow("physics real-time factor, arm moving + door swinging", "n/a", RTF_TARGET,
                         busy, "×")]
    with DoorWorld(WorldConfig(stance=WALK_STANCE)) as world:
        rows.append(BenchmarkRow(f"physics real-time factor, walking {WALK_STRIDES} × {WALK_STRIDE} m, "
                                 "camera off", "n/a", RTF_TARGET, physics_walking(world), "×"))
    graph_camera = CameraConfig(width=640, height=480, vertical_fov_deg=60.0)
    with DoorWorld(WorldConfig(stance=WALK_STANCE, camera=graph_camera)) as world:
        rows.append(BenchmarkRow(f"physics real-time factor, walking, camera {GRAPH_CAMERA_HZ:g} Hz 640×480",
                                 "n/a", RTF_TARGET, physics_walking(world, GRAPH_CAMERA_HZ), "×"))
    for name, config in PHYSICS_VARIANTS:
        with DoorWorld(config) as world:
            rows.append(BenchmarkRow(f"physics real-time factor, idle, {name}", "n/a", RTF_TARGET,
                                     physics_idle(world), "×"))
    for width, height in ((1024, 544), (640, 480)):
        rows.append(BenchmarkRow(f"camera RGB-D {width}×{height} (arms rendered)", "n/a", frame_rate,
                                 camera_rate(width, height), "frames/s"))
    rows.append(BenchmarkRow("camera RGB-D 1024×544 (whole robot rendered)", "n/a", frame_rate,
                             camera_rate(1024, 544, RobotVisuals.ALL), "frames/s"))
    return rows


def format_table(rows: list[BenchmarkRow]) -> str:
    header = f"{'figure':<56} {'paper':>6} {'target':>10} {'ours':>10} {'ours/target':>12}"
    lines = [header, "-" * len(header)]
    for row in rows:
        lines.append(f"{row.figure:<56} {row.paper:>6} {row.target:>8.1f} {row.unit[:1]:<1} "
                     f"{row.ours:>8.1f} {row.unit[:1]:<1} {row.ratio:>11.2f}")
    lines.append("units: × = simulated s per CPU s; f = frames per CPU second (one core, this process only)")
    return "\n".join(lines)


def main() -> int:
    print(format_table(run()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
