"""The automatic operators (the main job's, ``operator_console --approve-all``) answer again until
the FSM takes the answer: over real DDS, an FSM
whose subscription to /door_task/operator appears only after the first answer went out (what DDS
matching did on a fresh clone in stop 38: the approval was lost, the task failed after 300 s)
still receives ``approve N``, and a cleared request stops the repeats."""

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from ros_helpers import spin_until
from std_msgs.msg import String

from door_bringup.door_task import ScriptedOperator
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.topics import Topics
from door_fsm.operator_console import OperatorConsole

pytestmark = pytest.mark.ros

REQUEST = "DETECT_DOOR #3: approve detection 'door'? width=0.91 | reply 'approve 3', 'reject 3' or 'repeat 3'"


@pytest.mark.parametrize("make_operator", [lambda: ScriptedOperator(approve=True),
                                           lambda: OperatorConsole(approve_all=True)], ids=["main_job", "console"])
def test_an_answer_lost_before_the_fsm_subscribed_is_sent_again(make_operator):
    rclpy.init()
    operator = make_operator()
    fsm = rclpy.create_node("fake_fsm_supervisor")
    executor = SingleThreadedExecutor()
    executor.add_node(operator)
    executor.add_node(fsm)
    try:
        request_pub = create_contract_publisher(fsm, Topics.APPROVAL_REQUEST)
        request_pub.publish(String(data=REQUEST))  # latched: the operator receives it when it matches
        assert spin_until(executor, lambda: operator.answers.sends >= 1, timeout_s=30.0), "never answered"
        answers: list[str] = []  # subscribed only now: the first answer cannot have reached it
        create_contract_subscription(fsm, Topics.OPERATOR, lambda msg: answers.append(msg.data))
        assert spin_until(executor, lambda: "approve 3" in answers, timeout_s=30.0), operator.answers.sends
        assert operator.answers.sends >= 2
        request_pub.publish(String(data=""))  # the FSM took it: the request is cleared
        assert spin_until(executor, lambda: operator.answers.pending is None, timeout_s=30.0)
        assert operator.answers.due(float("inf")) is None
    finally:
        executor.shutdown()
        fsm.destroy_node()
        operator.destroy_node()
        rclpy.try_shutdown()
