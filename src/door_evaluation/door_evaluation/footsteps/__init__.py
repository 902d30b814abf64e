"""The footstep planner measured: its benchmark over the full ranges.

* :mod:`~door_evaluation.footsteps.benchmark_cases`: every approach to the stand pose from
  the full ranges and every leg of every push and pull passage, requested as the node does;
* ``python -m door_evaluation.footsteps.benchmark``: their planning times against the 50 ms
  target, in wall and CPU time.

The footstep planner's node and core (``footstep_planner``) import neither.
"""
