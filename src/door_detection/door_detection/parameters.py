"""Parameters of the door detector (defaults mirrored in params/door_detector.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "door_detector"

DETECTOR_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml): whose head camera "
                  "the frames come from"),
    ParameterSpec("vote_frames", 10, "window of the vote: frames whose estimates are voted on "
                  "([Banerjee 2015] Sec. III-A: 10)", minimum=1, maximum=100),
    ParameterSpec("vote_min_agreeing", 2, "agreeing estimates (more than half of the window's) that "
                  "confirm a door before the window is full", unit="frames", minimum=1, maximum=100),
    ParameterSpec("vote_handle_confidence", 0.01, "largest 95 % confidence half-width of the confirmed "
                  "handle position; noisier estimates wait for more frames", unit="m", minimum=0.0001, maximum=0.1),
    ParameterSpec("vote_normal_confidence_deg", 1.0, "largest 95 % confidence half-width of the confirmed "
                  "door normal", unit="deg", minimum=0.01, maximum=10.0),
    ParameterSpec("door_width_min", 0.80, "narrowest door accepted", unit="m", minimum=0.3, maximum=2.0),
    ParameterSpec("door_width_max", 1.00, "widest door accepted", unit="m", minimum=0.3, maximum=2.5),
    ParameterSpec("nominal_door_width", 0.914, "door width assumed when only the handle is measured "
                  "(operator-aided mode)", unit="m", minimum=0.3, maximum=2.5),
    ParameterSpec("nominal_door_height", 2.083, "door height assumed for the corners", unit="m",
                  minimum=1.0, maximum=4.0),
    ParameterSpec("grasp_to_free_edge", 0.136, "handle grasp point to the leaf's free edge (backset + "
                  "lever grasp radius)", unit="m", minimum=0.0, maximum=0.5),
    ParameterSpec("scribble_timeout", 30.0, "a scribble is used for frames up to this old", unit="s",
                  minimum=0.1, maximum=600.0),
    ParameterSpec("sync_tolerance", 0.05, "largest stamp difference matched between colour, depth, "
                  "camera info and camera pose", unit="s", minimum=0.0, maximum=1.0),
    ParameterSpec("head_search", True, "while no door is confirmed, ask to pan and tilt the head "
                  "(/door_detector/look; door_detection.head_search)"),
    ParameterSpec("head_search_max_pan", 1.2, "largest pan of the head search", unit="rad", minimum=0.0,
                  maximum=3.14),
)
