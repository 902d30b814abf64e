"""The sim bridge's publication schedules in simulated time, without ROS."""

import pytest

from door_sim_bridge.schedule import FrameSchedule, Schedule


def test_a_schedule_is_due_once_a_period() -> None:
    schedule = Schedule(10.0)
    due = [t / 100 for t in range(0, 31) if schedule.due(t / 100)]
    assert due == [0.0, 0.1, 0.2, 0.3]


def test_a_stall_is_not_made_up_period_by_period() -> None:
    schedule = Schedule(10.0)
    assert schedule.due(0.0)
    assert schedule.due(1.0)             # ten periods late: due once ...
    assert schedule.due(1.0)             # ... caught up with now, not ten more times
    assert not schedule.due(1.05)
    assert schedule.due(1.1)


def test_a_zero_rate_is_due_only_at_the_start() -> None:
    schedule = Schedule(0.0)
    assert schedule.due(0.0)
    assert not any(schedule.due(t) for t in (1.0, 100.0, 1e6))


def test_the_camera_renders_at_the_standing_rate_unless_the_robot_walks() -> None:
    frames = FrameSchedule(walking_hz=2.0, standing_hz=8.0)
    standing = [t / 240 for t in range(0, 241) if frames.due(t / 240, walking=False)]
    assert standing == pytest.approx([k * 0.125 for k in range(9)])
    walking = [t / 240 for t in range(241, 721) if frames.due(t / 240, walking=True)]
    assert walking == pytest.approx([1.5, 2.0, 2.5, 3.0])  # one period after the last frame


def test_after_a_walk_the_next_frame_is_a_standing_period_after_the_last() -> None:
    frames = FrameSchedule(walking_hz=2.0, standing_hz=8.0)
    assert frames.due(10.0, walking=True) and not frames.due(10.1, walking=True)
    assert not frames.due(10.1, walking=False) and frames.due(10.125, walking=False)


@pytest.mark.parametrize("walking_hz, standing_hz", [(0.0, 8.0), (2.0, 0.0), (-1.0, 2.0)])
def test_a_frame_schedule_needs_positive_rates(walking_hz, standing_hz) -> None:
    with pytest.raises(ValueError, match="frame rates must be positive"):
        FrameSchedule(walking_hz, standing_hz)


def test_frames_fall_on_multiples_of_the_period_as_the_other_streams_do() -> None:
    """A camera pose must share its stamp with a /tf message: frames one physics step off the
    period's multiples shared none (the /tf listener test waited in vain)."""
    frames, tf = FrameSchedule(walking_hz=2.0, standing_hz=8.0), Schedule(20.0)
    steps = [k / 240 for k in range(1, 481)]
    camera = [t for t in steps if frames.due(t, walking=False)]
    assert camera[1:4] == pytest.approx([0.125, 0.25, 0.375])
    shared = {round(t, 9) for t in camera} & {round(t, 9) for t in steps if tf.due(t)}
    assert len(shared) >= 7  # every 0.25 s
