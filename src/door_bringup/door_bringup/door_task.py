"""``door_task``: the main job — the whole graph runs the door task in simulation.

    door_task [--robot talos|atlas_v4|drc_hubo|g1] [--opening push|pull] [--hinge left|right]
              [--autonomy supervised] [--operator auto|console] [--seed 0] [--backend sqp|chomp]
              [--run-dir DIR] [--foxglove [--foxglove-port 8765]]

Starts the sim bridge, the four nodes and the proposal markers as separate processes (what
``ros2 launch door_bringup door_task.launch.py`` does on a real install), records every topic
into a rosbag2 bag, plays the operator (``auto`` approves every request on
/door_task/approval_request; ``console`` leaves it to you: ``./ros2 run door_fsm
operator_console`` in another terminal), waits for the FSM's TaskReport, prints a table in
the form of [Banerjee 2015]'s Table I, stops the graph with SIGINT, and writes the run folder:
``bag/``, ``logs/``, ``report.md``, ``report.json`` and plots (``summary.png`` first). While it
runs it prints the FSM's states and a progress line; ``--foxglove`` also serves the graph on a
Foxglove WebSocket (ws://127.0.0.1:8765; layout in ``src/door_viz/layouts/door_task.json``).
``--robot`` names the robot profile (``params/robot_<name>.yaml``) given to every node that
declares ``robot_profile`` (:func:`door_bringup.params_files.robot_nodes`); default TALOS.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String

from door_bringup.bags.recorder import message_digest, recorded_key
from door_bringup.domains import DomainsExhausted, lease_wanted_domain
from door_bringup.graph_spec import FOXGLOVE_BRIDGE, GRAPH, NodeLaunch
from door_bringup.interrupts import INTERRUPTED, interrupt_on_sigterm, signals_deferred
from door_bringup.params_files import ROBOT_PARAMETER, robot_nodes
from door_bringup.processes import ABANDONED_TEARDOWN_NOTE, ProcessSupervisor, teardown_abandoned
from door_bringup.progress_monitor import ProgressMonitor
from door_bringup.robot_option import add_robot_argument, check_robot
from door_bringup.run_plots import plot_run
from door_bringup.table_one import format_table, phase_rows, state_attempts
from door_bringup.workspace import Workspace, repository_root
from door_contract.converters.diagnostics import status_values
from door_contract.network import keep_discovery_local
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import TaskReport, decode, encode_document
from door_contract.stamps import stamp_ns
from door_contract.teardown_bound import TeardownBound, bounded_teardown
from door_contract.topics import Topics
from door_contract.vocabulary import TaskEnd
from door_fsm.answer_retry import AnswerRetry

__all__ = ["ScriptedOperator", "TaskOptions", "add_camera_arguments", "main", "parse_options", "run_task"]

RECORDER = NodeLaunch("door_bringup", "bag_record", "bag_recorder")
RECORDER_CONFIRM_S = 30.0
"""s (wall clock) the job waits for the recorder to say the terminal state is in the bag before it
stops the graph: a safety net, the wait ends on the recorder's heartbeat (twice a second)."""
WALL_SAFETY = 5.0
"""× a run's ``timeout_s`` (robot time) of wall clock after which it is given up even so: the net
for a simulation that no longer advances (a node that exits is caught at once)."""


