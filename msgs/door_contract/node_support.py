"""What every node of the graph shares: declaring validated parameters and the canonical main.

This is the only module of the contract that imports rclpy at module level.
"""

from __future__ import annotations

import difflib
import math
import signal
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import Any, Protocol

import rclpy
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor
from rclpy.clock import Clock, ClockType
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

from door_contract.converters.diagnostics import Health, diagnostic_array
from door_contract.errors import ParameterRangeError
from door_contract.network import keep_discovery_local
from door_contract.parameters import ParameterSpec, ParameterValue
from door_contract.teardown_bound import TeardownBound, bounded_teardown
from door_contract.topics import Topics, TopicSpec

__all__ = ["Heartbeat", "NodeMain", "StopRequest", "as_parameter_error", "create_contract_publisher",
           "create_contract_subscription", "declare_parameters", "node_main", "report_undeclared_parameters",
           "run_node"]


def _descriptor(spec: ParameterSpec) -> ParameterDescriptor:
    descriptor = ParameterDescriptor(
        description=spec.description + (f" [{spec.unit}]" if spec.unit else ""),
        additional_constraints=f"allowed: {spec.allowed()}",
        read_only=True,
    )
    bounds = spec.allowed_range
    if spec.is_number and bounds is not None and math.isfinite(bounds.low) and math.isfinite(bounds.high):
        # ROS's ranges are closed: an open end's value itself is refused by spec.validate
        if isinstance(spec.default, int):
            descriptor.integer_range = [IntegerRange(
                from_value=math.ceil(bounds.low), to_value=math.floor(bounds.high), step=0)]
        else:
            descriptor.floating_point_range = [FloatingPointRange(
                from_value=float(bounds.low), to_value=float(bounds.high), step=0.0)]
    return descriptor


def _ros_default(value: ParameterValue) -> Any:
    return list(value) if isinstance(value, tuple) else value


def declare_parameters(node: Node, specs: Iterable[ParameterSpec]) -> dict[str, Any]:
    """Declare ``specs`` on ``node`` with descriptors and return their validated values.

    Raises :class:`ParameterRangeError` naming the parameter and its allowed range when an
    override (``--ros-args -p`` or ``--params-file``) has the wrong type or is out of range.
    """
    values = {}
    for spec in specs:
        try:
            parameter = node.declare_parameter(spec.name, _ros_default(spec.default), _descriptor(spec))
        except Exception as error:  # rclpy raises several types for bad overrides
            raise ParameterRangeError(f"parameter '{spec.name}' is invalid ({error}); "
                                      f"expected {spec.allowed()}") from None
        values[spec.name] = spec.validate(parameter.value)
    return values


