"""The door motion library on TALOS: constraints hold at the solution, both backends plan
the closed chain, and a planned approach → grasp → turn → push opens the simulated door."""

from dataclasses import replace

import numpy as np
import pytest
from door_scenes import estimate_from_world, motion_setup, stand_world, talos_kinematics

from door_contract.vocabulary import Backend, DoorOpening, HingeSide, Motion, Side, grasp_hand
from door_sim_bridge.execution import TrajectoryExecution
from door_trajopt.chomp import ChompSolver
from door_trajopt.door_model import rotation_vector
from door_trajopt.evaluation import ProblemEvaluator
from door_trajopt.library import MotionLibrary
from door_trajopt.motions import (
    DoorStateOutOfRange,
    _tcp_in_grasp,
    anchored_to_hand,
    build_motion,
    start_door_for,
)
from door_trajopt.problem import TrajoptError
from door_trajopt.result import Outcome
from door_trajopt.sqp import SqpSolver


@pytest.fixture(scope="module")
def scene():
    world = stand_world(DoorOpening.PUSH)
    kinematics = talos_kinematics()
    estimate = estimate_from_world(world)
    yield world, kinematics, estimate
    world.close()


@pytest.fixture(scope="module")
def approach(scene):
    world, kinematics, estimate = scene
    setup = motion_setup(world, kinematics, estimate)
    plan = MotionLibrary().plan(Motion.APPROACH_HANDLE, setup, setup.chain.chain_of(setup.chain.body_q))
    assert plan.succeeded, plan.result.message
    return setup, plan


def _tcp_errors(setup, trajectory):
    """(position m, rotation rad) of the TCP against the door's grasp pose at each waypoint."""
    k, offset = setup.chain.size, _tcp_in_grasp(setup, None)
    errors = []
    for q in trajectory:
        pose, target = setup.chain.tcp_pose(q[:k]), setup.door.grasp_pose(q[k], q[k + 1]) @ offset
        errors.append((np.linalg.norm(pose[:3, 3] - target[:3, 3]),
                       np.linalg.norm(rotation_vector(pose[:3, :3] @ target[:3, :3].T))))
    return np.array(errors)


def _acceleration_cost(trajectory):
    return float(np.sum(np.diff(trajectory, n=2, axis=0) ** 2))


def test_approach_ends_on_the_handle_within_limits_and_balance(approach):
    """The TCP ends ``grasp_clearance`` in front of the grasp point (the grasp closes within
    2 cm), oriented for the grasp."""
    setup, plan = approach
    trajectory = plan.result.trajectory
    position, rotation = _tcp_errors(setup, trajectory[-1:])[0]
    clearance = MotionLibrary().options.grasp_clearance
    assert position == pytest.approx(clearance, abs=0.005) and rotation < 0.01
    chain = setup.chain
    assert np.all(trajectory[:, :chain.size] >= chain.lower - 1e-6)
    assert np.all(trajectory[:, :chain.size] <= chain.upper + 1e-6)
    x_min, x_max, y_min, y_max = setup.support_polygon
    for q in trajectory:
        com = setup.level @ chain.com_and_jacobian(q[:chain.size])[0]  # levelled, as the polygon
        assert x_min <= com[0] <= x_max and y_min <= com[1] <= y_max
        elbow = chain.point_and_jacobian(q[:chain.size], chain.elbow_frame)[0]
        assert (elbow - setup.door.grasp_point) @ setup.door.normal > 0.0  # in front of the door
    assert plan.path.times[-1] > 0 and np.all(np.diff(plan.path.times) > 0)


