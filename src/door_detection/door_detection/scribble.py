"""An operator's scribble checked on arrival, before it replaces automatic detection.

Issue #12: a scribble at (1e6, 1e6) was accepted and then made every frame fail for
``scribble_timeout`` (30 s): the operator-aided pipeline refuses it per frame, but the node
had already switched to it. Checked here once, against the camera's image size: at least
``min_points`` finite points (a dot is enough: the pipeline grows it), at most
``max_points`` (a scribble is a few strokes, not an image), all inside the image.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_SCRIBBLE_POINTS", "scribble_problem"]

MAX_SCRIBBLE_POINTS = 10_000


def scribble_problem(points: np.ndarray, width: int | None, height: int | None, min_points: int = 1,
                     max_points: int = MAX_SCRIBBLE_POINTS) -> str | None:
    """Why the (N, 2) pixel ``points`` cannot be used on a ``width`` × ``height`` image, or None."""
    if width is None or height is None:
        return "no camera image has arrived yet to check it against"
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < min_points:
        return f"it has {len(points)} point(s); at least {min_points} needed"
    if len(points) > max_points:
        return f"it has {len(points)} points; at most {max_points} accepted"
    if not np.all(np.isfinite(points)):
        return "it contains NaN or infinity"
    outside = (points[:, 0] < 0) | (points[:, 0] > width - 1) | (points[:, 1] < 0) | (points[:, 1] > height - 1)
    if outside.any():
        return f"{int(outside.sum())} of its {len(points)} points lie outside the {width}×{height} image"
    return None
