"""A PyBullet DIRECT connection whose functions get its client id automatically.

Like ``pybullet_utils.bullet_client.PhysicsClient`` (same calling style: ``client.stepSimulation()``),
but it connects without an ``options`` string — PhysicsClient's ``options=""`` makes PyBullet
print ``argv[0]=`` on every connection — and disconnects exactly once.
"""

from __future__ import annotations

import functools
import inspect
from typing import Any

import pybullet

__all__ = ["PhysicsClient"]


class PhysicsClient:
    """One headless PyBullet physics server (DIRECT mode: no window, no GPU)."""

    def __init__(self) -> None:
        self.client_id: int = pybullet.connect(pybullet.DIRECT)
        if self.client_id < 0:
            raise RuntimeError("could not start a PyBullet DIRECT client")

    def __getattr__(self, name: str) -> Any:
        attribute = getattr(pybullet, name)
        if inspect.isbuiltin(attribute) and name != "disconnect":
            return functools.partial(attribute, physicsClientId=self.client_id)
        return attribute

    @property
    def connected(self) -> bool:
        return self.client_id >= 0

    def disconnect(self) -> None:
        """Stop the physics server (idempotent)."""
        if self.client_id >= 0:
            pybullet.disconnect(physicsClientId=self.client_id)
            self.client_id = -1
