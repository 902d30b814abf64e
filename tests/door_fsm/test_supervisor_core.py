"""The supervisor's ROS-free core: the robot's hands and step time from its profile, inputs →
the machine's actions, bad input → one Notice and no change, a grasp hand the robot lacks."""

from __future__ import annotations

import pytest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path

from door_contract.payloads import (
    DoorEstimate,
    ExecutionKind,
    ExecutionOutcome,
    FootstepFigures,
    OutcomeStatus,
    PlanningOutcome,
    encode,
)
from door_contract.stamps import time_msg_of_ns
from door_contract.vocabulary import (
    AttemptOutcome,
    Autonomy,
    DoorOpening,
    HingeSide,
    Motion,
    Side,
    TaskEnd,
    TaskState,
    WalkGoal,
)
from door_fsm import actions as act
from door_fsm.graph_watch import GraphWatch
from door_fsm.machine import MachineOptions
from door_fsm.records import Instant
from door_fsm.supervisor import GRASP_SERVICES, SupervisedRobot, Supervisor
from door_robot.crouch import CrouchRules, LowLeverCrouch, PassageCrouch
from door_robot.profile import load_profile

HANDS_ONLY = ((Side.LEFT, frozenset()), (Side.RIGHT, frozenset()))
"""Both hands, their chains unnamed: what these tests need of a robot."""

ESTIMATE = DoorEstimate(0.0, "odom", (1.2, -0.35, 0.95), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((1.2, 0.46, 0.0), (1.2, -0.46, 0.0), (1.2, -0.46, 2.08), (1.2, 0.46, 2.08)),
                        1.0, 10, "automatic")


def t(seconds: float) -> Instant:
    return Instant(seconds, seconds)


@pytest.mark.parametrize("name", ["talos", "atlas_v4", "drc_hubo", "g1"])
def test_the_robot_is_read_from_its_profile(name: str, request: pytest.FixtureRequest) -> None:
    if name in ("atlas_v4", "drc_hubo"):  # their URDFs are real files in ../shared/data
        request.getfixturevalue("shared_data")
    profile = load_profile(name)
    robot = SupervisedRobot.of(profile)
    assert robot.name == name and robot.step_duration == profile.walking.step_duration
    assert robot.hands == {Side(side) for side in profile.arms} == {Side.LEFT, Side.RIGHT}
    assert robot.grasp_services() == GRASP_SERVICES


def _started(robot: SupervisedRobot, opening: DoorOpening = DoorOpening.PUSH) -> Supervisor:
    supervisor = Supervisor(MachineOptions(opening=opening, autonomy=Autonomy.FULL), "sqp", robot,
                            GraphWatch({"door_detector"}, start_at=0.0, graph_timeout=5.0))
    step, actions = supervisor.tick(t(0.0), {"door_detector"})
    assert step.start and act.AnnounceState(TaskState.DETECT_DOOR) in actions
    assert not any(isinstance(a, act.RequestDetection) for a in actions)  # the core waits for the detector
    supervisor.settle()
    return supervisor


def _walk_request(supervisor: Supervisor) -> act.RequestFootsteps:
    actions = supervisor.door_estimate(encode(ESTIMATE), t(1.0))
    supervisor.settle()
    request = next(a for a in actions if isinstance(a, act.RequestFootsteps))
    assert request.goal is WalkGoal.STAND
    return request


def test_a_walk_is_requested_with_the_approved_door_and_given_its_steps_time() -> None:
    supervisor = _started(SupervisedRobot("g1", 0.8, HANDS_ONLY))
    request = _walk_request(supervisor)
    kind, payload = supervisor.request(request)
    assert kind == "footsteps" and payload.door == encode(ESTIMATE) and payload.request_id == request.request_id
    path = Path(poses=[PoseStamped() for _ in range(10)])
    path.header.stamp = time_msg_of_ns(5_000)
    assert supervisor.proposal("footsteps", path, t(2.0)) == []  # waits for its outcome
    outcome = PlanningOutcome(request.request_id, OutcomeStatus.SUCCESS, stamp_ns=5_000,
                              footsteps=FootstepFigures(100, steps=10, length_m=2.5))
    execute = next(a for a in supervisor.planning_outcome("footsteps", encode(outcome), t(3.0))
                   if isinstance(a, act.Execute))
    supervisor.settle()
    assert supervisor.take(execute.request_id, 9_000) is path and supervisor.take(execute.request_id, 9_001) is None
    # 10 steps × 0.8 s × execution_factor 2 + margin 10 s: the walk's deadline is the robot's
    _, actions = supervisor.tick(t(3.0 + 25.0), {"door_detector"})
    assert not any(isinstance(a, act.StopMotion) for a in actions)
    _, actions = supervisor.tick(t(3.0 + 27.0), {"door_detector"})
    assert any(isinstance(a, act.StopMotion) and "longer than 26.0 s" in a.reason for a in actions)


