"""Evaluations, benchmarks, toy problems and sim scenes of the cores (issue #17: no core depends upward).

The cores (``door_detection`` and the others) import neither this package nor the simulator;
what measures them, on the simulator or alone, lives here, allowed to depend on
``door_sim_bridge`` and on the cores it measures.

* :mod:`door_evaluation.detection`: the door detector on the sim core ([Banerjee 2015]
  Table II with the head search, single frames, time per frame) and on real photographs.
* :mod:`door_evaluation.trajopt`: the trajectory optimiser's benchmarks (the backends on
  [Zucker 2013]'s problem, each door motion, the peer TrajOpt) and its toy problems.
* :mod:`door_evaluation.footsteps`: the footstep planner's benchmark over the full ranges.
* :mod:`door_evaluation.sim`: the simulation bridge's benchmark (real-time factor, camera rates).
"""
