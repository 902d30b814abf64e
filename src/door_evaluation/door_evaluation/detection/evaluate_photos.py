"""Evaluation of the 2-D stage on real door photographs with YOLO labels.

``python -m door_evaluation.detection.evaluate_photos [--data DIR] [--limit N] [--threshold S]``

The photographs (``shared/data/doors/detectdoor``: 27 labelled doors-with-handles and 4
images without annotations; classes 0 door, 1 handle, 2 cabinet door, 3 refrigerator
door) have no depth, so only the 2-D stage of Sec. III-A runs: lines, pairing by pixel
geometry and the colour handle blob (:mod:`~door_detection.proposals`).  Each image is
shrunk so that its longer side is ``MAX_SIDE`` px; the line length threshold is
``MIN_LINE_FRACTION`` of the image height (photos vary in size and framing).

Reported (IoU ≥ 0.5 against the labelled boxes):

* doors found: fraction of labelled doors matched by a proposal scoring ≥ threshold;
* top-1 precision: fraction of labelled images whose best proposal (≥ threshold) is a door;
* handles found: fraction of labelled handles matched by a handle box of those proposals,
  and, more leniently, whose box contains the proposed handle's centre;
* false detections: fraction of images *without* that class (the 4 unannotated images;
  caveat from SOURCES.md: an empty label does not always mean no door) with a proposal.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

from door_detection.errors import InputError
from door_detection.options import DetectionOptions
from door_detection.progress import ProgressBar
from door_detection.proposals import Box, DoorProposal, iou, propose_doors
from door_robot.locations import shared_data_dir

__all__ = ["DOOR", "evaluate", "load_dataset", "main"]

MAX_SIDE = 1024
MIN_LINE_FRACTION = 0.25
IOU_MATCH = 0.5
DOOR, HANDLE = 0, 1
DEFAULT_THRESHOLD = 1.8
"""Proposal score (:mod:`~door_detection.proposals`) counted as a detection."""


@dataclass(frozen=True)
class LabelledImage:
    """One photograph: its path and labelled boxes (pixels of the original image) by class."""

    path: Path
    boxes: tuple[tuple[int, Box], ...]

    def of_class(self, label: int) -> list[Box]:
        return [box for cls, box in self.boxes if cls == label]


@dataclass(frozen=True)
class PhotoReport:
    """Fractions in [0, 1] (nan when nothing to count) and the counts behind them."""

    images: int
    doors: int
    handles: int
    negatives: int
    door_found: float
    door_top1_precision: float
    handle_found: float
    handle_centre_hit: float
    door_false_detections: float
    handle_false_detections: float

    def text(self) -> str:
        return "\n".join([
            f"{self.images} images: {self.doors} labelled doors, {self.handles} labelled handles, "
            f"{self.negatives} images without annotations",
            f"  doors found (IoU ≥ {IOU_MATCH}):        {self.door_found:6.1%}",
            f"  best proposal is a door:        {self.door_top1_precision:6.1%}",
            f"  handles found (IoU ≥ {IOU_MATCH}):      {self.handle_found:6.1%}",
            f"  handles found (centre in box):  {self.handle_centre_hit:6.1%}",
            f"  false door detections on images without doors:     {self.door_false_detections:6.1%}",
            f"  false handle detections on images without handles: {self.handle_false_detections:6.1%}",
        ])


def default_data_dir() -> Path:
    """``$DOOR_SHARED_DATA/doors/detectdoor``, else ``<repo>/../shared/data/doors/detectdoor``."""
    return shared_data_dir() / "doors" / "detectdoor"


def load_dataset(folder: Path) -> list[LabelledImage]:
    """Every image of ``folder/images`` with its ``folder/labels/<stem>.txt`` boxes."""
    images = []
    for path in sorted((folder / "images").iterdir()):
        label_file = folder / "labels" / f"{path.stem}.txt"
        if path.suffix.lower() not in (".jpg", ".jpeg", ".png") or not label_file.exists():
            continue
        shape = _read_bgr(path).shape
        images.append(LabelledImage(path, tuple(_parse_labels(label_file, shape[1], shape[0]))))
    return images


def _read_bgr(path: Path) -> np.ndarray:
    """The image at ``path`` (BGR), or :class:`InputError` naming it (``cv2.imread`` returns None)."""
    bgr = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if bgr is None:
        raise InputError(f"cannot read the image {path}")
    return np.asarray(bgr)


def _scaled_box(box: Box, scale: float) -> Box:
    """``box`` (x0, y0, x1, y1 px) of an image scaled by ``scale``, in the original's pixels."""
    x0, y0, x1, y1 = box
    return x0 / scale, y0 / scale, x1 / scale, y1 / scale