def test_the_robots_answer_to_what_it_was_sent_finishes_the_state() -> None:
    supervisor = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY))
    request = _walk_request(supervisor)
    path = Path(poses=[PoseStamped()])
    path.header.stamp = time_msg_of_ns(7)
    supervisor.proposal("footsteps", path, t(2.0))
    outcome = PlanningOutcome(request.request_id, OutcomeStatus.SUCCESS, stamp_ns=7)
    execute = next(a for a in supervisor.planning_outcome("footsteps", encode(outcome), t(3.0))
                   if isinstance(a, act.Execute))
    supervisor.take(execute.request_id, 42)
    other = ExecutionOutcome(ExecutionKind.FOOTSTEPS, 41, OutcomeStatus.SUCCESS)
    assert supervisor.execution_outcome(encode(other), t(4.0)) == []  # not sent by this supervisor
    done = ExecutionOutcome(ExecutionKind.FOOTSTEPS, 42, OutcomeStatus.SUCCESS)
    actions = supervisor.execution_outcome(encode(done), t(5.0))
    assert act.AnnounceState(TaskState.MOVE_TO_HANDLE) in actions


@pytest.mark.parametrize("feed, says", [
    (lambda s: s.door_estimate("{not json", t(1.0)), "door estimate rejected"),
    (lambda s: s.door_estimate(encode(DoorEstimate(**{**ESTIMATE.__dict__, "width": -1.0})), t(1.0)),
     "door estimate rejected"),
    (lambda s: s.planning_outcome("motion", '{"request_id": "x"}', t(1.0)), "planning outcome rejected"),
    (lambda s: s.execution_outcome("[]", t(1.0)), "execution outcome rejected"),
    (lambda s: s.operator("dance", t(1.0)), "unknown operator command 'dance'"),
])
def test_bad_input_is_one_notice_and_changes_nothing(feed, says: str) -> None:
    supervisor = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY))
    before = (supervisor.machine.state, supervisor.machine.request_id, supervisor.door.latest)
    actions = feed(supervisor)
    assert len(actions) == 1 and isinstance(actions[0], act.Notice) and says in actions[0].text, actions
    assert (supervisor.machine.state, supervisor.machine.request_id, supervisor.door.latest) == before


def test_a_door_whose_grasp_hand_the_robot_lacks_says_so() -> None:
    one_armed = SupervisedRobot("one_armed", 1.0, ((Side.LEFT, frozenset()),))
    supervisor = _started(one_armed)
    supervisor.door.approved = ESTIMATE  # hinge left, push: the right hand opens it
    hand, problem = supervisor.grasp_hand()
    assert hand is Side.RIGHT and problem == "one_armed has no right hand (its profile's arms: left)"
    assert one_armed.grasp_services() == {Side.LEFT: GRASP_SERVICES[Side.LEFT]}
    assert _started(SupervisedRobot("talos", 1.5, HANDS_ONLY)).grasp_hand() == (Side.RIGHT, "")


def test_the_head_search_moves_the_neck_only_while_detect_door_waits() -> None:
    """door_detection.head_search asks; the supervisor sends a look only in DETECT_DOOR's
    planning phase: not once paused (the operator can always stop the robot), not later."""
    from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

    from door_fsm import events as ev
    from door_fsm.operator_commands import OperatorCommand, OperatorWord

    robot = SupervisedRobot.of(load_profile("talos"))
    supervisor = _started(robot)
    look = JointTrajectory(joint_names=["head_2_joint"], points=[JointTrajectoryPoint(positions=[0.4])])
    assert supervisor.look(look) == [act.Look(look)]
    assert supervisor.look(look) == [act.EndLook(), act.Look(look)]  # the last look may still run
    paused = _started(robot)
    paused.handle(ev.OperatorSaid(OperatorWord(OperatorCommand.PAUSE)), t(0.5))
    paused.settle()
    assert paused.look(look) == []
    _walk_request(supervisor)  # the door is confirmed: WALK_TO_DOOR
    assert supervisor.look(look) == []


