"""Payloads are bounded before parsing; a readable request id survives a bad request; NaN
never reaches encode; door estimates and angles a planner cannot use are named."""

import math
from dataclasses import replace

import pytest

from door_contract.door_estimates import door_angle_problem, door_estimate_problem, requested_estimate_problem
from door_contract.errors import ContractError
from door_contract.json_text import MAX_PAYLOAD_DEPTH, nesting_depth, parse_bounded, read_request_id
from door_contract.network import DISCOVERY_RANGE, keep_discovery_local
from door_contract.payloads import (
    DoorEstimate,
    FootstepRequest,
    MotionFigures,
    MotionRequest,
    OutcomeStatus,
    PlanningOutcome,
    decode,
    encode,
    finite_or_none,
)
from door_contract.vocabulary import Backend, HingeSide

ESTIMATE = DoorEstimate(1.5, "odom", (1.0, 0.3, 0.9), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((1.0, -0.45, 0.0), (1.0, 0.45, 0.0), (1.0, 0.45, 2.0), (1.0, -0.45, 2.0)),
                        0.9, 10, "automatic")


@pytest.mark.parametrize("text, depth", [
    ("{}", 1), ("[[1, [2]], {\"a\": [3]}]", 3), ('"[[[["', 0), ('{"a": "\\"[[["}', 1), ("", 0), ("]]]", 0),
])
def test_nesting_depth_ignores_brackets_in_strings(text, depth):
    assert nesting_depth(text) == depth


@pytest.mark.parametrize("text, match", [
    ("[" * 100000, "nested 100000 deep"),
    ("{" * (MAX_PAYLOAD_DEPTH + 1), "nested"),
    ("x" * 5_000_000, "characters"),
    ("[1, 2", "not JSON"),
])
def test_hostile_text_is_refused_before_parsing(text, match):
    with pytest.raises(ContractError, match=match):
        parse_bounded("FootstepRequest", text)
    with pytest.raises(ContractError):
        decode(FootstepRequest, text)


@pytest.mark.parametrize("text, request_id", [
    ('{"request_id": 7, "goal": "stand"}', 7),            # missing field: id still readable
    ('{"request_id": 8, "goal": "stand", "opening": "push", "colour": "red"}', 8),  # extra field
    ('{"request_id": true}', None), ('{"request_id": "7"}', None), ("[7]", None), ("[" * 1000, None),
])
def test_request_id_is_read_from_invalid_requests(text, request_id):
    assert read_request_id(text) == request_id


def test_requests_carry_an_attempt_number():
    request = MotionRequest(3, "turn_handle", "push", attempt=2)
    assert decode(MotionRequest, encode(request)).attempt == 2
    assert decode(FootstepRequest, encode(FootstepRequest(4, "stand", "pull"))).attempt == 0


def test_non_finite_figures_become_null_and_encode():
    assert (finite_or_none(math.nan), finite_or_none(-math.inf), finite_or_none(2.5)) == (None, None, 2.5)
    figures = MotionFigures(finite_or_none(math.nan), finite_or_none(math.inf), 40, 1, 0.0, Backend.SQP)
    text = encode(PlanningOutcome(1, OutcomeStatus.FAILURE, "diverged", 0.1, door_angle=None, motion=figures))
    decoded = decode(PlanningOutcome, text)
    assert decoded.motion is not None and decoded.motion.cost is None and decoded.motion.max_violation is None


@pytest.mark.parametrize("change, match", [
    ({"normal": (0.0, 0.0, 0.0)}, "not a unit vector"),
    ({"normal": (0.0, 0.0, 1.0)}, "not horizontal"),
    ({"width": 7.0}, "width"),
    ({"corners": ((0.0, 0.0, 0.0),)}, "four"),
    ({"confidence": 3.0}, "confidence"),
])
def test_door_estimates_a_planner_cannot_use_are_named(change, match):
    assert door_estimate_problem(ESTIMATE) is None
    assert match in door_estimate_problem(replace(ESTIMATE, **change))


def test_a_request_without_its_estimate_says_which_is_missing():
    assert requested_estimate_problem(None, -1.0) == "no door estimate yet"
    assert requested_estimate_problem(None, 12.5) == "door estimate of stamp 12.500 s was not received"
    assert requested_estimate_problem(ESTIMATE, 12.5) is None
    assert "not a unit vector" in requested_estimate_problem(replace(ESTIMATE, normal=(0.0, 0.0, 0.0)), -1.0)


def test_door_angles_out_of_range_are_named():
    assert door_angle_problem(0.3) is None and door_angle_problem(0.0) is None
    assert "1e+06" in door_angle_problem(1e6)
    assert door_angle_problem(-1.0) is not None


def test_discovery_stays_local_unless_set():
    env = {}
    assert keep_discovery_local(env) == "LOCALHOST" and env[DISCOVERY_RANGE] == "LOCALHOST"
    assert keep_discovery_local({DISCOVERY_RANGE: ""}) == "LOCALHOST"
    assert keep_discovery_local({DISCOVERY_RANGE: "SUBNET"}) == "SUBNET"  # the user's choice is kept
