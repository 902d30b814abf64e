"""Parameters of the door detector (defaults mirrored in params/door_detector.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "door_detector"

DETECTOR_PARAMETERS = (
    ParameterSpec("vote_frames", 10, "frames voted over before an estimate is published "
                  "(seed 001 Sec. III-A: 10)", minimum=1, maximum=100),
    ParameterSpec("door_width_min", 0.80, "narrowest door accepted", unit="m", minimum=0.3, maximum=2.0),
    ParameterSpec("door_width_max", 1.00, "widest door accepted", unit="m", minimum=0.3, maximum=2.5),
)