def test_the_estimate_that_confirms_the_door_stops_a_look_still_moving() -> None:
    """A look may still move the neck when the door is confirmed: the robot would then refuse the
    walk as busy with it (three repeats alike on a loaded machine), so the confirmation stops it
    first (EndLook: an empty trajectory, the neck holds). Without a look there is nothing to stop."""
    from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

    robot = SupervisedRobot.of(load_profile("talos"))
    looking = _started(robot)
    looking.look(JointTrajectory(joint_names=["head_2_joint"], points=[JointTrajectoryPoint(positions=[0.4])]))
    actions = looking.door_estimate(encode(ESTIMATE), t(1.0))
    ends = [i for i, a in enumerate(actions) if isinstance(a, act.EndLook)]
    walk = next(i for i, a in enumerate(actions) if isinstance(a, act.RequestFootsteps))
    assert len(ends) == 1 and ends[0] < walk
    still = _started(robot)
    assert not any(isinstance(a, act.EndLook) for a in still.door_estimate(encode(ESTIMATE), t(1.0)))


@pytest.mark.parametrize(("joints", "positions", "says"), [
    (["head_2_joint"], None, "trajectory has no points"),
    ([], [], "no joints"),
    (["head_2_joint", "arm_left_1_joint"], [0.1, 0.2], "arm_left_1_joint"),
    (["torso_1_joint"], [0.3], "torso_1_joint"),  # TALOS's torso is in its arm chains
    (["head_2_joint"], [0.1, 0.2], "every point needs 1 positions"),
    (["head_2_joint"], [float("nan")], "NaN or infinity"),
])
def test_a_malformed_or_arm_moving_look_is_refused_and_nothing_moves(joints, positions, says) -> None:
    from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

    supervisor = _started(SupervisedRobot.of(load_profile("talos")))
    points = [] if positions is None else [JointTrajectoryPoint(positions=positions)]
    actions = supervisor.look(JointTrajectory(joint_names=joints, points=points))
    assert len(actions) == 1 and isinstance(actions[0], act.Notice) and says in actions[0].text, actions
    assert actions[0].text.startswith("look refused")


def test_the_grasp_hand_is_the_arm_the_approach_moved_and_later_requests_name_it() -> None:
    """The optimiser picks the approach's arm (the one on the handle's side); the supervisor
    grasps with it and names it in every later motion request."""
    robot = SupervisedRobot.of(load_profile("talos"))
    assert robot.arm_of(["torso_1_joint", "torso_2_joint", "arm_left_1_joint", "arm_left_4_joint"]) is Side.LEFT
    assert robot.arm_of(["torso_1_joint", "torso_2_joint"]) is None  # shared by both arms
    assert robot.arm_of(["arm_left_1_joint", "arm_right_1_joint"]) is None
    supervisor = _started(robot)
    supervisor.door.approved = ESTIMATE  # hinge left, push: facing, the right hand would open it
    assert supervisor.grasp_hand() == (Side.RIGHT, "")
    supervisor.door.approach_hand = Side.LEFT  # sideways, its back to the hinge: the left
    assert supervisor.grasp_hand() == (Side.LEFT, "")
    from door_fsm import actions as fsm_actions
    request = supervisor.door.motion_request(fsm_actions.RequestMotion(12, Motion.TURN_HANDLE, 0))
    assert request.hand is Side.LEFT


def test_the_report_waits_for_a_terminal_state_and_names_how_the_task_ended() -> None:
    supervisor = _started(SupervisedRobot("g1", 0.8, HANDS_ONLY))
    assert supervisor.report("sim") is None
    supervisor.operator("abort", t(1.0))
    report = supervisor.report("sim")
    assert report is not None and report.final_state is TaskEnd.FAILED
    assert [(a.state, a.outcome) for a in report.attempts] == [(TaskState.DETECT_DOOR, AttemptOutcome.ABORTED)]


def test_a_push_door_is_walked_through_crouched_when_its_lever_meets_the_pelvis() -> None:
    """The walk's crouch (door_robot.profile.PassageCrouch) comes from the approved estimate's
    lever height: through a push door with the lever in the band, and only then."""
    crouching = SupervisedRobot("talos", 1.5, HANDS_ONLY,
                                CrouchRules(push_passage=PassageCrouch((0.90, 1.00), 0.06, min_door_width=0.87)))
    push = _started(crouching)
    stand = _walk_request(push)
    push.door.approved = ESTIMATE  # the lever at 0.95 m
    through = act.RequestFootsteps(stand.request_id + 1, WalkGoal.THROUGH)
    doorway = act.RequestFootsteps(stand.request_id + 1, WalkGoal.DOORWAY)  # a wide door's, before the tuck
    assert push.walk_crouch(stand) == 0.0 and push.walk_crouch(through) == pytest.approx(0.06)
    assert push.walk_crouch(doorway) == pytest.approx(0.06)
    push.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "handle_position": (1.2, -0.35, 1.05)})
    assert push.walk_crouch(through) == 0.0  # above the band
    push.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "width": 0.84})
    assert push.walk_crouch(through) == 0.0  # a narrow door
    pull = _started(crouching, DoorOpening.PULL)
    pull.door.approved = ESTIMATE
    assert pull.walk_crouch(through) == 0.0


