"""The trajectory optimiser measured: its benchmarks, toy problems and peer comparison.

* :mod:`~door_evaluation.trajopt.toy_problems`: analytic door-opening problems shared by the
  tests and the backends' benchmark (a planar door arc, a [Zucker 2013]-sized problem);
* ``python -m door_evaluation.trajopt.benchmark_backends``: both backends (and scipy's SLSQP)
  on the [Zucker 2013]-sized problem;
* ``python -m door_evaluation.trajopt.benchmark_motions``: each door motion on TALOS, both
  backends ([Banerjee 2015]: 10.1–21 s per plan);
* ``python -m door_evaluation.trajopt.benchmark_peers``: the project's SQP and CHOMP beside
  tesseract's TrajOpt (:mod:`~door_evaluation.trajopt.tesseract_peer`, an optional extra) on
  the arm problems of :mod:`~door_evaluation.trajopt.peer_problems`.

The trajectory optimiser's node and core (``door_trajopt``) import none of these.
"""
