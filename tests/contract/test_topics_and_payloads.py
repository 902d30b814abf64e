"""The topic table is complete, unique and resolvable; JSON payloads reject bad input."""

import json
import re

import pytest

from door_contract.errors import ContractError, NonFiniteError
from door_contract.payloads import (
    ExecutionKind,
    ExecutionOutcome,
    FootstepFigures,
    MotionFigures,
    OutcomeStatus,
    PlanningOutcome,
    StateAttempt,
    TaskReport,
    decode,
    decode_document,
    encode,
    encode_document,
)
from door_contract.qos import Durability
from door_contract.topics import Services, Topics
from door_contract.vocabulary import AttemptOutcome, Autonomy, Backend, DoorOpening, TaskEnd, TaskState

DESIGN_TOPICS = {
    "/clock", "/joint_states", "/odom", "/head_camera/color/image_raw",
    "/head_camera/color/camera_info", "/head_camera/depth/image_raw",
    "/head_camera/depth/camera_info", "/sim/door_joint_states", "/arm_controller/joint_trajectory",
    "/footstep_plan", "/door/handle_pose", "/door/markers", "/operator/scribble", "/door_task/state",
    "/door_task/approval_request", "/door_task/operator", "/diagnostics",
}


def test_every_design_topic_is_in_the_contract_once():
    names = [topic.name for topic in Topics.all()]
    assert len(names) == len(set(names))
    assert DESIGN_TOPICS <= set(names)
    assert {s.name for s in Services.all()} == {"/left_hand/grasp", "/right_hand/grasp"}


def test_every_type_resolves_to_a_standard_message():
    for topic in Topics.all():
        cls = topic.msg_class()
        assert cls.__name__ == topic.type_name.rsplit("/", 1)[1]
    for service in Services.all():
        assert hasattr(service.srv_class(), "Request")


def test_latched_topics_are_transient_local():
    for topic in (Topics.TASK_STATE, Topics.APPROVAL_REQUEST):
        assert topic.qos.durability is Durability.TRANSIENT_LOCAL
        assert topic.qos.to_profile().depth == 1


def test_payload_round_trip():
    outcome = ExecutionOutcome(ExecutionKind.TRAJECTORY, 42, OutcomeStatus.REJECTED, "unknown joint x")
    assert decode(ExecutionOutcome, encode(outcome)) == outcome
    planning = PlanningOutcome(3, OutcomeStatus.SUCCESS, planning_time_s=0.01, stamp_ns=17,
                               footsteps=FootstepFigures(240, steps=12, length_m=3.1))
    assert decode(PlanningOutcome, encode(planning)) == planning
    motion = PlanningOutcome(4, OutcomeStatus.SUCCESS, "", 0.2, 18, door_angle=0.35, motion=MotionFigures(
        1.5, 2e-6, 30, 1, 4.0, Backend.SQP, ("arm_right_1_joint",), ((0.0,), (0.5,)), ((0.0,), (0.4,))))
    assert decode(PlanningOutcome, encode(motion)) == motion


def test_a_task_report_lists_typed_state_attempts_and_its_json_stays_an_object_per_attempt():
    attempts = (StateAttempt(TaskState.DETECT_DOOR, 1, AttemptOutcome.SUCCEEDED, 0.4, 2.0, 0.0, "",
                             {"width_m": 0.914, "hinge": "left"}, robot_s=0.75),
                StateAttempt(TaskState.TURN_HANDLE, 2, AttemptOutcome.UNFINISHED, 0.1))
    report = TaskReport(TaskEnd.FAILED, "aborted", DoorOpening.PUSH, Autonomy.FULL, attempts, "wall")
    text = encode(report)
    assert decode(TaskReport, text) == report
    first, second = json.loads(text)["attempts"]
    assert first == {"state": "DETECT_DOOR", "attempt": 1, "outcome": "succeeded", "planning_s": 0.4,
                     "waiting_s": 2.0, "moving_s": 0.0, "reason": "", "summary": {"width_m": 0.914, "hinge": "left"},
                     "robot_s": 0.75}
    assert second["state"] == "OPEN_DOOR/TURN_HANDLE"  # the label, as /door_task/state publishes it
    assert encode_document(attempts[1]) == second


