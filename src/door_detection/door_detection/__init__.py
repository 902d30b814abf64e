"""Door and handle detection for the humanoid door traversal ([Banerjee 2015] Sec. III).

ROS-free core (no rclpy); the node ``door_detector_node`` wraps it.  Public API:

* :func:`door_detection.automatic.detect_automatic` (rgb, depth, intrinsics, options,
  hinge_side) → :class:`~door_detection.estimate.DetectionResult` — Sec. III-A;
* :func:`door_detection.operator_aided.detect_from_scribble` (rgb, depth, intrinsics,
  scribble, options, hinge_side, up) → ``DetectionResult`` — Sec. III-B;
* :class:`door_detection.voting.Voter` — the N-frame vote;
* :class:`door_detection.estimate.DetectedDoor` (camera optical frame; ``handle_pose()``,
  ``transformed()``), :class:`~door_detection.estimate.DetectionOutcome`,
  :class:`~door_detection.options.DetectionOptions`.

Scripts: ``python -m door_detection.evaluate_sim`` (Table II on the sim core),
``python -m door_detection.evaluate_photos`` (2-D stage on real photos),
``python -m door_detection.benchmark`` (time per frame vs the paper).
Importing the package imports nothing heavy.
"""
