"""What the fuzz suite shares: an observer that watches the robot, the door and every answer
over real DDS, and plays whatever part of the graph a test needs (the nodes under test are
processes: ``ros_helpers.start_node``).

Every case asserts three things (issue #12): the node lives, it answered as the contract
promises, and the robot and the door did not move (``/joint_states``, ``/odom``,
``/sim/door_joint_states``) — or, for stops, that they stopped.
"""

from __future__ import annotations

import subprocess
import threading
from dataclasses import dataclass

import numpy as np
import rclpy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from nav_msgs.msg import Path as PathMsg
from ros_helpers import executor_for, spin_until
from std_msgs.msg import String

from door_contract.converters.footsteps import FootPlacement, path_to_footsteps
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, ExecutionOutcome, PlanningOutcome, decode
from door_contract.qos import SERVICE
from door_contract.topics import Services, Topics
from door_contract.vocabulary import Foot, HingeSide

# Wall at x = 0, the sim robot 3 m in front facing +x; a left-hinged DRC door.
ESTIMATE = DoorEstimate(0.0, "odom", (-0.06, -0.39, 0.91), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((0.0, 0.457, 0.0), (0.0, -0.457, 0.0), (0.0, -0.457, 2.08), (0.0, 0.457, 2.08)),
                        1.0, 10, "automatic")


STILL_BASE = 2e-3
"""m: the standing physical robot sways by a fraction of a millimetre; a step moves it by cm."""


@dataclass(frozen=True)
class RobotState:
    joints: dict[str, float]
    base: np.ndarray  # x, y, z
    door: dict[str, float]

    def moved(self, other: RobotState) -> tuple[float, float, float]:
        """Largest joint change (rad), base displacement (m), door joint change (rad)."""
        joints = max(abs(self.joints[name] - other.joints[name]) for name in self.joints)
        door = max(abs(self.door[name] - other.door[name]) for name in self.door)
        return joints, float(np.linalg.norm(self.base - other.base)), door