@dataclass(frozen=True)
class TaskOptions:
    robot: str = "talos"  # a robot profile, params/robot_<name>.yaml
    opening: str = "push"
    hinge: str = "left"
    autonomy: str = "supervised"
    operator: str = "auto"
    seed: int = 0
    backend: str = "sqp"
    distance: float = 3.0
    lateral: float = 0.0
    yaw: float = 0.0
    depth_noise: float = 0.0
    wind: float = 0.0
    door_width: float = 0.914
    handle_height: float = 0.91
    timeout_s: float = 900.0  # s of the robot's time (sim time) the task may take; WALL_SAFETY × it on the wall clock
    record: bool = True
    storage: str = "sqlite3"
    compression: str = "none"  # "zstd": compressed mcap chunks (with storage mcap)
    camera_rate: float = 2.0  # Hz of sim time while walking (rendering costs ~0.14 s of CPU per frame)
    camera_rate_standing: float = 8.0  # Hz of sim time otherwise: detection's latency is 2-4 frame periods
    foxglove_port: int | None = None  # serve the graph on ws://127.0.0.1:<port> (None: no live view)
    colours: tuple[tuple[str, tuple[float, float, float]], ...] = ()  # (COLOUR_FIELDS name, RGB); () keeps the sim's

    def node_overrides(self) -> dict[str, list[str]]:
        """``-p name:=value`` arguments per node; the robot goes to every node that declares
        ``robot_profile``."""
        sim: dict[str, object] = {
            "door_opening": self.opening, "hinge_side": self.hinge, "seed": self.seed,
            "stance_distance": self.distance, "stance_lateral": self.lateral, "stance_yaw": self.yaw,
            "depth_noise": self.depth_noise, "wind_amplitude": self.wind, "door_width": self.door_width,
            "handle_height": self.handle_height, "camera_rate": self.camera_rate,
            "camera_rate_standing": self.camera_rate_standing, **dict(self.colours)}
        fsm: dict[str, object] = {"opening": self.opening, "autonomy": self.autonomy, "backend": self.backend}
        own: dict[str, dict[str, object]] = {
            "sim_bridge": sim, "fsm_supervisor": fsm,
            "foxglove_bridge": {} if self.foxglove_port is None else {"port": self.foxglove_port}}
        takes_robot = robot_nodes()
        return {launch.node_name: _ros_args({**own.get(launch.node_name, {}),
                                             **({ROBOT_PARAMETER: self.robot} if launch.node_name in takes_robot else {}),
                                             **({"use_sim_time": True} if launch.use_sim_time else {})})
                for launch in (*GRAPH, FOXGLOVE_BRIDGE)}


def _ros_args(values: dict[str, object]) -> list[str]:
    """``-p name:=value`` pairs; rclpy reads each value as YAML (a list as ``[a, b]``)."""
    args = []
    for name, value in values.items():
        args += ["-p", f"{name}:={_yaml_value(value)}"]
    return args


def _yaml_value(value: object) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_yaml_value(item) for item in value) + "]"
    return str(value)


class ScriptedOperator(Node):
    """The operator of the main job: approves every request (again until the FSM takes it:
    :mod:`door_fsm.answer_retry`) and collects the TaskReport and where the robot's base ended
    (odom, m)."""

    def __init__(self, approve: bool, context: rclpy.Context | None = None) -> None:
        super().__init__("door_task_operator", context=context)
        self._spinner: SingleThreadedExecutor | None = None
        self.approve = approve
        self.report: TaskReport | None = None
        self.states: list[str] = []
        self.base_xy: tuple[float, float] | None = None
        self.robot_time_s = 0.0  # the robot's clock (sim time) as /odom last stamped it
        self.recorded: dict[str, str] = {}  # the recorder's heartbeat: latched topic → digest of its last message
        create_contract_subscription(self, Topics.ODOM, self._on_odom)
        create_contract_subscription(self, Topics.DIAGNOSTICS, self._on_diagnostics)
        self.command_pub = create_contract_publisher(self, Topics.OPERATOR)
        self.answers = AnswerRetry()  # an answer lost before DDS matched the FSM is sent again
        self.create_timer(self.answers.options.check_period_s, self._resend)
        self.progress = ProgressMonitor(self)
        create_contract_subscription(self, Topics.APPROVAL_REQUEST, self._on_request)
        create_contract_subscription(self, Topics.TASK_STATE, self._on_state)
        create_contract_subscription(self, Topics.TASK_REPORT, self._on_report)

    def spin_once(self, timeout_sec: float) -> None:
        """Take this node's next callback, on an executor of its own context's."""
        if self._spinner is None:
            self._spinner = SingleThreadedExecutor(context=self.context)
            self._spinner.add_node(self)
        self._spinner.spin_once(timeout_sec=timeout_sec)

    def release(self) -> None:
        """Destroy the node, its executor and its context."""
        if self._spinner is not None:
            self._spinner.shutdown()
        context = self.context
        self.destroy_node()
        rclpy.try_shutdown(context=context)

    def _on_request(self, msg: String) -> None:
        if msg.data:
            self.progress.say(f"  [approval request] {msg.data}")
        if self.approve:
            self._answer(self.answers.on_request(msg.data, time.monotonic()))

    def _resend(self) -> None:
        self._answer(self.answers.due(time.monotonic()), again=True)

    def _answer(self, request_id: int | None, again: bool = False) -> None:
        if request_id is not None:
            self.command_pub.publish(String(data=f"approve {request_id}"))
            self.progress.say(f"  [operator] approve {request_id}{' (again: not taken yet)' if again else ''}")

    def _on_state(self, msg: String) -> None:
        if not self.states or self.states[-1] != msg.data:
            self.states.append(msg.data)
            self.progress.say(f"  [state] {msg.data}")

    def _on_report(self, msg: String) -> None:
        self.report = decode(TaskReport, msg.data)

    def _on_diagnostics(self, msg: DiagnosticArray) -> None:
        values = status_values(msg, RECORDER.node_name)
        if values is not None:
            self.recorded = values

    def has_recorded(self, topic: str, digest: str) -> bool:
        """Whether the recorder's last message on the latched ``topic`` has ``digest``
        (:func:`~door_bringup.bags.recorder.message_digest`)."""
        return self.recorded.get(recorded_key(topic)) == digest

    def _on_odom(self, msg: Odometry) -> None:
        self.base_xy = (round(msg.pose.pose.position.x, 3), round(msg.pose.pose.position.y, 3))
        self.robot_time_s = max(self.robot_time_s, stamp_ns(msg.header.stamp) * 1e-9)
        self.progress.odom(msg)


