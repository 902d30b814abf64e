"""Converters between standard ROS 2 messages and the cores' numpy / dataclass values."""
