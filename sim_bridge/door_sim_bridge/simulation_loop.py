"""The sim bridge's loop, without ROS: one execution at a time, the physics steps, the
publications due in simulated time, and a bug in one tick contained.

The node's timer calls :meth:`SimulationLoop.tick`, which runs :data:`STEPS_PER_TICK`
steps; each step commands the running execution for the world's time, steps the physics
once and hands the publications then due to the node (``publish``), so /clock and the
joint states interleave with the physics exactly as a real robot's drivers would.

Executions (``submit``): one at a time. A new one is refused (REJECTED, nothing moves) while
the dead-man (:mod:`door_sim_bridge.deadman`) is tripped or another one runs; one that its
own validation rejected reports that at once. ``stop`` ends the running one of a kind
(it reports STOPPED where it is safe to leave the robot, see
:meth:`~door_sim_bridge.execution.base.Execution.stop`).

Bugs: an exception raised while building an execution, commanding it, stepping the
physics or publishing is a :class:`TickFault`: it is counted (``status``), reported once
per distinct error (a fault that repeats every tick is not reported again until another
one comes between), the rest of that tick is skipped and the simulation goes on at the
next tick. A fault of the execution or of the physics ends the running execution with
FAILURE ``"internal error …"`` and the robot held where it is; a publication's fault
moves nothing.

Falls: every step's robot–door contacts are kept for 3 s of simulated time, and a FELL
outcome's reason names the hardest of them (:mod:`~door_sim_bridge.contact_history`), so that
a fall seen only in the graph can be told from its log and report.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from enum import Enum

from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus
from door_contract.vocabulary import Side
from door_sim_bridge.contact_history import ContactHistory
from door_sim_bridge.deadman import DeadMan
from door_sim_bridge.execution import Execution
from door_sim_bridge.schedule import FrameSchedule, Schedule
from door_sim_bridge.world import DoorWorld

__all__ = ["STEPS_PER_TICK", "LoopReport", "PublicationRates", "Running", "SimulationLoop", "Stop",
           "Stream", "TickFault", "TickStage"]

STEPS_PER_TICK = 4
"""Physics steps per timer tick (the node's timer period is STEPS_PER_TICK / physics rate in real time)."""


class Stream(str, Enum):
    """The periodic publications of the bridge (their rates in simulated time)."""

    CLOCK = "clock"
    STATE = "state"  # joint states, odometry, feet, the door's joints, the heartbeat's figures
    TF = "tf"
    CAMERA = "camera"


@dataclass(frozen=True)
class PublicationRates:
    """Rates (Hz, simulated time) of the streams; 0 turns a stream off. The camera's is its rate
    while the robot walks; ``camera_standing`` its rate otherwise (0: the same)."""

    clock: float
    state: float
    tf: float
    camera: float
    camera_standing: float = 0.0

    def of(self, stream: Stream) -> float:
        rate: float = getattr(self, stream.value)
        return rate

    def camera_frames(self) -> FrameSchedule:
        """The camera's schedule (its rate must be > 0)."""
        return FrameSchedule(self.camera, self.camera_standing or self.camera)


class TickStage(str, Enum):
    """Where in the loop a fault was raised."""

    BUILD = "building the execution"
    EXECUTION = "commanding the execution"
    HOLD = "holding the robot after a fault"
    GRASP = "operating a gripper"
    PHYSICS = "stepping the physics"
    PUBLICATION = "publishing"


@dataclass(frozen=True)
class TickFault:
    """A bug contained by the loop: where, the exception (its repr), the simulated time (s)."""

    stage: TickStage
    error: str
    sim_time: float

    def __str__(self) -> str:
        return f"{self.stage.value} failed at t = {self.sim_time:.3f} s: {self.error}"


@dataclass(frozen=True)
class Running:
    """The execution in progress, of ``kind``, answering request ``request_id`` (the stamp, ns)."""

    execution: Execution
    kind: ExecutionKind
    request_id: int

    def __str__(self) -> str:
        return f"{self.kind.value} {self.request_id}"


@dataclass(frozen=True)
class Stop:
    """A stop asked for (by an empty command, or by the dead-man: ``dead_man``) and why;
    ``stopped`` is the execution told to stop, None when none of the kind ran."""

    why: str
    stopped: Running | None
    dead_man: bool = False


@dataclass(frozen=True)
class LoopReport:
    """What a call of the loop has for the node: outcomes to publish, new faults to log, a
    stop, and the execution started."""

    outcomes: tuple[ExecutionOutcome, ...] = ()
    faults: tuple[TickFault, ...] = ()
    stop: Stop | None = None
    started: Running | None = None

    @property
    def errors(self) -> list[str]:
        """Log lines of severity ERROR: contained bugs, a dead-man stop."""
        lines = [f"contained a bug: {fault}" for fault in self.faults]
        return lines + ([self.stop.why] if self.stop is not None and self.stop.dead_man else [])

    @property
    def warnings(self) -> list[str]:
        """Log lines of severity WARNING: an execution stopped."""
        stop = self.stop
        return [f"stopping {stop.stopped}: {stop.why}"] if stop is not None and stop.stopped is not None else []

    @property
    def notes(self) -> list[str]:
        """Log lines of severity INFO: a stop with nothing to stop, an execution started."""
        stop = self.stop
        lines = [f"stop ({stop.why}): no such execution running"] if stop is not None and stop.stopped is None else []
        return lines + ([f"executing {self.started}"] if self.started is not None else [])


class SimulationLoop:
    def __init__(self, world: DoorWorld, deadman: DeadMan, rates: PublicationRates, real_time: bool,
                 wall_start: float) -> None:
        """``real_time``: never run the simulated clock ahead of the wall clock (``wall_start``:
        the wall time, s, of simulated time 0)."""
        self.world, self.deadman, self.real_time, self.wall_start = world, deadman, real_time, wall_start
        self._schedules = {stream: Schedule(rates.of(stream)) for stream in Stream
                           if rates.of(stream) > 0 and stream is not Stream.CAMERA}
        self._camera = rates.camera_frames() if rates.camera > 0 else None
        self.running: Running | None = None
        self.contacts = ContactHistory()  # what a fall's outcome names as having struck
        self.fault_count = 0
        self.last_fault: TickFault | None = None

    # ------------------------------------------------------------------ executions
    def submit(self, kind: ExecutionKind, request_id: int, build: Callable[[DoorWorld], Execution]) -> LoopReport:
        """Build the execution of a request and start it, or report why not. An execution that
        has already ended (a trajectory stops at once) frees the robot now, its outcome first,
        rather than at the next tick: the head search's look, stopped when the door is confirmed,
        must not refuse the walk that follows as busy."""
        ended = self._retire_ended()
        try:
            execution = build(self.world)
        except Exception as error:  # a bug: a failure outcome, not a dead node
            fault = self._fault(TickStage.BUILD, error)
            return LoopReport((*ended, self._internal_error(kind, request_id, fault)), self._new((fault,)))
        refusal = self.deadman.refusal() or (f"busy executing {self.running}" if self.running else None)
        if refusal is not None:
            return LoopReport((*ended, ExecutionOutcome(kind, request_id, OutcomeStatus.REJECTED, refusal)))
        if execution.done:  # rejected while validating: nothing moved
            return LoopReport((*ended, self._outcome(Running(execution, kind, request_id))))
        self.running = Running(execution, kind, request_id)
        return LoopReport(ended, started=self.running)

    def _retire_ended(self) -> tuple[ExecutionOutcome, ...]:
        """The running execution's outcome if it has ended (it is then no longer running)."""
        if self.running is None or not self.running.execution.done:
            return ()
        running, self.running = self.running, None
        return (self._outcome(running),)

    def stop(self, kind: ExecutionKind | None, why: str) -> LoopReport:
        """Stop the running execution if it is of ``kind`` (None: any); it reports STOPPED
        when it ends."""
        return LoopReport(stop=self._stop(kind, why))

    def _stop(self, kind: ExecutionKind | None, why: str, dead_man: bool = False) -> Stop:
        running = self.running
        if running is None or kind not in (None, running.kind):
            return Stop(why, None, dead_man)
        running.execution.stop(why)
        return Stop(why, running, dead_man)

    def grasp(self, side: Side, close: bool) -> tuple[bool, str, LoopReport]:
        """Close or open ``side``'s gripper: (success, message, report). A bug is contained like
        one in a tick: the call is answered with success False and "internal error …", and
        the fault is counted and reported (a service that raised would leave its caller waiting)."""
        try:
            result = self.world.grasp(side, close)
        except Exception as error:  # a bug: a refused call, not a dead service
            fault = self._fault(TickStage.GRASP, error)
            return False, f"internal error: {fault}", LoopReport(faults=self._new((fault,)))
        return bool(result.success), result.message, LoopReport()

    def supervisor_beat(self, wall_now: float) -> bool:
        """The supervisor's heartbeat arrived; True when it ends a tripped dead-man."""
        return self.deadman.beat(wall_now)

    # ------------------------------------------------------------------ the loop
    def tick(self, wall_now: float, publish: Callable[[float, tuple[Stream, ...]], None]) -> LoopReport:
        """Check the dead-man, then run up to :data:`STEPS_PER_TICK` steps (none while a
        real-time simulation is ahead of the wall clock); ``publish(now, streams)`` is called
        after each step with the streams due."""
        silence = self.deadman.check(wall_now)
        stop = self._stop(None, silence, dead_man=True) if silence is not None else None
        outcomes: list[ExecutionOutcome] = []
        faults: list[TickFault] = []
        if self.real_time and self.world.time > wall_now - self.wall_start:
            return LoopReport(stop=stop)
        for _ in range(STEPS_PER_TICK):
            stage = TickStage.EXECUTION
            try:
                ended = self._command()
                if ended is not None:
                    outcomes.append(ended)
                stage = TickStage.PHYSICS
                self.world.step()
                self.contacts.record(self.world.time, self.world.door_contact_forces())
                stage = TickStage.PUBLICATION
                publish(self.world.time, self.due(self.world.time))
            except Exception as error:  # a bug in one tick: reported, and the simulation goes on
                faults.append(self._fault(stage, error))
                if stage is not TickStage.PUBLICATION:
                    outcomes.extend(self._fail_running(faults))
                break
        return LoopReport(tuple(outcomes), self._new(faults), stop)

    def due(self, now: float) -> tuple[Stream, ...]:
        """The streams due at ``now`` (each is then scheduled for its next period; the camera's
        period is that of the robot's activity: :class:`~door_sim_bridge.schedule.FrameSchedule`)."""
        streams = tuple(stream for stream, schedule in self._schedules.items() if schedule.due(now))
        walking = self.running is not None and self.running.kind is ExecutionKind.FOOTSTEPS
        camera = self._camera is not None and self._camera.due(now, walking)
        return (*streams, Stream.CAMERA) if camera else streams

    def status(self, wall_now: float) -> dict[str, object]:
        """The figures of the bridge's heartbeat."""
        elapsed = max(wall_now - self.wall_start, 1e-6)
        return {"sim_time": round(self.world.time, 2), "real_time_factor": round(self.world.time / elapsed, 2),
                "executing": self.running.kind.value if self.running else "-", "tick_faults": self.fault_count,
                "last_fault": str(self.last_fault) if self.last_fault else "-"}

    # ------------------------------------------------------------------ internals
    def _command(self) -> ExecutionOutcome | None:
        """Command the running execution for the world's time; its outcome once it ends."""
        if self.running is None or not self.running.execution.command():
            return None
        running, self.running = self.running, None
        return self._outcome(running)

    def _outcome(self, running: Running) -> ExecutionOutcome:
        """The ended execution's outcome; a fall's names what struck the robot before it."""
        result = running.execution.result
        if result is None:  # not reached: a finished execution has its result
            raise AssertionError(f"{running} finished without a result")
        outcome = result.outcome(running.kind, running.request_id)
        if outcome.status is OutcomeStatus.FELL:
            return replace(outcome, reason=f"{outcome.reason}; {self.contacts.summary()}")
        return outcome

    def _fail_running(self, faults: list[TickFault]) -> list[ExecutionOutcome]:
        """End the running execution with FAILURE after ``faults[0]``, holding the robot."""
        running, self.running = self.running, None
        if running is None:
            return []
        reason = f"internal error: {faults[0]}"
        try:
            running.execution.cancel(reason)
        except Exception as error:  # the hold failed too: the outcome is still reported
            faults.append(self._fault(TickStage.HOLD, error))
        return [ExecutionOutcome(running.kind, running.request_id, OutcomeStatus.FAILURE, reason,
                                 running.execution.elapsed)]

    @staticmethod
    def _internal_error(kind: ExecutionKind, request_id: int, fault: TickFault) -> ExecutionOutcome:
        return ExecutionOutcome(kind, request_id, OutcomeStatus.FAILURE, f"internal error: {fault}")

    def _fault(self, stage: TickStage, error: Exception) -> TickFault:
        self.fault_count += 1
        return TickFault(stage, repr(error), self.world.time)

    def _new(self, faults: tuple[TickFault, ...] | list[TickFault]) -> tuple[TickFault, ...]:
        """The faults to report: each unless it repeats the one before it (stage and error)."""
        new = []
        for fault in faults:
            last, self.last_fault = self.last_fault, fault
            if last is None or (last.stage, last.error) != (fault.stage, fault.error):
                new.append(fault)
        return tuple(new)
