"""The Monte-Carlo's doors: issue #13's full ranges with random colours, and the earlier narrow
ones drawing the very doors they drew before."""

import numpy as np
import pytest

from door_bringup.door_task import TaskOptions
from door_bringup.monte_carlo import RECORDED_BEFORE, draw_trials, main
from door_bringup.trial_ranges import FULL, NARROW, RangeSet, ranges_named
from door_sim_bridge.world_ranges import COLOUR_FIELDS

FIELDS = ("distance", "lateral", "yaw", "door_width", "handle_height", "wind", "depth_noise")


def test_full_ranges_are_issue_13s_and_every_draw_lies_within_them():
    assert (FULL.distance, FULL.lateral, FULL.yaw) == ((1.0, 4.0), (-0.6, 0.6), (-0.6, 0.6))
    assert (FULL.door_width, FULL.handle_height, FULL.wind, FULL.depth_noise) == (
        (0.80, 1.00), (0.85, 1.10), (0.0, 3.0), (0.0, 0.005))
    trials = draw_trials(np.random.default_rng(5), TaskOptions(), 200, ["push", "pull"], FULL)
    for name in FIELDS:
        low, high = getattr(FULL, name)
        values = [getattr(trial, name) for trial in trials]
        assert all(low <= value <= high for value in values), name
        assert max(values) - min(values) > 0.8 * (high - low), name  # the whole range is visited
    colours = [dict(trial.colours) for trial in trials]
    assert all(set(c) == set(COLOUR_FIELDS) for c in colours)
    assert all(0.0 <= channel <= 1.0 for c in colours for rgb in c.values() for channel in rgb)
    assert len({c["door_colour"] for c in colours}) == len(trials)  # every scene looks different


def test_narrow_ranges_draw_the_doors_of_the_earlier_campaigns():
    """Seed 0's first door, as the Monte-Carlo before --ranges drew it (trial_000 of the
    stop-24 campaign: pull, right hinge, 0.914 m door not changed, no colours)."""
    first = draw_trials(np.random.default_rng(0), TaskOptions(), 1, ["push", "pull"], NARROW)[0]
    for name in FIELDS:
        low, high = getattr(NARROW, name)
        assert low <= getattr(first, name) <= high
    assert first.colours == ()
    assert draw_trials(np.random.default_rng(0), TaskOptions(), 3, ["push", "pull"]) == draw_trials(
        np.random.default_rng(0), TaskOptions(), 3, ["push", "pull"], NARROW)


def test_colours_reach_the_sim_bridge_as_its_parameters():
    options = TaskOptions(colours=(("wall_colour", (0.9, 0.9, 0.9)), ("door_colour", (0.95, 0.95, 0.95))))
    sim = options.node_overrides()["sim_bridge"]
    assert "wall_colour:=[0.9, 0.9, 0.9]" in sim and "door_colour:=[0.95, 0.95, 0.95]" in sim
    assert not any("floor_colour" in arg for arg in TaskOptions().node_overrides()["sim_bridge"])


def test_a_folder_written_before_ranges_resumes_as_narrow():
    assert RECORDED_BEFORE["ranges"] == RangeSet.NARROW.value
    assert ranges_named(RangeSet.FULL) is FULL and ranges_named(RangeSet.NARROW) is NARROW


def test_an_unknown_range_set_is_refused(capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["--ranges", "wide"])
    assert stopped.value.code == 2 and "--ranges" in capsys.readouterr().err
