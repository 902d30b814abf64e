"""Rendered scenes shared by the door-detection tests (rendered once per session).

``sim_scene(distance, yaw, ...)`` renders the project's simulation core (``DoorWorld``,
1024×544 head camera) through :mod:`door_evaluation.detection.sim_scenes`; ``fixture_scene`` is this
folder's own minimal PyBullet world (:mod:`door_scene`), a second, independently built
door (no frame, recessed leaf, a lever without a rose, other colours and intrinsics) so
the detector is not tuned to one renderer.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest

from door_contract.vocabulary import Side
from door_evaluation.detection.sim_scenes import Scenario, SceneFrame, render_scenario


@pytest.fixture(scope="session")
def sim_scene() -> Callable[..., SceneFrame]:
    cache: dict[Scenario, SceneFrame] = {}

    def render(distance: float = 2.0, yaw: float = 0.0, depth_noise: float = 0.0,
               hinge_side: Side = Side.LEFT) -> SceneFrame:
        scenario = Scenario(distance=distance, yaw=yaw, depth_noise=depth_noise, hinge_side=hinge_side)
        if scenario not in cache:
            cache[scenario] = render_scenario(scenario)
        return cache[scenario]

    return render


@pytest.fixture(scope="session")
def straight_on(sim_scene: Callable[..., SceneFrame]) -> SceneFrame:
    """The sim door at 2 m, straight on, no depth noise."""
    return sim_scene(2.0, 0.0)


@pytest.fixture(scope="session")
def fixture_scene():
    from door_scene import SceneSpec, render

    return render(SceneSpec(distance=2.5, yaw=0.3, noise_k=0.002))