OPERATOR_TEARDOWN = TeardownBound(stacks_after_s=10.0, limit_s=30.0)
"""The scripted operator node's teardown, in this process: a Fast DDS deadlock destroying it
(stop 38: a Monte-Carlo worker hung 90 min in ``Publisher.destroy``) holds the GIL, so no thread
can wait it out; the kernel's alarm ends the process instead (:mod:`door_contract.teardown_bound`)."""


def run_task(options: TaskOptions, run_dir: Path, workspace: Workspace) -> dict:
    """Run the task once; returns the report as a dict (final_state FAILED when it never ended).
    Call it from the main thread (the operator's teardown is bounded by a signal)."""
    supervisor = ProcessSupervisor(workspace, run_dir / "logs")
    recorder = ProcessSupervisor(workspace, run_dir / "logs")  # stopped after the graph: the bag ends with DONE
    overrides = options.node_overrides()
    keep_discovery_local()  # the scripted operator's participant
    context = rclpy.Context()  # the run's own
    rclpy.init(context=context)
    operator = ScriptedOperator(options.operator == "auto", context)
    started = time.monotonic()
    try:
        if options.record:
            recorder.start(RECORDER, args=(str(run_dir / "bag"), "--storage", options.storage,
                                           "--compression", options.compression))
        for launch in GRAPH + ((FOXGLOVE_BRIDGE,) if options.foxglove_port is not None else ()):
            supervisor.start(launch, overrides[launch.node_name])
        print(f"graph started ({len(GRAPH)} nodes); logs in {run_dir / 'logs'}", flush=True)
        if options.foxglove_port is not None:
            print(f"live view: Foxglove → open connection → ws://127.0.0.1:{options.foxglove_port}; layout "
                  f"{workspace.root / 'src/door_viz/layouts/door_task.json'}", flush=True)
        report = _wait_for_report(operator, supervisor, options.timeout_s)
        if options.record and operator.report is not None:  # the FSM ended and published its state
            _wait_until_recorded(operator, String(data=str(report["final_state"])))
    finally:
        with signals_deferred():  # a second stop waits: the recorder is stopped too
            operator.progress.printer.interrupt()
            codes = {**supervisor.stop(), **recorder.stop()}
        with bounded_teardown(OPERATOR_TEARDOWN):
            operator.release()
    report["wall_time_s"] = round(time.monotonic() - started, 2)
    report["final_base_xy"] = operator.base_xy
    report["exit_codes"] = codes
    abandoned = _abandoned_teardowns(codes)
    if abandoned:
        report["teardown_abandoned"] = abandoned
    return report


