"""Issue #13's first failure class through the graph: a door partly out of the head camera's
view at the start (the three starts that timed out in DETECT_DOOR: 3.6 m away turned 0.55 rad,
1.1 m turned -0.45 rad, 1.0 m with the robot 0.4 m aside; one door edge beyond the image) is
confirmed after the detector's head search, which the FSM executes while DETECT_DOOR waits
(door_detection.head_search). Every node is a process over real DDS. Without the search the
1.1 m start confirmed nothing in 60 s; with it, the door in ~15 s."""

import numpy as np
import pytest
import rclpy
from ros_helpers import executor_for, spin_until

from door_bringup.door_task import TaskOptions
from door_bringup.graph_spec import GRAPH
from door_bringup.processes import ProcessSupervisor
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.node_support import create_contract_subscription
from door_contract.payloads import DoorEstimate, decode
from door_contract.topics import Topics
from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.world import DoorConfig, DoorWorld, StanceConfig, WorldConfig

pytestmark = [pytest.mark.slow, pytest.mark.ros]
PAN = "head_2_joint"


@pytest.mark.parametrize("distance, lateral, yaw", [(3.6, 0.0, 0.55), (1.1, 0.0, -0.45), (1.0, -0.4, 0.0)])
def test_a_door_out_of_view_at_the_start_is_confirmed_after_the_head_search(distance, lateral, yaw, workspace,
                                                                             tmp_path, rclpy_context):
    start = TaskOptions(opening="push", hinge="left", distance=distance, lateral=lateral, yaw=yaw, autonomy="full",
                        record=False)
    with DoorWorld(WorldConfig(door=DoorConfig(opening=DoorOpening.PUSH, hinge_side=HingeSide.LEFT),
                               stance=StanceConfig(distance=distance, lateral_offset=lateral, yaw=yaw))) as world:
        handle = world.handle_grasp_pose()[:3, 3]
    graph = ProcessSupervisor(workspace, tmp_path / "logs")
    node = rclpy.create_node("head_search_listener", context=rclpy_context)
    estimates, pans, looks = [], [], []
    create_contract_subscription(node, Topics.DOOR_ESTIMATE, lambda m: estimates.append(decode(DoorEstimate, m.data)))
    create_contract_subscription(node, Topics.JOINT_STATES,
                                 lambda m: pans.append(joint_state_to_positions(m).get(PAN, 0.0)))
    create_contract_subscription(node, Topics.HEAD_LOOK, looks.append)
    executor = executor_for(node, rclpy_context)
    overrides = start.node_overrides()
    try:
        for launch in GRAPH:
            graph.start(launch, overrides[launch.node_name])
        assert spin_until(executor, lambda: bool(estimates), 240.0), "no door confirmed"
        # the search ends at the confirmation, so its looks were all sent by now
        assert spin_until(executor, lambda: bool(looks), 10.0), "confirmed without a head search"
    finally:
        graph.stop()
        node.destroy_node()
    # the head turned to find it: its first look is to ±0.3 rad, and with the camera at 8 Hz
    # while the robot stands the door may be confirmed on the way there (0.16 rad once, 0.098
    # once), so the pan is only asked to have left home (it holds within 1e-3 rad of 0 there)
    assert max(abs(pan) for pan in pans) > 0.03
    assert np.linalg.norm(np.array(estimates[0].handle_position) - handle) < 0.05