def _parse_labels(path: Path, width: int, height: int) -> list[tuple[int, Box]]:
    """YOLO lines ``class cx cy w h`` (normalised) → (class, pixel box)."""
    boxes = []
    for line in path.read_text().splitlines():
        parts = line.split()
        if len(parts) != 5:
            continue
        cls, cx, cy, w, h = int(parts[0]), *map(float, parts[1:])
        boxes.append((cls, ((cx - w / 2) * width, (cy - h / 2) * height,
                            (cx + w / 2) * width, (cy + h / 2) * height)))
    return boxes


@dataclass(frozen=True)
class _ImageResult:
    image: LabelledImage
    proposals: tuple[DoorProposal, ...]


def detect_image(image: LabelledImage, threshold: float) -> _ImageResult:
    """Proposals (boxes mapped back to the original pixels) scoring ≥ ``threshold``."""
    bgr = _read_bgr(image.path)
    scale = min(1.0, MAX_SIDE / max(bgr.shape[:2]))
    if scale < 1.0:
        bgr = cv2.resize(bgr, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
    rgb = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
    options = DetectionOptions(min_line_length=MIN_LINE_FRACTION * rgb.shape[0])
    proposals = tuple(DoorProposal(_scaled_box(p.box, scale), p.corners / scale, p.score,
                                   None if p.handle_box is None else _scaled_box(p.handle_box, scale))
                      for p in propose_doors(rgb, options) if p.score >= threshold)
    return _ImageResult(image, proposals)


def summarise(results: Sequence[_ImageResult]) -> PhotoReport:
    """The report's fractions over all images."""
    doors = [(r, box) for r in results for box in r.image.of_class(DOOR)]
    handles = [(r, box) for r in results for box in r.image.of_class(HANDLE)]
    labelled = [r for r in results if r.image.of_class(DOOR)]
    no_doors = [r for r in results if not r.image.of_class(DOOR)]
    no_handles = [r for r in results if not r.image.of_class(HANDLE)]
    door_found = _fraction([any(iou(box, p.box) >= IOU_MATCH for p in r.proposals) for r, box in doors])
    top1 = _fraction([bool(r.proposals) and any(iou(r.proposals[0].box, box) >= IOU_MATCH
                                                 for box in r.image.of_class(DOOR)) for r in labelled])

    def handle_boxes(r: _ImageResult) -> list[Box]:
        return [p.handle_box for p in r.proposals if p.handle_box is not None]

    handle_found = _fraction([any(iou(box, h) >= IOU_MATCH for h in handle_boxes(r)) for r, box in handles])
    centre_hit = _fraction([any(_contains(box, h) for h in handle_boxes(r)) for r, box in handles])
    return PhotoReport(len(results), len(doors), len(handles), len(no_doors), door_found, top1, handle_found,
                       centre_hit, _fraction([bool(r.proposals) for r in no_doors]),
                       _fraction([bool(handle_boxes(r)) for r in no_handles]))


def _contains(box: Box, inner: Box) -> bool:
    cx, cy = (inner[0] + inner[2]) / 2, (inner[1] + inner[3]) / 2
    return box[0] <= cx <= box[2] and box[1] <= cy <= box[3]


def _fraction(flags: Sequence[bool]) -> float:
    return float(np.mean(flags)) if len(flags) else float("nan")


def evaluate(images: Sequence[LabelledImage], threshold: float = DEFAULT_THRESHOLD,
             progress: bool = True) -> PhotoReport:
    """Run the 2-D stage on ``images`` and summarise."""
    bar = ProgressBar(len(images), enabled=progress)
    results = []
    for image in images:
        results.append(detect_image(image, threshold))
        bar.advance(image.path.name)
    bar.close()
    return summarise(results)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path, default=None, help="folder with images/ and labels/")
    parser.add_argument("--limit", type=int, default=None, help="only the first N images")
    parser.add_argument("--threshold", type=float, default=DEFAULT_THRESHOLD,
                        help="proposal score to count as a detection")
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    folder = args.data if args.data is not None else default_data_dir()
    if not (folder / "images").is_dir():
        parser.error(f"no images under {folder} (set --data or DOOR_SHARED_DATA)")
    images = load_dataset(folder)[: args.limit]
    print(evaluate(images, args.threshold, progress=not args.no_progress).text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
