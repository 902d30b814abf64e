"""``operator_console``: watch the door task and answer it from a terminal.

Shows ``/door_task/state`` and ``/door_task/approval_request`` as they change and sends what
you type on ``/door_task/operator`` — the same topic and message as ``ros2 topic pub
/door_task/operator std_msgs/msg/String "{data: 'approve 7'}"``. Answers name the request:
``approve 7``, ``reject 7``, ``repeat 7``; a bare ``approve``/``reject``/``repeat`` here answers
the request shown last. ``pause``, ``stop``, ``resume``, ``abort``, ``manual`` need no id.
``--approve-all`` answers every approval request itself (scripted operator for
demonstrations and tests), again every 2 s until the FSM takes the answer.
"""

from __future__ import annotations

import argparse
import sys
import threading
import time

from rclpy.node import Node
from std_msgs.msg import String

from door_contract.node_support import create_contract_publisher, create_contract_subscription, run_node
from door_contract.topics import Topics
from door_fsm.answer_retry import AnswerRetry
from door_fsm.operator_commands import (
    OperatorCommand,
    OperatorWord,
    UnknownCommandError,
    parse_command,
    request_id_of,
    usage,
)

__all__ = ["OperatorConsole", "main"]


class OperatorConsole(Node):
    def __init__(self, approve_all: bool) -> None:
        super().__init__("operator_console")
        self.approve_all = approve_all
        self.command_pub = create_contract_publisher(self, Topics.OPERATOR)
        create_contract_subscription(self, Topics.TASK_STATE, self._on_state)
        create_contract_subscription(self, Topics.APPROVAL_REQUEST, self._on_request)
        self.state = ""
        self.shown_request: int | None = None  # the id of the approval request shown last
        self.answers = AnswerRetry()  # --approve-all: an answer lost before DDS matched the FSM is sent again
        if approve_all:
            self.create_timer(self.answers.options.check_period_s, self._resend)

    def _on_state(self, msg: String) -> None:
        self.state = msg.data
        print(f"[state] {msg.data}", flush=True)

    def _on_request(self, msg: String) -> None:
        if msg.data:
            self.shown_request = request_id_of(msg.data)
            print(f"[approval request] {msg.data}", flush=True)
        if self.approve_all:
            self._approve(self.answers.on_request(msg.data, time.monotonic()))

    def _resend(self) -> None:
        self._approve(self.answers.due(time.monotonic()))

    def _approve(self, request_id: int | None) -> None:
        if request_id is not None:
            self.send(OperatorWord(OperatorCommand.APPROVE, request_id))

    def send(self, word: OperatorWord) -> None:
        self.command_pub.publish(String(data=str(word)))
        print(f"[sent] {word}", flush=True)

    def typed(self, line: str) -> OperatorWord:
        """What a typed line means: a bare approve/reject/repeat answers the request shown last."""
        words = line.split()
        if len(words) == 1 and words[0].lower() in ("approve", "reject", "repeat") and self.shown_request is not None:
            line = f"{words[0]} {self.shown_request}"
        return parse_command(line)


def _read_commands(console: OperatorConsole) -> None:
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            console.send(console.typed(line))
        except UnknownCommandError as error:
            print(f"[error] {error}", flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--approve-all", action="store_true", help="approve every request automatically")
    args, ros_args = parser.parse_known_args(argv)
    return run_node(lambda: _start_console(args.approve_all), ros_args)


def _start_console(approve_all: bool) -> OperatorConsole:
    console = OperatorConsole(approve_all)
    print(f"commands: {usage()}", flush=True)
    threading.Thread(target=_read_commands, args=(console,), daemon=True).start()
    return console


if __name__ == "__main__":
    sys.exit(main())
