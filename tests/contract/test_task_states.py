"""The task's states are the contract's vocabulary: each is spelled by its label, and only a
label names a state."""

import pytest

from door_contract.errors import ContractError
from door_contract.vocabulary import OPEN_DOOR_SUBSTATES, WALK_THROUGH_SUBSTATES, TaskEnd, TaskState


def test_a_sub_state_is_labelled_with_its_phase_first():
    assert TaskState.TURN_HANDLE.label == "OPEN_DOOR/TURN_HANDLE"
    assert TaskState.TUCK.label == "WALK_THROUGH/TUCK"
    assert TaskState.DETECT_DOOR.label == "DETECT_DOOR"
    assert all(state.is_open_door_substate for state in OPEN_DOOR_SUBSTATES)
    assert all(state.is_walk_through_substate for state in WALK_THROUGH_SUBSTATES)
    assert {state for state in TaskState if state.is_terminal} == {TaskState.DONE, TaskState.FAILED}


def test_the_terminal_states_are_the_task_ends_spelled_alike():
    """TaskReport.final_state (a TaskEnd) reads as the last /door_task/state (a label)."""
    assert {state.end: state.label for state in TaskState if state.is_terminal} == {end: end.value for end in TaskEnd}
    assert TaskState.WALK_THROUGH.end is None and TaskState.PAUSED.end is None


def test_of_label_inverts_label_for_every_state():
    assert [TaskState.of_label(state.label) for state in TaskState] == list(TaskState)
    assert len({state.label for state in TaskState}) == len(TaskState)


@pytest.mark.parametrize("text", ["TURN_HANDLE", "WALK_THROUGH/WALK_THROUGH", "done", "", "OPEN_DOOR"])
def test_anything_but_a_label_is_refused_naming_it(text):
    """A bare sub-state name is its value, not its spelling on the bus or in a report."""
    with pytest.raises(ContractError, match=f"unknown task state {text!r}"):
        TaskState.of_label(text)


def test_a_state_equals_no_string():
    """Not a StrEnum: a comparison with a label (or a value) must not be half true."""
    assert TaskState.DETECT_DOOR != "DETECT_DOOR"
    assert TaskState.TURN_HANDLE != "TURN_HANDLE" and TaskState.TURN_HANDLE != "OPEN_DOOR/TURN_HANDLE"
