"""Every package has one base error, and none is a ValueError: a node that catches its
package's error as bad input must not also take a bug's ValueError for bad input (issue #17)."""

import pytest

from door_contract.errors import ContractError
from door_detection.errors import DetectionError, InputError
from door_fsm.errors import DoorFsmError
from door_fsm.machine import MachineOptionsError
from door_fsm.operator_commands import UnknownCommandError
from door_fsm.wiring import WiringError
from door_robot.errors import RobotModelError
from door_sim_bridge.errors import SimulationError
from door_trajopt.motions import DoorStateOutOfRange
from door_trajopt.problem import TrajoptError
from door_viz.errors import DoorVizError
from door_viz.foxglove_core import ClientCommandError
from footstep_planner.errors import FootstepPlannerError

BASES = (ContractError, DetectionError, DoorFsmError, RobotModelError, SimulationError, TrajoptError, DoorVizError,
         FootstepPlannerError)


@pytest.mark.parametrize("base", BASES, ids=lambda error: error.__name__)
def test_a_package_base_error_is_no_value_error(base):
    assert issubclass(base, Exception) and not issubclass(base, ValueError)


@pytest.mark.parametrize("error, base", [
    (InputError, DetectionError), (MachineOptionsError, DoorFsmError), (UnknownCommandError, DoorFsmError),
    (WiringError, DoorFsmError), (DoorStateOutOfRange, TrajoptError), (ClientCommandError, DoorVizError),
], ids=lambda error: error.__name__)
def test_each_error_derives_from_its_package_base(error, base):
    assert issubclass(error, base)
