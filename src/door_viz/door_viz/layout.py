"""The operator's Foxglove layout, generated from the contract's topics (so it never names a
topic the graph does not have), in the layout file format Foxglove and Lichtblick import
("Layouts → Import from file"):

* 3-D scene in ``odom`` following ``base_link``: the robot from /robot_description and /tf, the
  door estimate, the proposal markers (footsteps, hand path, door swing), the planner's
  footprints;
* the head camera with the door estimate and proposals drawn over it (3-D markers projected
  through the camera's calibration and /tf), and the detector's own overlay image;
* the FSM's state and approval request;
* buttons (Publish panels) for ``pause``, ``stop`` (all motion, at once), ``resume`` and
  ``abort``, and an editable Publish panel for ``approve <id>`` / ``reject <id>`` /
  ``repeat <id>`` — the id is the ``#<id>`` of the approval request;
* the nodes' log lines.

    python -m door_viz.layout     # rewrites src/door_viz/layouts/door_task.json (a test compares)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from door_contract.frames import Frame
from door_contract.topics import Topics

__all__ = ["LAYOUT_FILE", "layout_text", "main", "panel_configs"]

LAYOUT_FILE = Path(__file__).resolve().parents[1] / "layouts" / "door_task.json"
BUTTONS = (("pause", "#f5a623"), ("stop", "#e8590c"), ("resume", "#4a90e2"), ("abort", "#d0021b"))
SCENE_TOPICS = (Topics.ROBOT_DESCRIPTION, Topics.DOOR_MARKERS, Topics.PROPOSAL_MARKERS, Topics.FOOTSTEP_MARKERS)
OVERLAY_TOPICS = (Topics.DOOR_MARKERS, Topics.PROPOSAL_MARKERS)


Json = dict[str, Any]
"""A JSON object of the layout file."""
Mosaic = str | Json
"""A node of Foxglove's split tree: a panel id, or a split of two nodes."""


def _split(direction: str, first: Mosaic, second: Mosaic, percentage: float) -> Json:
    return {"direction": direction, "first": first, "second": second, "splitPercentage": percentage}


def _operator_publish(text: str, button: str, colour: str, advanced: bool) -> Json:
    return {"topicName": Topics.OPERATOR.name, "datatype": "std_msgs/msg/String", "buttonText": button,
            "buttonTooltip": f"publish {{data: {text}}} on {Topics.OPERATOR.name}", "buttonColor": colour,
            "advancedView": advanced, "value": json.dumps({"data": text})}


def panel_configs() -> dict[str, Json]:
    """Every panel's configuration by panel id (``<PanelType>!<name>``)."""
    configs: dict[str, Json] = {
        "3D!scene": {"followTf": Frame.BASE_LINK.value, "followMode": "follow-position",
                     "scene": {"transforms": {"showLabel": False}},
                     "topics": {topic.name: {"visible": True} for topic in SCENE_TOPICS},
                     "layers": {"grid": {"layerId": "foxglove.Grid", "visible": True, "frameId": Frame.ODOM.value,
                                         "size": 10, "divisions": 10, "position": [0, 0, 0]}}},
        "Image!camera": {"imageMode": {"imageTopic": Topics.COLOR_IMAGE.name,
                                       "calibrationTopic": Topics.COLOR_INFO.name},
                         "topics": {topic.name: {"visible": True} for topic in OVERLAY_TOPICS}},
        "Image!detection": {"imageMode": {"imageTopic": Topics.DETECTION_DEBUG_IMAGE.name}},
        "RawMessages!state": {"topicPath": f"{Topics.TASK_STATE.name}.data", "fontSize": 18},
        "RawMessages!approval": {"topicPath": f"{Topics.APPROVAL_REQUEST.name}.data"},
        "Publish!answer": _operator_publish("approve 1", "Send (edit the id: #<id> of the request)",
                                            "#7ed321", advanced=True),
        "RosOut!log": {"minLogLevel": 2},
    }
    configs.update({f"Publish!{word}": _operator_publish(word, word, colour, advanced=False) for word, colour in BUTTONS})
    return configs


def mosaic() -> Json:
    """How the panels are arranged (Foxglove's split tree)."""
    buttons = _split("row", _split("row", "Publish!pause", "Publish!stop", 50),
                     _split("row", "Publish!resume", "Publish!abort", 50), 50)
    operator = _split("column", "RawMessages!state",
                      _split("column", "RawMessages!approval",
                             _split("column", buttons, _split("column", "Publish!answer", "RosOut!log", 45), 15), 30),
                      12)
    cameras = _split("row", "Image!camera", "Image!detection", 50)
    return _split("row", _split("column", "3D!scene", cameras, 60), operator, 62)


def layout() -> Json:
    return {"configById": panel_configs(), "globalVariables": {}, "userNodes": {},
            "playbackConfig": {"speed": 1.0}, "layout": mosaic()}


def layout_text() -> str:
    return json.dumps(layout(), indent=2) + "\n"


def main() -> int:
    LAYOUT_FILE.parent.mkdir(parents=True, exist_ok=True)
    LAYOUT_FILE.write_text(layout_text())
    print(f"wrote {LAYOUT_FILE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
