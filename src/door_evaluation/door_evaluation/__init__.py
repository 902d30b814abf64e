"""Evaluations, benchmarks and scenes on the simulator (issue #17: no core depends upward).

The cores (``door_detection`` and the others) do not import the simulator; what measures them
on it lives here, allowed to depend on ``door_sim_bridge`` and on the cores it measures.

* :mod:`door_evaluation.detection`: the door detector on the sim core ([Banerjee 2015]
  Table II with the head search, single frames, time per frame).
"""
