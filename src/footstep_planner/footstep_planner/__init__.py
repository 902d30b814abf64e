"""ROS-free core of the footstep planner: A* over footsteps to the door and through it.

Public API (everything in SI units, REP-103 axes, frame ``odom``):

* :class:`~footstep_planner.astar.FootstepPlanner` (``plan(start, goal) -> PlanResult``)
  and :func:`~footstep_planner.astar.plan_footsteps`;
* :class:`~footstep_planner.options.FootstepPlannerOptions`;
* :class:`~footstep_planner.door.DoorGeometry` and :class:`~footstep_planner.world.World`
  (``World.from_door``);
* :func:`~footstep_planner.goals.stand_pose_for_opening`,
  :func:`~footstep_planner.goals.through_door_pose`,
  :func:`~footstep_planner.goals.replan_needed`;
* values :class:`~footstep_planner.footstep.Footstep`, :class:`~footstep_planner.footstep.Stance`,
  :class:`~footstep_planner.footstep.Pose2D`; outcomes
  :class:`~footstep_planner.plan.PlanOutcome`, :class:`~footstep_planner.plan.PlanResult`,
  :class:`~footstep_planner.plan.FootstepPlan`; errors
  :class:`~footstep_planner.errors.FootstepPlannerError`.
"""
