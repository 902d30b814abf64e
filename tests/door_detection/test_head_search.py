"""The graph's head search, frames in and neck moves out: no move before the neck is known,
a view counts only once the neck is there, a used-up view moves on, a confirmed door ends it,
and a search out of views looks home and starts over."""

from __future__ import annotations

import pytest

from door_detection.errors import DetectionError
from door_detection.head_search import HeadSearch, HeadSearchOptions, LookCommand, home_view
from door_detection.view_search import Neck, NeckAxis, ViewSearchOptions

NECK = Neck(NeckAxis("pan", -1.309, 1.309, 1.0, velocity=1.0), NeckAxis("tilt", -0.262, 0.785, 1.0, velocity=1.0))
HOME = {"pan": 0.0, "tilt": 0.1}
FRAME_PERIOD = 0.125  # s: the standing camera's 8 Hz


class Camera:
    """Frame stamps (s, robot clock) at FRAME_PERIOD, one per call."""

    def __init__(self) -> None:
        self.time = 0.0

    def __call__(self) -> float:
        self.time += FRAME_PERIOD
        return self.time


def _at(command: LookCommand) -> dict[str, float]:
    """The neck where ``command`` takes it."""
    return dict(zip(command.joint_names, command.goal))


def test_nothing_is_asked_before_the_neck_is_known_and_an_empty_view_is_left_after_two_frames() -> None:
    frame = Camera()
    search = HeadSearch(NECK)
    assert search.after_frame(frame(), None, False, False) is None and not search.searching
    assert search.after_frame(frame(), HOME, False, False) is None  # the home view's first empty frame
    move = search.after_frame(frame(), HOME, False, False)
    assert move is not None and _at(move) == pytest.approx({"pan": 0.3, "tilt": 0.1})
    assert move.duration == pytest.approx(0.3 / 0.5)  # at half the neck's 1 rad/s


def test_frames_before_the_neck_arrives_do_not_count_for_the_view() -> None:
    frame = Camera()
    search = HeadSearch(NECK, HeadSearchOptions(max_settle_frames=3))
    search.after_frame(frame(), HOME, False, False)
    first = search.after_frame(frame(), HOME, False, False)
    assert first is not None
    assert search.after_frame(frame(), HOME, False, False) is None  # still at home: unsettled, not counted
    assert search.after_frame(frame(), _at(first), False, False) is None  # there: the view's first empty frame
    second = search.after_frame(frame(), _at(first), False, False)
    assert second is not None and _at(second)["pan"] == pytest.approx(-0.3)


def test_a_neck_that_never_arrives_counts_after_max_settle_frames() -> None:
    """Frames count anyway once the move's duration is over and max_settle_frames more came."""
    frame = Camera()
    search = HeadSearch(NECK, HeadSearchOptions(max_settle_frames=2))
    search.after_frame(frame(), HOME, False, False)
    move = search.after_frame(frame(), HOME, False, False)
    assert move is not None
    arrival = frame.time + move.duration
    while frame.time + FRAME_PERIOD < arrival:
        assert search.after_frame(frame(), HOME, False, False) is None  # moving: not counted
    assert search.after_frame(frame(), HOME, False, False) is None   # unsettled 1
    assert search.after_frame(frame(), HOME, False, False) is None   # unsettled 2: counts, first empty frame
    assert search.after_frame(frame(), HOME, False, False) is not None  # second empty frame: moves on


def test_a_confirmed_door_ends_the_search_where_the_head_is() -> None:
    frame = Camera()
    search = HeadSearch(NECK)
    search.after_frame(frame(), HOME, False, False)
    assert search.searching
    assert search.after_frame(frame(), HOME, True, True) is None and not search.searching


def test_a_search_out_of_views_looks_home_and_starts_over() -> None:
    views = ViewSearchOptions(max_pan=0.3, tilt_offsets=(), max_body_turns=0)
    frame = Camera()
    search = HeadSearch(NECK, HeadSearchOptions(views=views, max_settle_frames=1))
    joints, moves = dict(HOME), []
    for _ in range(12):
        move = search.after_frame(frame(), joints, False, False)
        if move is not None:
            moves.append(_at(move))
            joints = _at(move)
    pans = [round(m["pan"], 3) for m in moves]
    assert pans[:3] == [0.3, -0.3, 0.0]  # the views 0, +0.3, −0.3, then home
    assert pans[3:5] == [0.3, -0.3]      # and the same search again


def test_the_home_view_is_the_necks_look_and_bad_options_are_refused() -> None:
    assert home_view(NECK, {"pan": -0.2, "tilt": 0.3}).pan == pytest.approx(-0.2)
    with pytest.raises(DetectionError, match="settle_tolerance"):
        HeadSearchOptions(settle_tolerance=0.0)
    with pytest.raises(DetectionError, match="neck"):
        HeadSearch(Neck(None, None))


def test_frames_during_a_long_move_do_not_use_up_the_view() -> None:
    """A 2.4 s pan at 8 Hz spans 19 frames, far more than max_settle_frames: the head must get
    there before the view's frames count (they were counted from the move's start, and the
    search left the view the head was still turning to)."""
    frame = Camera()
    slow = Neck(NeckAxis("pan", -1.309, 1.309, 1.0, velocity=0.25), NeckAxis("tilt", -0.262, 0.785, 1.0, velocity=0.25))
    search = HeadSearch(slow, HeadSearchOptions(max_settle_frames=2))
    search.after_frame(frame(), HOME, False, False)
    move = search.after_frame(frame(), HOME, False, False)
    assert move is not None and move.duration == pytest.approx(0.3 / 0.125)  # 2.4 s at half of 0.25 rad/s
    arrival = frame.time + move.duration
    while frame.time + FRAME_PERIOD < arrival:  # on the way: none of these count
        assert search.after_frame(frame(), HOME, False, False) is None
    assert search.after_frame(frame(), _at(move), False, False) is None  # there: the view's first empty frame
    assert search.after_frame(frame(), _at(move), False, False) is not None  # second: moves on
