"""The sequential vote ([Banerjee 2015] Sec. III-A's 10-frame vote, stopping when the evidence suffices)."""

from __future__ import annotations

import numpy as np
import pytest

from door_contract.vocabulary import DetectionMode, Side
from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.options import DetectionOptions
from door_detection.voting import Voter, precision


def _estimate(x: float, normal=(0.0, 0.0, -1.0), side: Side = Side.LEFT, y: float = 0.1) -> DetectedDoor:
    corners = np.array([[-0.45, 1.0, 2.0], [0.45, 1.0, 2.0], [0.45, -1.0, 2.0], [-0.45, -1.0, 2.0]])
    return DetectedDoor(np.array([x, y, 2.0]), np.array(normal), side, 0.9, corners, 0.95,
                        DetectionMode.AUTOMATIC)


def test_two_agreeing_frames_confirm_at_once() -> None:
    voter = Voter(DetectionOptions(vote_frames=10))
    first = voter.add(_estimate(0.300))
    assert first.outcome is DetectionOutcome.VOTING          # one frame is never enough by default
    second = voter.add(_estimate(0.3005))
    assert second.outcome is DetectionOutcome.DETECTED and second.agreeing == 2
    assert abs(second.estimate.handle_position[0] - 0.30025) < 1e-9   # the mean
    assert second.estimate.frames_voted == 2 and second.estimate.confidence == 0.2
    assert second.confidence == pytest.approx(12.706 * 0.00025, rel=1e-3)   # t(1)·s/√2


def test_an_outlier_delays_the_vote_until_the_door_has_the_majority() -> None:
    voter = Voter(DetectionOptions(vote_frames=10))
    outcomes = [voter.add(_estimate(x)).outcome for x in (0.30, 0.80, 0.301)]   # 0.80: a wrong handle
    assert outcomes == [DetectionOutcome.VOTING, DetectionOutcome.VOTING, DetectionOutcome.DETECTED]
    result = voter.decide()
    assert result.agreeing == 2 and abs(result.estimate.handle_position[0] - 0.3005) < 1e-9


def test_scattered_estimates_wait_for_more_frames() -> None:
    """Handles scattered by ±1 cm (stereo noise at 4 m) agree (3 cm) but the 95 % interval of
    their mean is not within 1 cm from a few frames; the vote confirms once it is."""
    voter = Voter(DetectionOptions(vote_frames=10))
    xs = [0.29, 0.31, 0.295, 0.305, 0.30, 0.30, 0.30, 0.30]
    results = [voter.add(_estimate(x)) for x in xs]
    confirmed = [r.ok for r in results]
    assert not any(confirmed[:3]) and confirmed[-1]
    first = confirmed.index(True)
    assert results[first].confidence <= 0.01 < results[first - 1].confidence
    assert abs(results[-1].estimate.handle_position[0] - 0.30) < 1e-9


def test_two_noisy_frames_that_happen_to_agree_wait_for_a_third() -> None:
    """3 mm apart: a standard error of 1.5 mm, but with one degree of freedom the 95 % interval
    is ±1.9 cm (t = 12.7); a third close frame (t = 4.3) confirms."""
    voter = Voter(DetectionOptions(vote_frames=10))
    assert not [voter.add(_estimate(x)).ok for x in (0.300, 0.303)][-1]
    assert voter.add(_estimate(0.301)).ok


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
    tilt = (np.sin(np.radians(0.1)), 0.0, -np.cos(np.radians(0.1)))
    voter.add(_estimate(0.3))
    result = voter.add(_estimate(0.3005, normal=tilt))
    assert result.ok
    assert np.isclose(np.linalg.norm(result.estimate.normal), 1.0)
    voter.reset()
    assert len(voter) == 0 and voter.decide().outcome is DetectionOutcome.VOTING


def test_normals_apart_wait_until_their_mean_is_precise() -> None:
    tilt = (np.sin(np.radians(2.0)), 0.0, -np.cos(np.radians(2.0)))
    handle_error, normal_error = precision([_estimate(0.3), _estimate(0.3, normal=tilt)])
    assert handle_error == 0.0 and normal_error == pytest.approx(12.706, rel=1e-3)   # t(1) × RMS 1° over √1
    slight = (np.sin(np.radians(0.5)), 0.0, -np.cos(np.radians(0.5)))
    voter = Voter(DetectionOptions(vote_frames=10))
    voter.add(_estimate(0.3))
    assert not voter.add(_estimate(0.3, normal=slight)).ok             # 12.7 × 0.25° = 3.2° > 1°
    assert voter.add(_estimate(0.3)).ok                                # 4.3 × 0.167° = 0.72°


def test_single_frame_vote_when_allowed() -> None:
    result = Voter(DetectionOptions(vote_frames=1, vote_min_agreeing=1)).add(_estimate(0.3))
    assert result.ok and result.estimate.confidence == 1.0
