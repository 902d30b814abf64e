"""One run of the head search on the sim core (no ROS): look, detect, vote, move on.

What the graph is to do through the FSM (see :mod:`~door_detection.view_search`), played
directly on a :class:`door_sim_bridge.world.DoorWorld`: the search's views are taken in
turn — the body turned in place (the base rotated about its vertical axis, as the
quasi-static walker's turn in place leaves it; charged 2 steps of ``step_duration`` per
``max_turn``), the neck joints set to the view's targets and the world stepped until they
settle — and frames are rendered every 1/``camera_rate`` s of sim time and fed to the
detector. Every estimate is moved to ``odom`` with the frame's camera pose and voted on
together (:class:`~door_detection.voting.Voter`), whatever view it came from.

Operator-aided runs scribble once per settled view, when the whole lever projects into the
image (an operator marks what they see): the projected lever's outline with ±2 px noise
(:func:`~door_evaluation.detection.sim_scenes.synthetic_scribble`), the hinge side given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from door_contract.vocabulary import DetectionMode
from door_detection.automatic import detect_automatic
from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.head_search import home_view as neck_view
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.view_search import Neck, SearchStep, View, ViewSearch, ViewSearchOptions, plan_views
from door_detection.voting import Voter
from door_evaluation.detection.sim_scenes import lever_corners, synthetic_scribble

if TYPE_CHECKING:  # the caller builds the world (and imports the sim)
    from door_sim_bridge.world import DoorWorld
    from door_sim_bridge.world.camera import CameraFrame

__all__ = ["SearchOutcome", "SearchSettings", "home_view", "operator_scribble", "run_search"]


@dataclass(frozen=True)
class SearchSettings:
    """Timing of a simulated search."""

    camera_rate: float = 2.0
    """Frames per second of sim time (the sim bridge's default)."""
    settle_tolerance: float = 0.01
    """A neck joint has reached its target within this (rad)."""
    max_settle_time: float = 4.0
    """Sim seconds a head move may take before the view is used anyway."""


@dataclass(frozen=True)
class SearchOutcome:
    """``estimate``: the confirmed door in odom (None: the search ran out of views); ``frames``
    detected on, ``views`` visited, ``sim_time`` from the search's first frame to the
    confirming one (s), the detector's wall time per frame (s)."""

    estimate: DetectedDoor | None
    frames: int
    views: int
    sim_time: float
    frame_seconds: tuple[float, ...]


def home_view(world: DoorWorld, neck: Neck) -> View:
    """The view the robot has now (its neck joints' look angles)."""
    return neck_view(neck, world.joint_positions())


def run_search(world: DoorWorld, neck: Neck, mode: DetectionMode = DetectionMode.AUTOMATIC,
               options: DetectionOptions | None = None, search_options: ViewSearchOptions | None = None,
               settings: SearchSettings | None = None, seed: int = 0) -> SearchOutcome:
    """Search for the door from the world's current state (see the module docstring)."""
    opts, timing = options or DetectionOptions(), settings or SearchSettings()
    search = ViewSearch(plan_views(neck, home_view(world, neck), search_options), search_options)
    voter, rng = Voter(opts), np.random.default_rng(seed)
    start, start_base = world.time, world.base_pose()
    frames, views = 0, 0
    seconds: list[float] = []
    while (view := search.view) is not None:
        _look(world, neck, view, start_base, timing)
        views += 1
        scribble = operator_scribble(world, rng) if mode is DetectionMode.OPERATOR else None
        while True:
            frame = world.render()
            result = _detect(frame, mode, scribble, opts, world)
            frames, seconds = frames + 1, seconds + [result.elapsed]
            seen = result.estimate if result.ok else None
            vote = voter.add(seen.transformed(frame.camera_pose) if seen is not None else None)
            step = search.after_frame(result.ok, vote.ok)
            if step is SearchStep.CONFIRMED:
                return SearchOutcome(vote.estimate, frames, views, frame.time - start, tuple(seconds))
            world.step(_steps(world, 1.0 / timing.camera_rate))
            if step is not SearchStep.STAY:
                break
    return SearchOutcome(None, frames, views, world.time - start, tuple(seconds))


def _steps(world: DoorWorld, seconds: float) -> int:
    return max(int(round(seconds * world.config.physics_rate)), 1)


def _look(world: DoorWorld, neck: Neck, view: View, start_base: np.ndarray, timing: SearchSettings) -> None:
    """Turn the body to the view's yaw (if it differs) and the neck to its targets; step until
    the neck joints settle."""
    turned = start_base.copy()
    c, s = math.cos(view.body_yaw), math.sin(view.body_yaw)
    turned[:3, :3] = start_base[:3, :3] @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    if not np.allclose(turned, world.base_pose(), atol=1e-6):
        change = abs(math.atan2(turned[1, 0], turned[0, 0]) - math.atan2(world.base_pose()[1, 0],
                                                                            world.base_pose()[0, 0]))
        world.set_base_pose(turned)
        turns = math.ceil(abs(math.remainder(change, 2 * math.pi)) / world.profile.walking.max_turn)
        world.step(_steps(world, 2 * turns * world.config.execution.step_duration))
    targets = view.joint_targets(neck)
    world.set_joint_targets(targets)
    period = 1.0 / timing.camera_rate
    waited = 0.0
    while waited < timing.max_settle_time:
        joints = world.joint_positions()
        if all(abs(joints[name] - value) <= timing.settle_tolerance for name, value in targets.items()):
            return
        world.step(_steps(world, period))
        waited += period


def operator_scribble(world: DoorWorld, rng: np.random.Generator) -> np.ndarray | None:
    """The operator's scribble on the lever when all of it projects into the image."""
    pose = world.camera.pose()
    points = (lever_corners(world) - pose[:3, 3]) @ pose[:3, :3]
    intrinsics = world.camera.intrinsics
    if np.any(points[:, 2] <= 0.05):
        return None
    pixels = intrinsics.project(points)
    inside = (pixels[:, 0] >= 0) & (pixels[:, 0] <= intrinsics.width - 1) & \
             (pixels[:, 1] >= 0) & (pixels[:, 1] <= intrinsics.height - 1)
    return synthetic_scribble(pixels, intrinsics, rng, 2.0) if inside.all() else None


def _detect(frame: CameraFrame, mode: DetectionMode, scribble: np.ndarray | None, options: DetectionOptions,
            world: DoorWorld) -> DetectionResult:
    if mode is DetectionMode.AUTOMATIC:
        return detect_automatic(frame.rgb, frame.depth, frame.intrinsics, options)
    if scribble is None:
        return DetectionResult(DetectionOutcome.NO_HANDLE, None, "no whole handle in view for the operator to mark")
    up = frame.camera_pose[:3, :3].T @ np.array([0.0, 0.0, 1.0])
    side = world.config.door.hinge_side
    return detect_from_scribble(frame.rgb, frame.depth, frame.intrinsics, scribble, options, side, up)