class Observer:
    def __init__(self, context, name: str = "fuzz_observer") -> None:
        self.node = rclpy.create_node(name, context=context)
        self.executor = executor_for(self.node, context)
        self.joints: dict[str, float] = {}
        self.base: np.ndarray | None = None
        self.door: dict[str, float] = {}
        self.feet: list[FootPlacement] | None = None
        self.outcomes: dict[str, list] = {"footsteps": [], "motion": [], "execution": []}
        self.heartbeats: dict[str, int] = {}
        self.messages: dict[str, list[str]] = {}
        self.values: dict[str, dict[str, str]] = {}  # the latest key-values of each node's heartbeat
        self.states: list[str] = []
        self.requests: list[str] = []  # approval requests
        self.sent_plans: list[PathMsg] = []  # what reached /footstep_plan
        self._subscribe()
        topics = ("FOOTSTEP_REQUEST", "MOTION_REQUEST", "FOOTSTEP_CANCEL", "MOTION_CANCEL", "ARM_TRAJECTORY",
                  "FOOTSTEP_PLAN", "OPERATOR", "DIAGNOSTICS", "DOOR_ESTIMATE", "SCRIBBLE", "WALK_CROUCH")
        self.pubs = {name: create_contract_publisher(self.node, getattr(Topics, name)) for name in topics}
        self.grasp = {spec.name: self.node.create_client(spec.srv_class(), spec.name, qos_profile=SERVICE.to_profile())
                      for spec in Services.all()}
        self.supervisor_beating = False
        # The stand-in heartbeat beats from its own thread: an executor timer fires only while
        # a test spins, and a test busy elsewhere for 0.8 s of wall time (3 s of sim time at the
        # sim's 3.6x) tripped the dead-man it meant to keep quiet.
        self._closed = threading.Event()
        self._beater = threading.Thread(target=self._beat_until_closed, name="supervisor_beat", daemon=True)
        self._beater.start()

    def _subscribe(self) -> None:
        def sub(topic, callback):
            return create_contract_subscription(self.node, topic, callback)
        sub(Topics.JOINT_STATES, lambda m: self.joints.update(joint_state_to_positions(m)))
        sub(Topics.ODOM, lambda m: setattr(self, "base", np.array([m.pose.pose.position.x, m.pose.pose.position.y,
                                                                   m.pose.pose.position.z])))
        sub(Topics.DOOR_JOINT_STATES, lambda m: self.door.update(dict(zip(m.name, m.position))))
        sub(Topics.FOOT_POSES, lambda m: setattr(self, "feet", path_to_footsteps(m)))
        sub(Topics.FOOTSTEP_OUTCOME, lambda m: self.outcomes["footsteps"].append(decode(PlanningOutcome, m.data)))
        sub(Topics.MOTION_OUTCOME, lambda m: self.outcomes["motion"].append(decode(PlanningOutcome, m.data)))
        sub(Topics.EXECUTION_OUTCOME, lambda m: self.outcomes["execution"].append(decode(ExecutionOutcome, m.data)))
        sub(Topics.TASK_STATE, lambda m: self.states.append(m.data))
        sub(Topics.APPROVAL_REQUEST, lambda m: m.data and self.requests.append(m.data))
        sub(Topics.FOOTSTEP_PLAN, self.sent_plans.append)
        self.node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, self._on_diagnostics, 50)

    def _on_diagnostics(self, array: DiagnosticArray) -> None:
        for status in array.status:
            self.heartbeats[status.name] = self.heartbeats.get(status.name, 0) + 1
            self.messages.setdefault(status.name, []).append(status.message)
            self.values.setdefault(status.name, {}).update({kv.key: kv.value for kv in status.values})

    def _beat_until_closed(self) -> None:
        """Stand in for the supervisor's heartbeat (the sim bridge's dead-man watches it), every
        0.1 s of wall time while ``supervisor_beating``."""
        while not self._closed.wait(0.1):
            if self.supervisor_beating:
                self.pubs["DIAGNOSTICS"].publish(DiagnosticArray(status=[DiagnosticStatus(name="fsm_supervisor",
                                                                                          message="fuzz")]))

    # ------------------------------------------------------------------ waiting
    def wait(self, condition, timeout_s: float = 30.0) -> bool:
        return spin_until(self.executor, condition, timeout_s)

    def state(self) -> RobotState:
        assert self.wait(lambda: self.joints and self.base is not None and self.door, 60.0)
        return RobotState(dict(self.joints), self.base.copy(), dict(self.door))

    def settled_state(self, samples: int = 3) -> RobotState:
        """The state after a few more /odom messages (what is published now, not before)."""
        for _ in range(samples):
            self.base = None
            assert self.wait(lambda: self.base is not None, 30.0)
        return self.state()

    def assert_lives(self, process: subprocess.Popen, name: str) -> None:
        """The process runs and its heartbeat still arrives."""
        assert process.poll() is None, process.log.read_text()[-3000:]
        seen = self.heartbeats.get(name, 0)
        assert self.wait(lambda: self.heartbeats.get(name, 0) > seen, 10.0), f"/{name} heartbeat stopped"

    def answers(self, kind: str, request_id: int) -> list:
        return [o for o in self.outcomes[kind] if o.request_id == request_id]

    def wait_answer(self, kind: str, request_id: int, timeout_s: float = 30.0):
        assert self.wait(lambda: self.answers(kind, request_id), timeout_s), f"no {kind} outcome for {request_id}"
        return self.answers(kind, request_id)[0]

    def publish(self, topic: str, text: str) -> None:
        self.pubs[topic].publish(String(data=text))

    def wait_subscribed(self, *topics: str) -> None:
        assert self.wait(lambda: all(self.pubs[t].get_subscription_count() > 0 for t in topics), 60.0)

    def walk_plan(self, steps: int, stride: float = 0.1) -> list[FootPlacement]:
        """Straight ahead (+x) from where the feet stand: each foot ``stride`` beyond the other,
        counted from the foot in front (a physical walk may end with the feet staggered)."""
        assert self.wait(lambda: self.feet is not None, 30.0)
        feet = {step.foot: step for step in self.feet}
        front = max(step.x for step in self.feet)
        return [FootPlacement(foot, front + stride * (index + 1), feet[foot].y, feet[foot].yaw)
                for index, foot in enumerate(Foot.LEFT if i % 2 == 0 else Foot.RIGHT for i in range(steps))]

    def destroy(self) -> None:
        self._closed.set()
        self._beater.join(timeout=5.0)
        self.node.destroy_node()
