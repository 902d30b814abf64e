"""Errors of the simulation bridge's ROS-free core.

:class:`SimulationError` is the package's one base error; it is not a :class:`ValueError`,
so a bug's ``ValueError`` is never reported as a bad configuration or command.
"""

__all__ = ["SimulationError"]


class SimulationError(Exception):
    """A configuration value out of range, an unknown joint or link, or a misuse of the world.

    The message names the field (or joint) and, for ranges, the allowed interval, so a node
    can log it verbatim and refuse to start.
    """
