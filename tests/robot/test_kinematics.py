"""Robot profiles and Pinocchio kinematics: FK against PyBullet, Jacobians against finite
differences, the seed papers' robots from ../shared/data."""

import numpy as np
import pybullet
import pytest

from door_contract.vocabulary import Side
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile


@pytest.fixture(scope="module")
def talos() -> RobotKinematics:
    return RobotKinematics(load_profile("talos"))


def _random_q(kin: RobotKinematics, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(kin.lower_limits, kin.upper_limits)


def _pybullet_link_frames(kin: RobotKinematics, q: np.ndarray) -> dict[str, np.ndarray]:
    """URDF link frames of every link from PyBullet, for a configuration given by joint name."""
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(kin.profile.urdf_path), useFixedBase=True,
                                 flags=pybullet.URDF_USE_INERTIA_FROM_FILE, physicsClientId=client)
        frames = {}
        for j in range(pybullet.getNumJoints(body, physicsClientId=client)):
            info = pybullet.getJointInfo(body, j, physicsClientId=client)
            name = info[1].decode()
            if name in kin.joint_names:
                pybullet.resetJointState(body, j, q[kin.joint_indices([name])[0]], physicsClientId=client)
        for j in range(pybullet.getNumJoints(body, physicsClientId=client)):
            link = pybullet.getJointInfo(body, j, physicsClientId=client)[12].decode()
            state = pybullet.getLinkState(body, j, computeForwardKinematics=True, physicsClientId=client)
            transform = np.eye(4)
            transform[:3, :3] = np.reshape(pybullet.getMatrixFromQuaternion(state[5]), (3, 3))
            transform[:3, 3] = state[4]
            frames[link] = transform
        return frames
    finally:
        pybullet.disconnect(client)


@pytest.mark.parametrize("seed", [0, 1])
def test_forward_kinematics_matches_pybullet(talos, seed):
    """Every link frame relative to torso_1_link agrees with PyBullet to 1e-6 m (base-independent)."""
    q = _random_q(talos, seed)
    bullet = _pybullet_link_frames(talos, q)
    reference = "torso_1_link"
    ours_ref, bullet_ref = talos.frame_pose(q, reference), bullet[reference]
    compared = 0
    for link, bullet_pose in bullet.items():
        if not talos.model.existFrame(link):
            continue
        ours = np.linalg.inv(ours_ref) @ talos.frame_pose(q, link)
        theirs = np.linalg.inv(bullet_ref) @ bullet_pose
        np.testing.assert_allclose(ours[:3, 3], theirs[:3, 3], atol=1e-6, err_msg=link)
        np.testing.assert_allclose(ours[:3, :3], theirs[:3, :3], atol=1e-6, err_msg=link)
        compared += 1
    assert compared > 40


def test_frame_jacobian_matches_finite_differences(talos):
    q = _random_q(talos, 3)
    jacobian = talos.frame_jacobian(q, "left_tcp")
    step = 1e-6
    for i in talos.arm_indices(Side.LEFT):
        dq = np.zeros_like(q)
        dq[i] = step
        moved = (talos.frame_pose(q + dq, "left_tcp")[:3, 3] - talos.frame_pose(q - dq, "left_tcp")[:3, 3]) / (2 * step)
        np.testing.assert_allclose(jacobian[:3, i], moved, atol=1e-6)


def test_com_jacobian_matches_finite_differences(talos):
    q = _random_q(talos, 4)
    jacobian = talos.com_jacobian(q)
    step = 1e-6
    for i in range(0, q.size, 5):
        dq = np.zeros_like(q)
        dq[i] = step
        moved = (talos.center_of_mass(q + dq) - talos.center_of_mass(q - dq)) / (2 * step)
        np.testing.assert_allclose(jacobian[:, i], moved, atol=1e-6)


def test_batched_equals_single(talos):
    trajectory = np.stack([_random_q(talos, s) for s in range(5)])
    poses = talos.frame_poses(trajectory, "right_tcp")
    jacobians = talos.frame_jacobians(trajectory, "right_tcp")
    coms = talos.centers_of_mass(trajectory)
    com_jacobians = talos.com_jacobians(trajectory)
    assert poses.shape == (5, 4, 4) and jacobians.shape == (5, 6, talos.model.nv)
    for t, q in enumerate(trajectory):
        np.testing.assert_allclose(poses[t], talos.frame_pose(q, "right_tcp"))
        np.testing.assert_allclose(jacobians[t], talos.frame_jacobian(q, "right_tcp"))
        np.testing.assert_allclose(coms[t], talos.center_of_mass(q))
        np.testing.assert_allclose(com_jacobians[t], talos.com_jacobian(q))


def test_talos_profile_is_consistent(talos):
    profile = talos.profile
    assert len(profile.arm(Side.LEFT).joints) == 9  # 2 torso + 7 arm joints
    q = talos.nominal_q
    assert talos.within_limits(q)
    sole = talos.frame_pose(q, profile.feet[Side.LEFT])
    assert -sole[2, 3] == pytest.approx(profile.base_height, abs=0.01)
    left, right = talos.frame_pose(q, "left_tcp"), talos.frame_pose(q, "right_tcp")
    np.testing.assert_allclose(left[:3, 3] * [1, -1, 1], right[:3, 3], atol=1e-3)  # mirror image
    com = talos.center_of_mass(q)
    assert abs(com[0]) < 0.05 and abs(com[1]) < 0.01  # above the feet


def test_unknown_names_are_errors(talos):
    with pytest.raises(RobotModelError, match="no joint 'elbow'"):
        talos.configuration({"elbow": 0.1})
    with pytest.raises(RobotModelError, match="no frame"):
        talos.frame_pose(talos.nominal_q, "nose")
    with pytest.raises(RobotModelError, match="NaN"):
        talos.configuration({"torso_1_joint": float("nan")})
    with pytest.raises(RobotModelError, match="not found"):
        load_profile("asimo")


@pytest.mark.parametrize("name, joints", [("atlas_v4", 30), ("drc_hubo", 35)])
def test_seed_paper_robots_load_with_consistent_fk(shared_data, name, joints):
    kin = RobotKinematics(load_profile(name))
    assert len(kin.joint_names) == joints
    q = kin.nominal_q
    left, right = kin.frame_pose(q, "left_tcp"), kin.frame_pose(q, "right_tcp")
    assert left[1, 3] > 0.1 and right[1, 3] < -0.1  # left hand on the left (REP-103: y left)
    assert abs(left[1, 3] + right[1, 3]) < 0.02     # symmetric robot, symmetric posture
    for side in Side:
        sole = kin.frame_pose(q, kin.profile.feet[side])
        assert -sole[2, 3] == pytest.approx(kin.profile.base_height, abs=0.02)
    head = kin.frame_pose(q, kin.profile.head_camera_frame)
    assert head[2, 3] > left[2, 3] - 0.05  # the head is above the hands
