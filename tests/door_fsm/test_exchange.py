"""Proposals meet their outcomes in either order, only for the current request, once; every
table stays bounded."""

from door_contract.payloads import OutcomeStatus, PlanningOutcome
from door_fsm.exchange import PlanExchange, Proposal


def outcome(request_id, stamp, status=OutcomeStatus.SUCCESS):
    return PlanningOutcome(request_id, status, "", 0.1, stamp_ns=stamp)


def exchange():
    return PlanExchange(work_of=lambda message: len(message) * 1.0, capacity=4)


def test_pairs_in_either_order():
    ex = exchange()
    ex.begin(1)
    assert ex.add_message("footsteps", 100, "abc") is None
    pair = ex.add_outcome("footsteps", outcome(1, 100))
    assert isinstance(pair, Proposal) and pair.message == "abc" and pair.work_s == 3.0
    ex.begin(2)
    assert ex.add_outcome("motion", outcome(2, 200)) is None
    assert ex.add_message("motion", 200, "xy").request_id == 2


def test_stale_outcomes_and_other_kinds_do_not_pair():
    ex = exchange()
    ex.begin(5)
    assert ex.add_outcome("footsteps", outcome(4, 100)) is None  # an earlier request
    ex.add_message("motion", 100, "trajectory")
    assert ex.add_outcome("footsteps", outcome(5, 100)) is None  # same stamp, other planner
    failure = outcome(5, -1, OutcomeStatus.SUPERSEDED)
    assert ex.add_outcome("footsteps", failure) is failure


def test_a_proposal_is_taken_once_and_dropped_by_a_newer_request():
    ex = exchange()
    ex.begin(1)
    ex.add_message("footsteps", 1, "p")
    ex.add_outcome("footsteps", outcome(1, 1))
    assert ex.take(1).message == "p" and ex.take(1) is None
    ex.add_message("footsteps", 2, "q")
    ex.add_outcome("footsteps", outcome(1, 2))
    ex.begin(2)
    assert ex.take(1) is None


def test_executions_are_found_by_their_stamp_once():
    ex = exchange()
    ex.sent(123, 7)
    assert ex.finished(999) is None and ex.finished(123) == 7 and ex.finished(123) is None


def test_tables_stay_bounded():
    ex = exchange()
    ex.begin(1)
    for stamp in range(1000):
        ex.add_message("footsteps", stamp, "m")
        ex.add_outcome("motion", outcome(1, 10_000 + stamp))
        ex.sent(stamp, 1)
    assert all(size <= 4 for size in ex.sizes().values())
