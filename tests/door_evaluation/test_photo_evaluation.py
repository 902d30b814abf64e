"""The photo evaluation runs and returns sane numbers on real photographs (no timing asserts)."""

from __future__ import annotations

import math

import pytest

from door_evaluation.detection import evaluate_photos


def test_photo_evaluation_on_three_labelled_photos(shared_data) -> None:
    images = [image for image in evaluate_photos.load_dataset(shared_data / "doors" / "detectdoor")
              if image.of_class(evaluate_photos.DOOR)][:3]
    assert len(images) == 3
    report = evaluate_photos.evaluate(images, progress=False)
    assert report.images == 3 and report.doors >= 3 and report.handles >= 3
    for value in (report.door_found, report.door_top1_precision, report.handle_found,
                  report.handle_centre_hit):
        assert 0.0 <= value <= 1.0
    assert math.isnan(report.door_false_detections)          # no image without doors among the 3
    assert "doors found" in report.text()


def test_photo_labels_are_parsed_in_pixels(shared_data) -> None:
    dataset = evaluate_photos.load_dataset(shared_data / "doors" / "detectdoor")
    images = {image.path.stem: image for image in dataset}
    door = images["000c9e454bbf6d0d"].of_class(evaluate_photos.DOOR)[0]   # 678×1024, cx 0.477
    assert door[0] == pytest.approx((0.477344 - 0.479688 / 2) * 678, abs=0.5)
    assert images["00eb261110ac46c5"].boxes == ()                         # a negative
