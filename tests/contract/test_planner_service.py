"""The planners' serving rules without ROS: every request ends exactly once, the newest wins,
a cancel drops a request, a failing job is an answer too."""

import threading
from dataclasses import dataclass

import pytest

from door_contract.errors import ContractError
from door_contract.payloads import FootstepRequest, OutcomeStatus, encode
from door_contract.planner_service import CancelResult, Finished, PlanningWorker, decode_request

DEADLINE_S = 10.0  # a safety net far above the milliseconds these jobs take


@dataclass(frozen=True)
class Request:
    request_id: int


class Collector:
    """The node's side: wakes record that answers are waiting; ``wait_for`` drains them."""

    def __init__(self):
        self.woken = threading.Event()
        self.finished = []
        self.worker = PlanningWorker(self.woken.set)

    def wait_for(self, count):
        while len(self.finished) < count:
            assert self.woken.wait(DEADLINE_S), f"only {len(self.finished)} of {count} answers"
            self.woken.clear()
            self.finished += self.worker.take_finished()
        return {f.request.request_id: f for f in self.finished}


def blocking_job(release, value):
    def job():
        assert release.wait(DEADLINE_S)
        return value
    return job


def test_newest_request_supersedes_queued_and_running_ones():
    node, release = Collector(), threading.Event()
    node.worker.submit(Request(1), blocking_job(release, "one"))
    for request_id in range(2, 101):  # a burst of 99 more while 1 runs
        node.worker.submit(Request(request_id), lambda rid=request_id: f"plan {rid}")
    release.set()
    answers = node.wait_for(100)
    assert len(answers) == 100 and len(node.finished) == 100  # every request exactly once
    assert answers[100].result == "plan 100" and not answers[100].dropped
    assert answers[1].dropped == "superseded by request 2" and answers[1].result is None
    assert all(answers[i].dropped == f"superseded by request {i + 1}" for i in range(2, 100))
    node.worker.close()


def test_cancel_queued_running_and_unknown():
    node, release = Collector(), threading.Event()
    node.worker.submit(Request(1), blocking_job(release, "one"))
    node.worker.submit(Request(2), lambda: "two")  # supersedes 1 (running)
    assert node.worker.cancel(2, "operator paused") is CancelResult.QUEUED
    assert node.worker.cancel(99, "") is CancelResult.UNKNOWN
    release.set()
    answers = node.wait_for(2)
    assert answers[2].dropped == "cancelled: operator paused"
    assert answers[1].dropped.startswith("superseded by request 2")
    node.worker.close()


def test_a_cancelled_running_job_is_never_proposed():
    node, release = Collector(), threading.Event()
    started = threading.Event()

    def job():
        started.set()
        assert release.wait(DEADLINE_S)
        return "plan"
    node.worker.submit(Request(5), job)
    assert started.wait(DEADLINE_S)
    assert node.worker.cancel(5, "timeout") is CancelResult.RUNNING
    release.set()
    answers = node.wait_for(1)
    assert answers[5].dropped == "cancelled: timeout" and answers[5].result is None
    node.worker.close()


def test_a_failing_job_is_answered_with_its_error():
    node = Collector()
    node.worker.submit(Request(3), lambda: 1 / 0)
    answers = node.wait_for(1)
    assert isinstance(answers[3].error, ZeroDivisionError)
    node.worker.close()


@pytest.mark.parametrize("finished, answer", [
    (Finished(Request(1), result="plan"), None),
    (Finished(Request(1), dropped="superseded by request 2"), (OutcomeStatus.SUPERSEDED, "superseded by request 2")),
    (Finished(Request(1), error=ContractError("no door estimate yet")), (OutcomeStatus.REJECTED, "no door estimate yet")),
    # a bug's ValueError (numpy, float(), an enum lookup) is no refusal of the input
    (Finished(Request(1), error=ValueError("operands could not be broadcast")),
     (OutcomeStatus.FAILURE, "internal error: ValueError('operands could not be broadcast')")),
    (Finished(Request(1), error=ZeroDivisionError("division by zero")),
     (OutcomeStatus.FAILURE, "internal error: ZeroDivisionError('division by zero')")),
])
def test_bad_input_is_rejected_and_a_bug_is_an_internal_failure(finished, answer):
    assert finished.answer_without_result((ContractError,)) == answer


def test_decode_request_reads_the_id_of_an_invalid_request():
    valid = encode(FootstepRequest(4, "stand", "push"))
    assert decode_request(FootstepRequest, valid)[:2][1] == 4
    request, request_id, reason = decode_request(FootstepRequest, '{"request_id": 9, "goal": "stand"}')
    assert request is None and request_id == 9 and "opening" in reason
    request, request_id, reason = decode_request(FootstepRequest, "[" * 100000)
    assert request is None and request_id is None and "nested" in reason