def _abandoned_teardowns(codes: dict[str, int]) -> list[str]:
    """The nodes that ended themselves in a hung middleware teardown, each warned about."""
    abandoned = sorted(name for name, code in codes.items() if teardown_abandoned(code))
    for name in abandoned:
        print(f"warning: /{name}: {ABANDONED_TEARDOWN_NOTE}", flush=True)
    return abandoned


def _no_report(reason: str) -> dict:
    return {"final_state": TaskEnd.FAILED, "failure_reason": reason, "attempts": []}


def _wait_until_recorded(operator: ScriptedOperator, terminal_state: String) -> None:
    """Keep the graph up until the recorder has written the FSM's terminal state: stopped at once,
    the bag of a push door that reached DONE once ended at WALK_THROUGH (the recorder, behind
    under load, had not taken the latched DONE before the FSM's process was gone)."""
    deadline, digest = time.monotonic() + RECORDER_CONFIRM_S, message_digest(terminal_state)
    while not operator.has_recorded(Topics.TASK_STATE.name, digest):
        if time.monotonic() > deadline:
            print(f"warning: the bag may lack the terminal state {terminal_state.data} "
                  f"(the recorder did not confirm it within {RECORDER_CONFIRM_S:g} s)", flush=True)
            return
        operator.spin_once(timeout_sec=0.1)


def _wait_for_report(operator: ScriptedOperator, supervisor: ProcessSupervisor, timeout_s: float) -> dict:
    """Spin until the FSM's TaskReport, a node's exit, or ``timeout_s`` of the robot's time (the
    task's own pace, whatever the machine's load: with two graphs per core a wall-clock limit
    ends trials that are still working), with :data:`WALL_SAFETY` × ``timeout_s`` of wall clock as
    the net for a simulation that no longer advances."""
    started, wall_limit = time.monotonic(), WALL_SAFETY * timeout_s
    while operator.report is None:
        operator.spin_once(timeout_sec=0.1)
        operator.progress.tick()
        dead = [c.launch.node_name for c in supervisor.exited()]
        if dead:
            return _no_report(f"process(es) exited: {', '.join(dead)}")
        if operator.robot_time_s > timeout_s:
            return _no_report(f"no TaskReport within {timeout_s:g} s of the robot's time")
        if time.monotonic() - started > wall_limit:
            return _no_report(f"no TaskReport within {wall_limit:g} s of wall time (the robot's clock read "
                              f"{operator.robot_time_s:.1f} s)")
    report = operator.report
    return {"final_state": report.final_state, "failure_reason": report.failure_reason,
            "opening": report.opening, "autonomy": report.autonomy,
            "attempts": [encode_document(attempt) for attempt in report.attempts],  # report.json: an object per attempt
            "clocks": report.clocks}


def add_camera_arguments(parser: argparse.ArgumentParser) -> None:
    """The head camera's rates, shared by the main job and the Monte-Carlo."""
    parser.add_argument("--camera-rate", type=float, default=TaskOptions.camera_rate,
                        help="head camera frames per second of sim time while the robot walks (rendering costs "
                             "~0.14 s of CPU per frame)")
    parser.add_argument("--camera-rate-standing", type=float, default=TaskOptions.camera_rate_standing,
                        help="the same while it does not walk (detection works then)")


def write_report(run_dir: Path, options: TaskOptions, report: dict) -> str:
    ok = report["final_state"] == TaskEnd.DONE
    table = format_table(phase_rows([report]), 1, int(ok), f"Door task: {options.robot}, {options.opening} door, "
                         f"hinge {options.hinge}, seed {options.seed}")
    lines = [f"# Door task run {run_dir.name}", "", f"Final state: **{report['final_state']}**"
             + (f" — {report['failure_reason']}" if report.get("failure_reason") else ""), "",
             f"Wall time: {report.get('wall_time_s', 0):.1f} s; autonomy {options.autonomy}; backend {options.backend}",
             "", table, "", f"Times: {report.get('clocks') or 'see docs/CLOCKS.md'}.", "", "## State attempts", "", "| state | attempt | outcome | planning | moving | robot time | reason |",
             "|---|---|---|---|---|---|---|"]
    for a in state_attempts(report):
        lines.append(f"| {a.state.label} | {a.attempt} | {a.outcome} | {a.planning_s:.3f} s | {a.moving_s:.1f} s | {a.robot_s:.2f} s | {a.reason} |")
    text = "\n".join(lines) + "\n"
    (run_dir / "report.md").write_text(text)
    (run_dir / "report.json").write_text(json.dumps({"options": options.__dict__, **report}, indent=2, default=str))
    return table


