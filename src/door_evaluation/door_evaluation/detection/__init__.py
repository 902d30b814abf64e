"""The door detector measured on the simulator and on real photographs ([Banerjee 2015] Sec. III, Table II).

* :mod:`~door_evaluation.detection.sim_scenes`: a rendered RGB-D frame of ``DoorWorld`` with
  its ground truth, the robot facing the door; :mod:`~door_evaluation.detection.trial_scenes`:
  randomised starts of the door task;
* :mod:`~door_evaluation.detection.search_trial`: the head search played on the sim core;
* ``python -m door_evaluation.detection.evaluate_sim`` (Table II with the head search,
  :mod:`~door_evaluation.detection.table_two`; ``--single-frame`` for single frames) and
  ``python -m door_evaluation.detection.benchmark`` (time per frame vs the paper);
* ``python -m door_evaluation.detection.evaluate_photos``: the 2-D stage
  (:mod:`door_detection.proposals`) on the real photographs of ``../shared/data``.

Results: ``src/door_detection/door_detection/RESULTS.md``.
"""
