"""Errors of the robot-profile and kinematics package."""


class RobotModelError(ValueError):
    """A profile that cannot be loaded or used: missing URDF, unknown joint or frame."""