@pytest.mark.parametrize("backend", list(Backend))
def test_optimum_beats_the_initial_guess(scene, backend):
    """From the IK-keyed guess (a few cm off its key poses, CoM and clearance not enforced),
    both backends reach a feasible trajectory that also costs less (smoothness Q1 + posture Q2)."""
    world, kinematics, estimate = scene
    setup = motion_setup(world, kinematics, estimate)
    built = build_motion(Motion.APPROACH_HANDLE, setup, setup.chain.chain_of(setup.chain.body_q))
    evaluator = ProblemEvaluator.for_problem(built.problem)
    guess = evaluator.values(built.problem.free_vector(built.initial_guess))
    solver = SqpSolver(built.problem) if backend is Backend.SQP else ChompSolver(built.problem)
    result = solver.solve(built.initial_guess)
    assert result.outcome is Outcome.SUCCESS, result.message
    assert result.max_violation < 1e-6 < guess.infeasibility()
    assert result.cost < guess.cost


@pytest.mark.parametrize("backend", list(Backend))
def test_turn_keeps_the_hand_on_the_handle_along_the_closed_chain(approach, backend):
    setup, plan = approach
    start = plan.result.trajectory[-1, :setup.chain.size]
    turn = MotionLibrary().plan(Motion.TURN_HANDLE, setup, start, backend)
    assert turn.succeeded, turn.result.message
    errors = _tcp_errors(anchored_to_hand(setup, start), turn.result.trajectory)  # the hand as it closed
    assert errors[:, 0].max() < 0.005 and errors[:, 1].max() < 0.01
    assert turn.final_door[1] == pytest.approx(MotionLibrary().options.handle_turn, abs=1e-4)
    assert turn.final_door[0] == pytest.approx(0.0, abs=1e-9)  # the door stays shut while turning


def test_both_backends_agree_on_the_turn(approach):
    setup, plan = approach
    start = plan.result.trajectory[-1, :setup.chain.size]
    costs = [MotionLibrary().plan(Motion.TURN_HANDLE, setup, start, backend).result.cost for backend in Backend]
    assert costs[0] == pytest.approx(costs[1], rel=0.25)


def test_unreachable_handle_is_infeasible_and_names_the_constraint(scene):
    world, kinematics, estimate = scene
    far = replace(estimate, handle_position=(estimate.handle_position[0] + 1.5, *estimate.handle_position[1:]))
    setup = motion_setup(world, kinematics, far)
    library = MotionLibrary(starts=1)
    plan = library.plan(Motion.APPROACH_HANDLE, setup, setup.chain.chain_of(setup.chain.body_q))
    assert not plan.succeeded and plan.path is None
    assert plan.result.outcome is not Outcome.SUCCESS
    assert plan.result.violated_constraint in ("pregrasp_pose", "grasp_pose")


@pytest.mark.slow
@pytest.mark.parametrize("backend", list(Backend))
def test_planned_turn_and_push_open_the_simulated_door(backend):
    world = stand_world(DoorOpening.PUSH)
    kinematics, library = talos_kinematics(), MotionLibrary()
    estimate = estimate_from_world(world)
    door_angle = 0.0
    try:
        for motion in (Motion.APPROACH_HANDLE, "grasp", Motion.TURN_HANDLE, Motion.PUSH_DOOR):
            if motion == "grasp":
                assert world.grasp(grasp_hand(estimate.hinge_side, DoorOpening.PUSH), True).success
                continue
            setup = motion_setup(world, kinematics, estimate,
                                 door_angles=start_door_for(motion, door_angle, library.options))
            plan = library.plan(motion, setup, setup.chain.chain_of(setup.chain.body_q), backend)
            assert plan.succeeded, f"{motion.value}: {plan.result.message}"
            result = TrajectoryExecution.from_joint_path(world, plan.path).run()
            assert result.status.value == "success", f"{motion.value}: {result.reason}"
            door_angle = plan.final_door[0]
        state = world.door_state()
        assert not state.latched
        assert state.hinge_angle > 0.15  # planned 0.2 rad
    finally:
        world.close()


