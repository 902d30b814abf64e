"""Parameters of the door detector (defaults mirrored in params/door_detector.yaml).

Parameters that are :class:`~door_detection.options.DetectionOptions` or
:class:`~door_detection.view_search.ViewSearchOptions` fields take their ranges from them
(their ``option_range``).
"""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange
from door_detection.options import option_range
from door_detection.view_search import option_range as view_range

__all__ = ["DETECTOR_PARAMETERS", "NODE_NAME"]

NODE_NAME = "door_detector"

DETECTOR_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml): whose head camera "
                  "the frames come from"),
    ParameterSpec("vote_frames", 10, "window of the vote: frames whose estimates are voted on "
                  "([Banerjee 2015] Sec. III-A: 10)", option_range("vote_frames")),
    ParameterSpec("vote_min_agreeing", 2, "agreeing estimates (more than half of the window's) that "
                  "confirm a door before the window is full", option_range("vote_min_agreeing")),
    ParameterSpec("vote_handle_confidence", 0.01, "largest 95 % confidence half-width of the confirmed "
                  "handle position; noisier estimates wait for more frames", option_range("vote_handle_confidence")),
    ParameterSpec("vote_normal_confidence_deg", 1.0, "largest 95 % confidence half-width of the confirmed "
                  "door normal", option_range("vote_normal_confidence_deg")),
    ParameterSpec("door_width_min", 0.80, "narrowest door accepted", option_range("door_width_min")),
    ParameterSpec("door_width_max", 1.00, "widest door accepted", option_range("door_width_max")),
    ParameterSpec("nominal_door_width", 0.914, "door width assumed when only the handle is measured "
                  "(operator-aided mode)", FieldRange(0.3, 2.5, "m")),
    ParameterSpec("nominal_door_height", 2.083, "door height assumed for the corners", FieldRange(1.0, 4.0, "m")),
    ParameterSpec("grasp_to_free_edge", 0.136, "handle grasp point to the leaf's free edge (backset + "
                  "lever grasp radius)", FieldRange(0.0, 0.5, "m")),
    ParameterSpec("scribble_timeout", 30.0, "a scribble is used for frames up to this old", FieldRange(0.1, 600.0, "s")),
    ParameterSpec("sync_tolerance", 0.05, "largest stamp difference matched between colour, depth, "
                  "camera info and camera pose", FieldRange(0.0, 1.0, "s")),
    ParameterSpec("head_search", True, "while no door is confirmed, ask to pan and tilt the head "
                  "(/door_detector/look; door_detection.head_search)"),
    ParameterSpec("head_search_max_pan", 1.2, "largest pan of the head search", view_range("max_pan")),
)