def report_undeclared_parameters(node: Node) -> list[str]:
    """Warn about overrides (``-p``, ``--params-file``) that name no declared parameter.

    rclpy ignores them silently, so a typo (``vote_frame:=5``) would change nothing unseen.
    Returns the names reported.
    """
    overrides = getattr(node, "_parameter_overrides", {})  # rclpy keeps them only privately
    declared = {name for name in overrides if node.has_parameter(name)}
    unknown = sorted(set(overrides) - declared)
    for name in unknown:
        known = sorted(node._parameters) if hasattr(node, "_parameters") else []
        close = difflib.get_close_matches(name, known, n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        node.get_logger().warning(f"parameter '{name}' is not a parameter of /{node.get_name()} "
                                  f"and is ignored{hint}")
    return unknown


@contextmanager
def as_parameter_error(what: str, *errors: type[Exception]) -> Iterator[None]:
    """Turn a core's refusal of the node's configuration (``errors``) into
    :class:`ParameterRangeError`, which :func:`run_node` reports as one line and exit code 2
    (an unknown robot profile or an inverted range used to exit 1 with a traceback)."""
    try:
        yield
    except errors as error:
        raise ParameterRangeError(f"{what}: {error}") from None


class StopRequest:
    """SIGINT/SIGTERM handler: the first signal asks the spin loop to stop between callbacks.

    rclpy's own handler shuts the context down at once, which races with a callback taking
    its message (rclpy then raises from inside ``take_message``) and once left a node hung
    in shutdown. Stopping between callbacks avoids both. A second signal interrupts a long
    callback (a plan with a 10 s budget) with :class:`KeyboardInterrupt`.
    """

    def __init__(self) -> None:
        self.signal_name: str | None = None

    def __call__(self, signum: int, _frame: object) -> None:
        if self.signal_name is not None:
            raise KeyboardInterrupt
        self.signal_name = signal.Signals(signum).name

    @property
    def requested(self) -> bool:
        return self.signal_name is not None


def run_node(node_factory: Callable[[], Node], args: list[str] | None = None,
             poll_period_s: float = 0.1, drain_s: float = 0.0,
             teardown: TeardownBound | None = None) -> int:
    """The canonical rclpy main: init, build, spin until Ctrl-C/SIGTERM, clean shutdown.

    ``drain_s``: after the stop is asked for, go on taking what is already queued for this
    long before shutting down (a recorder stopped right after the graph it records still has
    the graph's last messages queued: a fall's outcome and the FAILED state were lost so).
    Returns the process exit code: 0 after a clean shutdown, 2 when a parameter is invalid.
    The teardown (executor, node, context) runs under ``teardown`` (default: a
    :class:`TeardownBound`'s): a middleware hang longer than its limit ends the process with
    SIGALRM (:mod:`door_contract.teardown_bound`).
    DDS discovery stays on this machine unless the environment says otherwise
    (:func:`~door_contract.network.keep_discovery_local`).
    """
    keep_discovery_local()
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    stop = StopRequest()
    previous = {sig: signal.signal(sig, stop) for sig in (signal.SIGINT, signal.SIGTERM)}
    executor = SingleThreadedExecutor()
    node = None
    try:
        node = node_factory()
        report_undeclared_parameters(node)
        executor.add_node(node)
        while not stop.requested and rclpy.ok():
            executor.spin_once(timeout_sec=poll_period_s)
        node.get_logger().info(f"{stop.signal_name or 'context shut down'}: stopping")
        _drain(executor, drain_s)
    except ParameterRangeError as error:
        rclpy.logging.get_logger("door_task").fatal(str(error))
        return 2
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        with bounded_teardown(teardown or TeardownBound()):
            executor.shutdown(timeout_sec=1.0)
            if node is not None:
                node.destroy_node()
            rclpy.try_shutdown()
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    return 0


def _drain(executor: SingleThreadedExecutor, drain_s: float) -> None:
    """Run ready callbacks for ``drain_s`` (wall clock) while the context is still up."""
    deadline = time.monotonic() + drain_s
    while rclpy.ok() and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=min(0.05, max(deadline - time.monotonic(), 0.0)))


class NodeMain(Protocol):
    """A node module's ``main``: what ``setup.py``'s console_scripts (``ros2 run``) call."""

    def __call__(self, args: list[str] | None = None) -> int: ...


def node_main(node_factory: Callable[[], Node], module_name: str) -> NodeMain:
    """The entry point of a node module, written once: ``main = node_main(MyNode, __name__)``.

    Returns ``main(args=None) -> int``, which runs the node with :func:`run_node`. When the
    module itself is the program (``python -m pkg.my_node``: ``module_name == "__main__"``)
    it runs the node at once and exits with its code, so no node module repeats the
    ``if __name__ == "__main__"`` block. Call it last in the module (after the node class).
    """

    def main(args: list[str] | None = None) -> int:
        return run_node(node_factory, args)

    main.__doc__ = f"Run {getattr(node_factory, '__name__', 'the node')} until Ctrl-C or SIGTERM; the exit code."
    if module_name == "__main__":
        raise SystemExit(main())
    return main


def create_contract_publisher(node: Node, topic: TopicSpec) -> Any:
    """Publisher for a :class:`~door_contract.topics.TopicSpec` with its contract QoS."""
    return node.create_publisher(topic.msg_class(), topic.name, topic.qos.to_profile())


def create_contract_subscription(node: Node, topic: TopicSpec, callback: Callable[[Any], None]) -> Any:
    """Subscription for a :class:`~door_contract.topics.TopicSpec` with its contract QoS."""
    return node.create_subscription(topic.msg_class(), topic.name, callback, topic.qos.to_profile())


class Heartbeat:
    """Publishes the node's health on ``/diagnostics`` every ``period_s`` (wall clock)."""

    def __init__(self, node: Node, period_s: float = 1.0) -> None:
        self._node = node
        self._publisher = create_contract_publisher(node, Topics.DIAGNOSTICS)
        self.health, self.message = Health.OK, "ready"
        self.values: dict[str, object] = {}
        self._timer = node.create_timer(period_s, self.publish, clock=Clock(clock_type=ClockType.STEADY_TIME))

    def update(self, health: Health, message: str, **values: object) -> None:
        self.health, self.message = health, message
        self.values.update(values)

    def publish(self) -> None:
        self._publisher.publish(diagnostic_array(self._node.get_name(), self.health, self.message,
                                                 self.values))
