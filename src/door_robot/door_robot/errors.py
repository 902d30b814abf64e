"""Errors of the robot-profile and kinematics package.

:class:`RobotModelError` is the package's one base error; it is not a :class:`ValueError`, so
callers catch it by name and a bug's ``ValueError`` is never taken for a bad profile.
"""

__all__ = ["RobotModelError"]


class RobotModelError(Exception):
    """A profile that cannot be loaded or used: missing URDF, unknown joint or frame."""
