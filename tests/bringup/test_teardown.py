"""A teardown step that hangs is given up after its bound (stop 38: a Monte-Carlo worker hung for
90 min destroying the operator node) and one that finishes is waited for."""

import threading

import pytest

from door_bringup.teardown import finishes_within


def test_a_step_that_never_returns_is_given_up_after_the_bound():
    never = threading.Event()
    assert finishes_within(never.wait, timeout_s=0.2) is False
    never.set()  # lets the daemon thread end


def test_a_step_that_returns_is_waited_for():
    ran = threading.Event()
    assert finishes_within(ran.set, timeout_s=30.0) is True
    assert ran.is_set()


def test_a_steps_error_reaches_the_caller():
    def broken() -> None:
        raise RuntimeError("context already shut down")

    with pytest.raises(RuntimeError, match="already shut down"):
        finishes_within(broken, timeout_s=30.0)