def test_a_narrow_push_door_is_walked_through_higher_when_its_lever_meets_the_pelvis() -> None:
    """Through a push door narrower than ``min_door_width`` whose lever is in the band and at
    most ``narrow_rise_top``, the walk rises ``narrow_rise`` (a negative crouch); a higher lever
    is passed upright, and any crouch a rule asks for wins over the rise."""
    band = PassageCrouch((0.90, 1.00), 0.06, min_door_width=0.87, narrow_rise=0.04, narrow_rise_top=0.96)
    push = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY, CrouchRules(push_passage=band)))
    stand = _walk_request(push)
    through = act.RequestFootsteps(stand.request_id + 1, WalkGoal.THROUGH)
    push.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "width": 0.84})  # the lever at 0.95 m
    assert push.walk_crouch(stand) == 0.0 and push.walk_crouch(through) == pytest.approx(-0.04)
    push.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "width": 0.84, "handle_position": (1.2, -0.35, 0.98)})
    assert push.walk_crouch(through) == 0.0  # in the band, above narrow_rise_top
    push.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "width": 0.95})
    assert push.walk_crouch(through) == pytest.approx(0.06)  # a wide door: crouched
    tall = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY, CrouchRules(0.10, band)))
    tall.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "width": 0.84})
    assert tall.walk_crouch(through) == pytest.approx(0.10)  # the opening crouch wins over a rise
    pull = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY, CrouchRules(push_passage=band)), DoorOpening.PULL)
    pull.door.approved = ESTIMATE
    assert pull.walk_crouch(through) == 0.0
    upright = _started(SupervisedRobot("g1", 0.8, HANDS_ONLY))
    upright.door.approved = ESTIMATE
    assert upright.walk_crouch(through) == 0.0  # a profile without a crouch
    assert SupervisedRobot.of(load_profile("talos")).crouch == load_profile("talos").crouch


def test_a_robot_with_an_opening_crouch_walks_every_walk_that_low() -> None:
    """A profile's ``opening_crouch`` (Atlas v4's 0.15 m) lowers the walk to the door, and every
    walk after it, whether or not an estimate is known; a deeper passage crouch still wins."""
    low = SupervisedRobot("atlas_v4", 1.5, HANDS_ONLY, CrouchRules(0.10, PassageCrouch((0.90, 1.00), 0.12)))
    supervisor = _started(low)
    stand = _walk_request(supervisor)
    assert supervisor.walk_crouch(stand) == pytest.approx(0.10)
    supervisor.door.approved = None
    assert supervisor.walk_crouch(stand) == pytest.approx(0.10)  # no estimate
    supervisor.door.approved = ESTIMATE  # push, the lever at 0.95 m: in the band
    assert supervisor.walk_crouch(act.RequestFootsteps(stand.request_id + 1, WalkGoal.THROUGH)) == pytest.approx(0.12)
    supervisor.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "handle_position": (1.2, -0.35, 1.05)})
    assert supervisor.walk_crouch(act.RequestFootsteps(stand.request_id + 1, WalkGoal.THROUGH)) == pytest.approx(0.10)
    assert SupervisedRobot.of(load_profile("talos")).crouch.opening == 0.0


def test_the_walk_to_a_door_with_a_low_lever_is_crouched() -> None:
    """A profile's ``low_lever_crouch`` lowers the walk to the door by how far the approved
    estimate's lever is below the reach height; the passage's walks are upright."""
    supervisor = _started(SupervisedRobot("talos", 1.5, HANDS_ONLY, CrouchRules(low_lever=LowLeverCrouch(0.95, 0.10))))
    stand = _walk_request(supervisor)
    supervisor.door.approved = DoorEstimate(**{**ESTIMATE.__dict__, "handle_position": (1.2, -0.35, 0.87)})
    assert supervisor.walk_crouch(stand) == pytest.approx(0.08)
    assert supervisor.walk_crouch(act.RequestFootsteps(stand.request_id + 1, WalkGoal.THROUGH)) == 0.0
    supervisor.door.approved = ESTIMATE  # the lever at 0.95 m
    assert supervisor.walk_crouch(stand) == 0.0
