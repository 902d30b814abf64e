"""The sim bridge's publication schedules in simulated time, without ROS."""

from door_sim_bridge.schedule import Schedule


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
