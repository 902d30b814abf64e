"""The sequential vote (seed 001 Sec. III-A's 10-frame vote, stopping when the evidence suffices)."""

from __future__ import annotations

import numpy as np

from door_detection.estimate import DetectionMode, DetectionOutcome, DetectionResult, DoorEstimate, Side
from door_detection.options import DetectionOptions
from door_detection.voting import Voter, precision


def _estimate(x: float, normal=(0.0, 0.0, -1.0), side: Side = Side.LEFT, y: float = 0.1) -> DoorEstimate:
    corners = np.array([[-0.45, 1.0, 2.0], [0.45, 1.0, 2.0], [0.45, -1.0, 2.0], [-0.45, -1.0, 2.0]])
    return DoorEstimate(np.array([x, y, 2.0]), np.array(normal), side, 0.9, corners, 0.95,
                        DetectionMode.AUTOMATIC)


def test_two_agreeing_frames_confirm_at_once() -> None:
    voter = Voter(DetectionOptions(vote_frames=10))
    first = voter.add(_estimate(0.300))
    assert first.outcome is DetectionOutcome.VOTING          # one frame is never enough by default
    second = voter.add(_estimate(0.302))
    assert second.outcome is DetectionOutcome.DETECTED and second.agreeing == 2
    assert abs(second.estimate.handle_position[0] - 0.301) < 1e-9     # the mean
    assert second.estimate.frames_voted == 2 and second.estimate.confidence == 0.2
    assert second.standard_error < 0.005


def test_an_outlier_delays_the_vote_until_the_door_has_the_majority() -> None:
    voter = Voter(DetectionOptions(vote_frames=10))
    outcomes = [voter.add(_estimate(x)).outcome for x in (0.30, 0.80, 0.301)]   # 0.80: a wrong handle
    assert outcomes == [DetectionOutcome.VOTING, DetectionOutcome.VOTING, DetectionOutcome.DETECTED]
    result = voter.decide()
    assert result.agreeing == 2 and abs(result.estimate.handle_position[0] - 0.3005) < 1e-9


def test_scattered_estimates_wait_for_more_frames() -> None:
    """Handles scattered by ±1.5 cm (stereo noise at 4 m) agree (3 cm) but their mean is not
    precise to 5 mm from two or three frames; the vote confirms once it is."""
    voter = Voter(DetectionOptions(vote_frames=10))
    xs = [0.285, 0.315, 0.29, 0.31, 0.30, 0.30, 0.30, 0.30]
    results = [voter.add(_estimate(x)) for x in xs]
    confirmed = [r.ok for r in results]
    assert not any(confirmed[:3]) and confirmed[-1]
    first = confirmed.index(True)
    assert results[first].standard_error <= 0.005 < results[first - 1].standard_error


def test_failed_frames_do_not_count_against_a_door() -> None:
    """While the head searches, most frames see no door; they neither confirm nor block one."""
    voter = Voter(DetectionOptions(vote_frames=6))
    failure = DetectionResult(DetectionOutcome.NO_VERTICAL_LINES, None, "no lines")
    outcomes = [voter.add(item).outcome for item in (failure, None, failure, _estimate(0.3), None, _estimate(0.3))]
    assert outcomes == [DetectionOutcome.VOTING] * 5 + [DetectionOutcome.DETECTED]
    for _ in range(6):
        last = voter.add(None)
    assert last.outcome is DetectionOutcome.NO_CONSENSUS     # the window forgot the door


def test_normals_and_hinge_sides_must_agree_too() -> None:
    voter = Voter(DetectionOptions(vote_frames=3))
    tilted = (np.sin(np.radians(10)), 0.0, -np.cos(np.radians(10)))
    voter.add(_estimate(0.3))
    voter.add(_estimate(0.3, normal=tilted))
    result = voter.add(_estimate(0.3, side=Side.RIGHT))
    assert result.outcome is DetectionOutcome.NO_CONSENSUS


def test_consensus_normal_is_a_unit_vector_and_reset_forgets() -> None:
    voter = Voter(DetectionOptions(vote_frames=3))
    tilt = (np.sin(np.radians(0.4)), 0.0, -np.cos(np.radians(0.4)))
    voter.add(_estimate(0.3))
    result = voter.add(_estimate(0.301, normal=tilt))
    assert result.ok
    assert np.isclose(np.linalg.norm(result.estimate.normal), 1.0)
    voter.reset()
    assert len(voter) == 0 and voter.decide().outcome is DetectionOutcome.VOTING


def test_normals_apart_wait_until_their_mean_is_precise() -> None:
    tilt = (np.sin(np.radians(2.0)), 0.0, -np.cos(np.radians(2.0)))
    handle_error, normal_error = precision([_estimate(0.3), _estimate(0.3, normal=tilt)])
    assert handle_error == 0.0 and abs(normal_error - 1.0) < 0.01   # RMS 1° over √1
    slight = (np.sin(np.radians(1.2)), 0.0, -np.cos(np.radians(1.2)))
    voter = Voter(DetectionOptions(vote_frames=10))
    voter.add(_estimate(0.3))
    assert not voter.add(_estimate(0.3, normal=slight)).ok             # 0.6° > 0.5°
    assert voter.add(_estimate(0.3)).ok                                # 0.4°


def test_single_frame_vote_when_allowed() -> None:
    result = Voter(DetectionOptions(vote_frames=1, vote_min_agreeing=1)).add(_estimate(0.3))
    assert result.ok and result.estimate.confidence == 1.0
