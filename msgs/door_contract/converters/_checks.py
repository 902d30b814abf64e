"""Shared finiteness checks for the converters."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from door_contract.errors import NonFiniteError

__all__ = ["require_finite"]


def require_finite(values: npt.ArrayLike, what: str) -> np.ndarray:
    """``values`` as a float array, or :class:`NonFiniteError` naming ``what``."""
    array = np.asarray(values, dtype=float)
    if not np.all(np.isfinite(array)):
        raise NonFiniteError(f"{what} contains NaN or infinity")
    return array
