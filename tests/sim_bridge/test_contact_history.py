"""What struck the robot before it fell: the last seconds' robot–door contacts, hardest first,
and a FELL outcome of the loop that names them (door_sim_bridge.contact_history)."""

from __future__ import annotations

import pytest
from walk_plans import straight_plan

from door_contract.payloads import ExecutionKind, OutcomeStatus
from door_sim_bridge.contact_history import ContactHistory, ContactPeak
from door_sim_bridge.deadman import DeadMan
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.execution import FootstepExecution
from door_sim_bridge.simulation_loop import PublicationRates, SimulationLoop
from door_sim_bridge.world import DoorWorld, StanceConfig, WorldConfig


def test_the_hardest_contact_of_each_pair_in_the_window_is_kept_hardest_first():
    history = ContactHistory(window=3.0)
    history.record(1.0, {"base | handle": 3000.0})  # more than 3 s before the last sample: forgotten
    history.record(2.5, {"torso_2_link | leaf": 120.0, "base | handle": 40.0})
    history.record(3.0, {})
    history.record(4.1, {"torso_2_link | leaf": 510.0, "arm_left_2_link | leaf": 80.0})
    history.record(4.5, {"torso_2_link | leaf": 300.0})
    assert history.peaks() == (ContactPeak("torso_2_link | leaf", 510.0, 4.1), ContactPeak("arm_left_2_link | leaf", 80.0, 4.1),
                               ContactPeak("base | handle", 40.0, 2.5))
    assert history.peaks(count=1) == (ContactPeak("torso_2_link | leaf", 510.0, 4.1),)
    assert history.summary() == ("hardest robot–door contacts in the last 3 s: torso_2_link | leaf 510 N at t = 4.10 s, "
                                 "arm_left_2_link | leaf 80 N at t = 4.10 s, base | handle 40 N at t = 2.50 s")
    history.record(9.0, {})
    assert history.peaks() == () and history.summary() == "no robot–door contact in the last 3 s"


@pytest.mark.parametrize("window", [0.0, -1.0, float("nan"), float("inf")])
def test_a_window_that_is_not_a_positive_finite_time_is_refused(window):
    with pytest.raises(SimulationError, match="window"):
        ContactHistory(window)


def test_a_fall_outcome_of_the_loop_names_the_contacts_before_it():
    """The physical robot shoved over (200 N at the torso, far from the door, as the walking
    tests' shove): FELL, its reason the tilt and the contacts of the last 3 s — none here."""
    with DoorWorld(WorldConfig(stance=StanceConfig(distance=3.5))) as world:
        loop = SimulationLoop(world, DeadMan(0.0), PublicationRates(clock=0.0, state=0.0, tf=0.0, camera=0.0),
                              False, 0.0)
        plan = straight_plan(world, 0.2, 6)
        assert loop.submit(ExecutionKind.FOOTSTEPS, 7, lambda w: FootstepExecution(w, plan)).started is not None
        rate = int(world.config.physics_rate)
        while world.time < 1.0:
            loop.tick(0.0, lambda now, streams: None)
        world.push_robot("torso_2_link", [0.0, 200.0, 0.0], steps=rate // 2)
        outcomes = []
        while not outcomes and world.time < 7.0:
            outcomes.extend(loop.tick(0.0, lambda now, streams: None).outcomes)
    assert [(o.request_id, o.status) for o in outcomes] == [(7, OutcomeStatus.FELL)]
    assert "base tilted" in outcomes[0].reason
    assert outcomes[0].reason.endswith("; no robot–door contact in the last 3 s")
