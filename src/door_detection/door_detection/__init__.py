"""Door and handle detection for the humanoid door traversal ([Banerjee 2015] Sec. III).

ROS-free core (no rclpy); the node ``door_detector_node`` wraps it.  Public API:

* :func:`door_detection.automatic.detect_automatic` (rgb, depth, intrinsics, options,
  hinge_side) → :class:`~door_detection.estimate.DetectionResult` — Sec. III-A;
* :func:`door_detection.operator_aided.detect_from_scribble` (rgb, depth, intrinsics,
  scribble, options, hinge_side, up) → ``DetectionResult`` — Sec. III-B;
* :class:`door_detection.voting.Voter` — the N-frame vote;
* :class:`door_detection.detector.DoorDetector` — what the node does between messages: a
  decoded frame in, detection (automatic or after a scribble), vote, the estimate to publish;
* :class:`door_detection.estimate.DetectedDoor` (camera optical frame; ``handle_pose()``,
  ``transformed()``), :class:`~door_detection.estimate.DetectionOutcome`,
  :class:`~door_detection.options.DetectionOptions`.

The evaluations (Table II on the simulator, the benchmark, the 2-D stage on real photos) are
in ``door_evaluation.detection``: this package does not depend on the simulator.
Importing the package imports nothing heavy.
"""