def parse_options(argv: list[str] | None) -> tuple[TaskOptions, Path | None]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_robot_argument(parser)
    parser.add_argument("--opening", choices=("push", "pull"), default="push")
    parser.add_argument("--hinge", choices=("left", "right"), default="left")
    parser.add_argument("--autonomy", choices=("full", "supervised", "step"), default="supervised")
    parser.add_argument("--operator", choices=("auto", "console"), default="auto")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--backend", choices=("sqp", "chomp"), default="sqp")
    parser.add_argument("--distance", type=float, default=3.0, help="start distance to the door (m)")
    parser.add_argument("--timeout", type=float, default=900.0,
                        help="give up after this many seconds of the robot's time (sim time; 5x that of wall time "
                             "as a safety net)")
    parser.add_argument("--storage", choices=("sqlite3", "mcap"), default="sqlite3")
    parser.add_argument("--compression", choices=("none", "zstd"), default="none",
                        help="zstd: compressed mcap chunks (needs --storage mcap)")
    add_camera_arguments(parser)
    parser.add_argument("--no-bag", action="store_true")
    parser.add_argument("--foxglove", action="store_true", help="serve the graph live on a Foxglove WebSocket")
    parser.add_argument("--foxglove-port", type=int, default=8765)
    parser.add_argument("--run-dir", type=Path, default=None)
    args, _ = parser.parse_known_args(argv)
    if args.compression != "none" and args.storage != "mcap":
        parser.error("--compression zstd needs --storage mcap")
    check_robot(parser, args.robot)
    options = TaskOptions(robot=args.robot, opening=args.opening, hinge=args.hinge, autonomy=args.autonomy,
                          operator=args.operator, seed=args.seed, backend=args.backend, distance=args.distance,
                          timeout_s=args.timeout, record=not args.no_bag, storage=args.storage,
                          camera_rate=args.camera_rate, camera_rate_standing=args.camera_rate_standing,
                          compression=args.compression,
                          foxglove_port=args.foxglove_port if args.foxglove else None)
    return options, args.run_dir


def main(argv: list[str] | None = None) -> int:
    options, run_dir = parse_options(argv)
    interrupt_on_sigterm()
    try:
        lease, wanted = lease_wanted_domain(os.environ)  # held until this process exits
    except (ValueError, DomainsExhausted) as error:
        print(f"door_task: {error}", file=sys.stderr)
        return 2
    os.environ["ROS_DOMAIN_ID"] = str(lease.domain)
    workspace = Workspace(repository_root())
    stamp = datetime.now(UTC).strftime("%Y%m%dT%H%M%SZ")
    run_dir = run_dir or workspace.root / "runs" / f"{stamp}_{options.robot}_{options.opening}_{options.hinge}"
    run_dir.mkdir(parents=True, exist_ok=True)
    busy = "" if lease.domain == wanted else f" ({wanted} is another run's)"
    print(f"door task: {options.robot}, {options.opening} door hinged {options.hinge}, autonomy "
          f"{options.autonomy}, operator {options.operator}; ROS domain {lease.domain}{busy}; run folder {run_dir}",
          flush=True)
    try:
        report = run_task(options, run_dir, workspace)
    except KeyboardInterrupt as signal_name:  # run_task has stopped the graph on its way out
        print(f"\ninterrupted ({signal_name or 'SIGINT'}): the graph is stopped; logs in {run_dir}", file=sys.stderr)
        return INTERRUPTED
    table = write_report(run_dir, options, report)
    print(table, flush=True)
    for plot in plot_run(run_dir, options.opening, options.robot):
        print(f"plot: {plot}", flush=True)
    print(f"\nreport: {run_dir / 'report.md'}", flush=True)
    return 0 if report["final_state"] == TaskEnd.DONE else 1


if __name__ == "__main__":
    sys.exit(main())
