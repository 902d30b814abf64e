"""The nodes' signal handling: the first SIGINT/SIGTERM asks the spin loop to stop between
callbacks; a second one interrupts a long callback."""

import signal

import pytest

from door_contract.node_support import StopRequest


def test_first_signal_requests_a_stop_and_names_it():
    stop = StopRequest()
    assert not stop.requested
    stop(signal.SIGTERM, None)
    assert stop.requested and stop.signal_name == "SIGTERM"


def test_second_signal_interrupts_the_running_callback():
    stop = StopRequest()
    stop(signal.SIGINT, None)
    with pytest.raises(KeyboardInterrupt):
        stop(signal.SIGINT, None)
