"""The simulation bridge measured: its physics real-time factor and camera frame rates.

* ``python -m door_evaluation.sim.benchmark``: the physics (robot + door, 240 Hz, idle, arm
  moving, walking, and the other physics settings tried) against the 5× real-time target, and
  the head camera's frames per CPU second.

The sim bridge's node and core (``door_sim_bridge``) do not import it.
"""
