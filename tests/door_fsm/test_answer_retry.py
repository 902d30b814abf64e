"""An automatic operator's answer is sent again until the FSM takes it (stop 38: a fresh clone's
main job lost its first approval to DDS matching and ended FAILED after the 300 s approval
timeout). The pure core here; the DDS case in tests/bringup/test_operator_answers.py."""

import pytest

from door_fsm.answer_retry import AnswerRetry, RetryOptions

REQUEST_3 = "DETECT_DOOR #3: approve detection 'door'? width=0.91 | reply 'approve 3', 'reject 3' or 'repeat 3'"
REQUEST_4 = "WALK_TO_DOOR #4: approve footsteps 'stand'? steps=14 | reply 'approve 4', 'reject 4' or 'repeat 4'"


def test_a_new_request_is_answered_at_once():
    retry = AnswerRetry()
    assert retry.on_request(REQUEST_3, now=10.0) == 3


def test_an_answer_not_taken_is_sent_again_every_resend_period():
    retry = AnswerRetry(RetryOptions(resend_after_s=2.0))
    retry.on_request(REQUEST_3, now=10.0)
    assert retry.due(11.9) is None
    assert retry.due(12.0) == 3
    assert retry.due(13.0) is None and retry.due(14.1) == 3
    assert retry.sends == 3


def test_a_cleared_request_stops_the_repeats():
    retry = AnswerRetry()
    retry.on_request(REQUEST_3, now=10.0)
    assert retry.on_request("", now=10.5) is None
    assert retry.due(100.0) is None and retry.sends == 1


def test_a_late_joiners_copy_of_the_same_request_is_not_answered_twice():
    retry = AnswerRetry()
    retry.on_request(REQUEST_3, now=10.0)
    assert retry.on_request(REQUEST_3, now=10.1) is None


def test_the_next_request_replaces_the_pending_one():
    retry = AnswerRetry(RetryOptions(resend_after_s=2.0))
    retry.on_request(REQUEST_3, now=10.0)
    assert retry.on_request(REQUEST_4, now=11.0) == 4
    assert retry.due(13.0) == 4


def test_text_without_a_request_id_is_not_answered():
    retry = AnswerRetry()
    assert retry.on_request("DETECT_DOOR: looking for the door", now=1.0) is None
    assert retry.due(100.0) is None


def test_a_resend_period_must_be_positive():
    with pytest.raises(ValueError, match="resend_after_s"):
        RetryOptions(resend_after_s=0.0)


def test_a_check_period_must_be_positive():
    with pytest.raises(ValueError, match="check_period_s"):
        RetryOptions(check_period_s=-1.0)
