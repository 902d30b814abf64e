"""The stabiliser's feed-forward: smooth, bounded, and blind to one-tick spikes (ROS-free).

Why it matters (issue #11): counted from the first tick of a walk, 30 N at a hand leaned
TALOS 3.4 cm at the rate limit and tipped it over the stance toe; a body striking a leaf
reads 2 kN for a tick, and that spike alone leaned the robot for half a second.
"""

from __future__ import annotations

import numpy as np
import pytest

from door_sim_bridge.errors import SimulationError
from door_sim_bridge.walking.stabilizer import ContactWrench, Stabilizer, StabilizerOptions, clipped

DT = 1.0 / 240.0
WEIGHT = 90.0 * 9.81
AT_THE_HAND = np.array([0.5, 0.0, 1.0])


def run(stabilizer: Stabilizer, force: np.ndarray | None, seconds: float, walking: bool = True) -> list[np.ndarray]:
    """Offsets while walking (or standing) with ``force`` (N) at the hand (None: no contact) for ``seconds``."""
    wrench = ContactWrench.none() if force is None else ContactWrench(np.asarray(force, float), AT_THE_HAND)
    return [stabilizer.update(DT, np.zeros(2), wrench, None, walking=walking).copy()
            for _ in range(int(round(seconds / DT)))]


def test_a_force_that_appears_leans_the_robot_smoothly_to_the_static_balance():
    stabilizer = Stabilizer(StabilizerOptions(), WEIGHT)
    offsets = np.array(run(stabilizer, [-30.0, 0.0, 0.0], 3.0))
    static = 30.0 * 1.0 / WEIGHT  # Δc = p_z F / (m g): forwards against a backward push
    assert offsets[-1][0] == pytest.approx(static, rel=0.02)
    speeds = np.diff(offsets[:, 0]) / DT
    assert abs(speeds[0]) < 0.005  # no jump: the lean starts at rest
    accelerations = np.diff(speeds) / DT
    assert np.max(np.abs(accelerations)) < 1.0  # m/s²: bounded, where a rate-limited ramp is impulsive


def test_unfiltered_the_same_force_starts_the_lean_at_the_rate_limit():
    options = StabilizerOptions(force_filter_s=0.0)
    offsets = np.array(run(Stabilizer(options, WEIGHT), [-30.0, 0.0, 0.0], 0.5))
    assert offsets[0][0] == pytest.approx(options.max_rate * DT)


def test_a_one_tick_strike_of_2_kN_barely_moves_the_com():
    stabilizer = Stabilizer(StabilizerOptions(), WEIGHT)
    run(stabilizer, [0.0, 2000.0, 0.0], DT)
    peak = max(abs(offset[1]) for offset in run(stabilizer, None, 1.0))
    assert peak < 0.002


def test_a_sustained_force_beyond_the_clip_counts_as_the_clip():
    """Walking, the clip is max_walking_force (a pushed leaf escapes the hand: a lean against
    more outlasted the force and the robot toppled); standing, max_force (beyond the dead band)."""
    options = StabilizerOptions(max_offset=0.2)
    walking = run(Stabilizer(options, WEIGHT), [0.0, 400.0, 0.0], 4.0)
    assert walking[-1][1] == pytest.approx(-options.max_walking_force / WEIGHT, rel=0.02)
    standing = run(Stabilizer(options, WEIGHT), [0.0, 400.0, 0.0], 4.0, walking=False)
    assert standing[-1][1] == pytest.approx(-(options.max_force / WEIGHT - options.force_deadband), rel=0.02)
    assert options.max_walking_force < options.max_force


def test_clipping_keeps_direction_and_point():
    wrench = ContactWrench(np.array([300.0, 400.0, 0.0]), AT_THE_HAND)
    limited = clipped(wrench, 100.0)
    assert np.allclose(limited.force, [60.0, 80.0, 0.0])
    assert limited.point is wrench.point
    assert clipped(ContactWrench(np.array([3.0, 4.0, 0.0]), AT_THE_HAND), 100.0).force[0] == 3.0


def test_reset_forgets_the_filtered_force():
    stabilizer = Stabilizer(StabilizerOptions(), WEIGHT)
    run(stabilizer, [-30.0, 0.0, 0.0], 2.0)
    stabilizer.reset()
    assert np.allclose(run(stabilizer, None, DT)[0], 0.0)


@pytest.mark.parametrize("field, value", [("force_filter_s", -0.1), ("max_force", -1.0), ("max_walking_force", -1.0),
                                          ("force_filter_s", float("nan"))])
def test_bad_options_are_refused_with_the_field_named(field, value):
    with pytest.raises(SimulationError, match=field):
        StabilizerOptions(**{field: value})