def test_push_never_swings_the_door_past_its_goal(scene, approach):
    """The hinge is a free DOF of the optimisation: unbounded, the optimum swung the door
    out to 0.27–0.42 rad and pulled it back, and TALOS's forearm met the post on the way."""
    world, kinematics, estimate = scene
    setup, approach_plan = approach
    library, k = MotionLibrary(), setup.chain.size
    for width in (estimate.width, estimate.width + 0.04):
        wide = motion_setup(world, kinematics, replace(estimate, width=width))
        turn = library.plan(Motion.TURN_HANDLE, wide, approach_plan.result.trajectory[-1, :k])
        assert turn.succeeded, turn.result.message
        push = library.plan(Motion.PUSH_DOOR,
                            replace(wide, start_door=start_door_for(Motion.PUSH_DOOR, 0.0, library.options)),
                            turn.result.trajectory[-1, :k])
        assert push.succeeded, push.result.message
        hinge = push.result.trajectory[:, k]
        assert hinge.max() <= library.options.push_angle + 1e-6
        assert hinge[-1] == pytest.approx(library.options.push_angle, abs=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("hinge", list(HingeSide))
def test_pulled_door_is_blocked_by_the_other_hand_when_the_first_lets_go(hinge):
    """[Banerjee 2015] Fig. 2: pull with the hinge-side hand, insert the other hand behind the leaf,
    release the handle and bring the arm to the walking posture: the door stays open on the
    blocking hand instead of closing (closer ~5 N·m at 0.35 rad)."""
    world = stand_world(DoorOpening.PULL, hinge)
    kinematics, library = talos_kinematics(), MotionLibrary()
    estimate = estimate_from_world(world)
    pulling = grasp_hand(estimate.hinge_side, DoorOpening.PULL)
    door_angle = 0.0
    try:
        for motion in (Motion.APPROACH_HANDLE, "grasp", Motion.TURN_HANDLE, Motion.PULL_DOOR, Motion.BLOCK_DOOR,
                       "release", Motion.READY_TO_WALK):
            if motion in ("grasp", "release"):
                assert world.grasp(pulling, motion == "grasp").success
                continue
            side = pulling.other if motion.moves_other_arm(DoorOpening.PULL) else pulling
            setup = motion_setup(world, kinematics, estimate, side=side,
                                 door_angles=start_door_for(motion, door_angle, library.options))
            plan = library.plan(motion, setup, setup.chain.chain_of(setup.chain.body_q))
            assert plan.succeeded, f"{motion.value}: {plan.result.message}"
            result = TrajectoryExecution.from_joint_path(world, plan.path).run()
            assert result.status.value == "success", f"{motion.value}: {result.reason}"
            door_angle = plan.final_door[0]
        world.step(480)  # 2 s more: a door that the block did not hold would have shut by now
        state = world.door_state()
        assert not world.holding(pulling)
        assert 0.3 < state.hinge_angle < 0.45  # pulled to 0.35 rad, resting on the blocking hand
        assert world.scene_penetration() < 0.01
    finally:
        world.close()


@pytest.mark.parametrize("door_angles", [(1e6, 0.0), (-0.5, 0.0), (0.0, 2.0), (float("nan"), 0.0)])
def test_a_door_state_outside_the_stops_is_refused_before_any_work(scene, door_angles):
    """A turn_handle at θ = 1e6 rad once ran every IK and guess to its budget (80 s)."""
    world, kinematics, estimate = scene
    setup = motion_setup(world, kinematics, estimate, door_angles=door_angles)
    with pytest.raises(DoorStateOutOfRange, match=r"door (hinge|handle) angle = .* is outside the allowed range") as error:
        MotionLibrary().plan(Motion.TURN_HANDLE, setup, setup.chain.chain_of(setup.chain.body_q))
    assert isinstance(error.value, TrajoptError) and not isinstance(error.value, ValueError)  # REJECTED by the node


def test_a_repeat_skips_the_cache_and_tries_more_guesses_with_more_iterations(scene):
    world, kinematics, estimate = scene
    setup = motion_setup(world, kinematics, estimate)
    start = setup.chain.chain_of(setup.chain.body_q)
    library = MotionLibrary()
    first = library.plan(Motion.APPROACH_HANDLE, setup, start)
    cached = library.plan(Motion.APPROACH_HANDLE, setup, start)
    assert first.succeeded and cached.succeeded
    assert np.array_equal(cached.initial_guess, first.result.trajectory)  # the first try reuses the cache
    repeat = library.plan(Motion.APPROACH_HANDLE, setup, start, attempt=1)
    assert repeat.succeeded
    assert not np.array_equal(repeat.initial_guess, first.result.trajectory)  # a repeat starts afresh
    unreachable = motion_setup(world, kinematics, replace(
        estimate, handle_position=(estimate.handle_position[0] + 1.5, *estimate.handle_position[1:])))
    tries = [MotionLibrary(starts=1, max_iterations=5).plan(Motion.APPROACH_HANDLE, unreachable,
                                                            start, attempt=attempt) for attempt in (0, 1)]
    assert [plan.attempts for plan in tries] == [1, 2]
    assert tries[1].result.iterations > tries[0].result.iterations
    with pytest.raises(TrajoptError, match="attempt"):
        library.plan(Motion.APPROACH_HANDLE, setup, start, attempt=-1)


@pytest.mark.parametrize("backend", list(Backend))
def test_the_tuck_takes_the_blocking_arm_to_the_walking_posture_with_the_torso_held(scene, backend):
    """A pull passage's tuck (footstep_planner.pull_passage): the blocking arm's own joints end
    in the profile's walking posture, the torso (shared with the other arm) never moves, the
    CoM stays over the feet, and it takes at least ``tuck_duration`` (the leaf follows the hand)."""
    world, kinematics, estimate = scene
    library = MotionLibrary()
    side = grasp_hand(estimate.hinge_side, DoorOpening.PULL).other
    assert Motion.TUCK_ARM.moves_other_arm(DoorOpening.PULL) and not Motion.TUCK_ARM.moves_other_arm(DoorOpening.PUSH)
    setup = motion_setup(world, kinematics, estimate, side=side,
                         door_angles=start_door_for(Motion.TUCK_ARM, 1.7500004, library.options))
    assert setup.start_door == (1.75, 0.0)  # a leaf on its stop reads a hair beyond it
    start = setup.chain.chain_of(setup.chain.body_q)
    plan = library.plan(Motion.TUCK_ARM, setup, start, backend)
    assert plan.succeeded, plan.result.message
    names = setup.chain.joint_names
    walking = setup.chain.chain_of(kinematics.walking_q)
    shared = [i for i, name in enumerate(names) if name in kinematics.profile.arm(side.other).joints]
    own = [i for i in range(len(names)) if i not in shared]
    assert shared and own
    assert np.allclose(plan.path.positions[:, shared], start[shared], atol=1e-6)
    assert np.allclose(plan.path.positions[-1, own], walking[own], atol=1e-4)
    assert plan.path.times[-1] >= library.options.tuck_duration - 1e-9
    assert plan.result.max_violation <= library.constraint_tolerance


@pytest.mark.slow
def test_sideways_the_hinge_side_hand_opens_a_push_door_and_holds_it_with_the_arm_inside_the_doorway():
    """footstep_planner.push_passage (the default): the robot stands sideways, its back to the
    hinge; the hinge-side hand approaches, grasps, turns and pushes, lets go, and ready_to_walk
    keeps it on the leaf (the door never closes on the latch) with every arm joint inside the
    doorway, doorway_arm_margin from the latch-side post (the elbow struck the post without)."""
    from door_bringup.passage_rig import NODE_DEFAULTS, open_door, opening_hand
    from door_bringup.passage_rig import stand_world as rig_stand_world
    from door_sim_bridge.world import DoorConfig

    parameters = {**NODE_DEFAULTS, "push_passage": "sideways"}
    kinematics = talos_kinematics()
    with rig_stand_world(DoorConfig(opening=DoorOpening.PUSH, hinge_side=HingeSide.LEFT), robot="talos",
                         parameters=parameters) as world:
        estimate = estimate_from_world(world)
        hand = opening_hand(world, estimate)
        assert hand is estimate.hinge_side
        stage, status, reason = open_door(world, kinematics, estimate, {}, hand)
        assert (stage, status) == (Motion.READY_TO_WALK.value, "success"), reason
        world.step(240)  # a second on: the closer presses the leaf against the hand
        door = world.door_state()
        assert not door.latched and door.hinge_angle > 0.1
        setup = motion_setup(world, kinematics, estimate, hand)
        along = setup.door.along
        limit = setup.door_width - MotionLibrary().options.post_inset
        chain = setup.chain
        arm = [chain.body_frame(i) for i in range(2, chain.size)] + [chain.tcp_frame]
        q = chain.chain_of(chain.body_q)
        for frame in arm:  # inside the doorway, short of the latch-side post's face
            point = chain.point_and_jacobian(q, frame)[0]
            assert (point - setup.door.hinge_point) @ along < limit, frame


def test_sideways_ready_to_walk_starts_from_a_guess_on_the_leaf_and_inside_the_doorway():
    """The push passage's ready_to_walk (sideways stance, the benchmark's door): its initial
    guess turns the torso back while the hand slides along the leaf, so every waypoint is on
    the leaf with the hand's orientation and the arm ends inside the doorway; the SQP then only
    polishes (it took 28 iterations from a guess that held the arm 0.21 m outside, issue #15)."""
    from door_evaluation.trajopt.benchmark_motions import DOOR_WIDTH, scenarios
    from door_trajopt.chain import ArmChain
    from door_trajopt.constraints import ConstraintStack
    from door_trajopt.motions import MotionSetup, support_polygon
    from door_trajopt.problem import ConstraintKind

    kinematics = talos_kinematics()
    scenario = next(s for s in scenarios(kinematics) if s.name == "push, sideways")
    library, body_q, angle = MotionLibrary(), kinematics.nominal_q.copy(), 0.0
    for motion in scenario.sequence:
        chain = ArmChain(kinematics, scenario.hand, body_q)
        setup = MotionSetup(chain, scenario.door, DOOR_WIDTH, support_polygon(chain),
                            start_door_for(motion, angle, library.options))
        if motion is Motion.READY_TO_WALK:
            built = build_motion(motion, setup, chain.chain_of(body_q), library.options)
            for kind in ConstraintKind:
                stack = ConstraintStack.of_kind(built.problem, kind)
                violations = stack.violations(stack.values(built.initial_guess))
                named = {stack.block_name(row) for row in np.flatnonzero(violations > 1e-3)}
                assert not named & {"on_leaf", "hand_orientation", "arm_in_doorway"}, named
        plan = library.plan(motion, setup, chain.chain_of(body_q), Backend.SQP)
        assert plan.succeeded, (motion, plan.result.message)
        body_q, angle = chain.full(plan.result.trajectory[-1, :chain.size]), plan.final_door[0]
        library.clear_cache()
    assert plan.result.iterations <= 15


def test_a_push_doors_tuck_takes_the_pushing_arm_to_the_walking_posture_with_the_torso_held():
    """A wide push door's tuck (footstep_planner.push_passage): the arm that pushed the door —
    the grasping hand, not the other — goes from ready_to_walk's pose on the leaf to the
    walking posture; the torso (shared with the other arm) stays where the opening left it."""
    from door_evaluation.trajopt.benchmark_motions import DOOR_WIDTH, scenarios
    from door_trajopt.chain import ArmChain
    from door_trajopt.motions import MotionSetup, support_polygon

    kinematics = talos_kinematics()
    scenario = next(s for s in scenarios(kinematics) if s.name == "push, sideways")
    library, body_q, angle = MotionLibrary(), kinematics.nominal_q.copy(), 0.0
    for motion in (*scenario.sequence, Motion.TUCK_ARM):
        side = scenario.hand.other if motion.moves_other_arm(DoorOpening.PUSH) else scenario.hand
        assert side is scenario.hand
        chain = ArmChain(kinematics, side, body_q)
        setup = MotionSetup(chain, scenario.door, DOOR_WIDTH, support_polygon(chain),
                            start_door_for(motion, angle, library.options))
        start = chain.chain_of(body_q)
        plan = library.plan(motion, setup, start, Backend.SQP)
        assert plan.succeeded, (motion, plan.result.message)
        body_q, angle = chain.full(plan.result.trajectory[-1, :chain.size]), plan.final_door[0]
    names = chain.joint_names
    shared = [i for i, name in enumerate(names) if name in kinematics.profile.arm(side.other).joints]
    own = [i for i in range(len(names)) if i not in shared]
    assert shared and own
    assert np.allclose(plan.path.positions[:, shared], start[shared], atol=1e-6)
    assert np.allclose(plan.path.positions[-1, own], chain.chain_of(kinematics.walking_q)[own], atol=1e-4)
    assert plan.path.times[-1] >= library.options.tuck_duration - 1e-9


@pytest.mark.parametrize("hand", [Side.LEFT, Side.RIGHT])
@pytest.mark.parametrize("lever_height", [0.87, 0.88])
def test_sideways_a_low_lever_is_grasped_with_room_left_to_turn_it(lever_height, hand):
    """The approach's key pose is the IK solution farthest from the joint limits: the first one
    found put TALOS's shoulder roll at its limit for a lever at 0.87-0.88 m (sideways stance),
    and no turn was feasible from that grasp (closed chain off by 7.9 cm; a full-range
    Monte-Carlo door failed its four TURN_HANDLE attempts so). The right hand opens the mirrored
    door: with 6 random IK seeds it never met the branch that turns (24 now)."""
    from door_evaluation.trajopt.benchmark_motions import DOOR_WIDTH, scenarios
    from door_trajopt.chain import ArmChain
    from door_trajopt.door_model import DoorModel
    from door_trajopt.motions import MotionSetup, support_polygon

    kinematics = talos_kinematics()
    scenario = next(s for s in scenarios(kinematics) if s.name == "push, sideways")
    assert scenario.hand is Side.LEFT
    drop = np.array([0.0, 0.0, lever_height - 0.91])
    mirror = np.array([1.0, 1.0 if hand is Side.LEFT else -1.0, 1.0])  # about the robot's sagittal plane
    door = DoorModel(mirror * (scenario.door.grasp_point + drop), mirror * scenario.door.normal,
                     mirror * (scenario.door.hinge_point + drop), push=True)
    library, body_q, angle = MotionLibrary(), kinematics.nominal_q.copy(), 0.0
    for motion in (Motion.APPROACH_HANDLE, Motion.TURN_HANDLE):
        chain = ArmChain(kinematics, hand, body_q)
        setup = MotionSetup(chain, door, DOOR_WIDTH, support_polygon(chain), start_door_for(motion, angle, library.options))
        plan = library.plan(motion, setup, chain.chain_of(body_q), Backend.SQP)
        assert plan.succeeded, (motion, plan.result.message, plan.result.violated_constraint)
        body_q, angle = chain.full(plan.result.trajectory[-1, :chain.size]), plan.final_door[0]
        library.clear_cache()


def test_sideways_chomp_plans_every_motion_of_the_push_door():
    """Constrained CHOMP through the sideways push sequence: its ready_to_walk stalled ("no merit
    decrease") on 68 of 78 doors, a limit the working set had released for its negative
    multiplier being pushed through by the next step and clipped; such limits now join the
    working set when the line search finds no decrease."""
    from door_evaluation.trajopt.benchmark_motions import run_sequence, scenarios

    kinematics = talos_kinematics()
    scenario = next(s for s in scenarios(kinematics) if s.name == "push, sideways")
    planned = run_sequence(kinematics, scenario, MotionLibrary(), Backend.CHOMP)
    assert Motion.READY_TO_WALK in planned
    assert all(succeeded for *_, succeeded in planned.values()), \
        {motion.value: succeeded for motion, (*_, succeeded) in planned.items()}
