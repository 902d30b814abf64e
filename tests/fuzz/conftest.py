"""The fuzz suite's shared fixtures."""

import pytest


@pytest.fixture(scope="module")
def rclpy_module_context():
    """An rclpy context for one test module (its nodes under test start once per module)."""
    import rclpy

    context = rclpy.Context()
    rclpy.init(context=context)
    yield context
    rclpy.try_shutdown(context=context)