def test_an_attempt_of_an_old_report_file_reads_back_typed():
    """Campaigns resume from the trial.json / report.json files they wrote: an object per
    attempt, its state a label; one written before ``robot_s`` existed reads back with 0."""
    old = {"state": "WALK_THROUGH/TUCK", "attempt": 1, "outcome": "fell", "planning_s": 0.3, "waiting_s": 0.0,
           "moving_s": 2.5, "reason": "the robot fell: tilt", "summary": {"cost": 1.5, "backend": "sqp"}}
    attempt = decode_document(StateAttempt, old)
    assert attempt.state is TaskState.TUCK and attempt.outcome is AttemptOutcome.FELL
    assert attempt.summary == {"cost": 1.5, "backend": "sqp"}
    assert attempt.robot_s == 0.0 and encode_document(attempt) == {**old, "robot_s": 0.0}


@pytest.mark.parametrize("state, match", [
    ("TURN_HANDLE", "unknown state 'TURN_HANDLE'; use one of DETECT_DOOR, WALK_TO_DOOR, OPEN_DOOR/MOVE_TO_HANDLE"),
    ("dance", "StateAttempt.state: unknown state 'dance'"),
    (3, "StateAttempt.state: expected a string"),
    (["DETECT_DOOR"], "StateAttempt.state: expected a string"),
])
def test_an_attempt_names_its_state_by_its_label_only(state, match):
    with pytest.raises(ContractError, match=re.escape(match)):
        decode_document(StateAttempt, {"state": state, "attempt": 1, "outcome": "failed"})


@pytest.mark.parametrize("document, match", [
    ({"motion": {"cost": 1.0}}, "PlanningOutcome.motion: .*required"),
    ({"footsteps": {"expansions": 3, "steps": "many"}}, "PlanningOutcome.footsteps.steps: expected an integer"),
    ({"footsteps": [3]}, "PlanningOutcome.footsteps: expected a JSON object"),
    ({"motion": {"cost": None, "max_violation": None, "iterations": 1, "attempts": 1, "duration_s": 1.0,
                 "backend": "sqp", "joint_names": [1]}}, "joint_names: expected a string"),
    ({"details": {"stamp_ns": 5}}, "unknown field"),
])
def test_malformed_figures_are_refused_naming_the_field(document, match):
    with pytest.raises(ContractError, match=match):
        decode(PlanningOutcome, json.dumps({"request_id": 1, "status": "success", **document}))


@pytest.mark.parametrize("text, error, match", [
    ("not json", ContractError, "not JSON"),
    ('{"kind": "dance", "request_id": 1, "status": "success"}', ContractError, "dance"),
    ('{"kind": "trajectory", "request_id": 1, "status": "success", "extra": 1}', ContractError, "extra"),
    ('{"kind": "trajectory", "request_id": "1", "status": "success"}', ContractError, "integer"),
    ('{"kind": "trajectory", "status": "success"}', ContractError, "request_id"),
    ('{"kind": "trajectory", "request_id": 1, "status": "success", "duration_s": NaN}', NonFiniteError, "duration_s"),
])
def test_bad_payloads(text, error, match):
    with pytest.raises(error, match=match):
        decode(ExecutionOutcome, text)


def test_readme_topic_table_lists_every_topic():
    from door_bringup.workspace import repository_root

    readme = (repository_root() / "README.md").read_text()
    for topic in Topics.all():
        assert f"`{topic.name}`" in readme, topic.name
    for service in Services.all():
        assert f"`{service.name}`" in readme, service.name


def test_door_estimate_round_trip_and_nan_rejected():
    from door_contract.payloads import DoorEstimate
    from door_contract.vocabulary import HingeSide

    estimate = DoorEstimate(1.5, "odom", (1.0, 0.3, 0.9), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                            ((1.0, -0.45, 0.0), (1.0, 0.45, 0.0), (1.0, 0.45, 2.0), (1.0, -0.45, 2.0)),
                            0.9, 10, "automatic")
    assert decode(DoorEstimate, encode(estimate)) == estimate
    broken = encode(estimate).replace("0.3, 0.9]", "0.3, 1e999]")
    with pytest.raises(NonFiniteError, match="handle_position"):
        decode(DoorEstimate, broken)
