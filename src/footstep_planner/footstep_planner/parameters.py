"""Parameters of the footstep planner node (defaults mirrored in params/footstep_planner.yaml).

The search parameters are :class:`~footstep_planner.options.FootstepPlannerOptions` fields and
take their ranges from it (:func:`~footstep_planner.options.option_range`); the goal settings'
ranges are stated here only.
"""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange
from footstep_planner.options import option_range

__all__ = ["NODE_NAME", "PLANNER_PARAMETERS"]

NODE_NAME = "footstep_planner"

PLANNER_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml) giving step limits"),
    ParameterSpec("heuristic_weight", 3.0, "A* heuristic weight; 1 = A*, > 1 weighted A* (plan cost at most "
                  "w times the optimum; over the benchmark's approaches 3 costs 10 % more than 1.5 and plans "
                  "every approach and passage leg of the full ranges in <= 171 expansions, where 1.5 needed "
                  "up to 5,400)", option_range("heuristic_weight")),
    ParameterSpec("max_expansions", 20000, "the search's deterministic budget of A* node expansions (x2 per "
                  "repeat of a request)", option_range("max_expansions")),
    ParameterSpec("max_planning_time", 30.0, "wall-clock safety net only, far above normal use (plans take "
                  "milliseconds): the budget is max_expansions", option_range("max_planning_time")),
    ParameterSpec("stand_reach", 0.50, "base to door plane when opening a push door", FieldRange(0.2, 1.5, "m")),
    ParameterSpec("stand_reach_pull", 0.65, "base to door plane when opening a pull door (room to pull "
                  "the handle towards the robot)", FieldRange(0.2, 1.5, "m")),
    ParameterSpec("pull_sweep_angle", 0.45, "how far a pull door swings while pulled, kept clear of the "
                  "torso at the stand pose", FieldRange(0.05, 1.57, "rad")),
    ParameterSpec("pull_stand_beyond_latch", 0.05, "base past a pull door's latch edge along the wall "
                  "(one hand pulls, the other blocks the gap)", FieldRange(-0.5, 1.0, "m")),
    ParameterSpec("pull_sweep_half_depth", 0.15, "how far the torso reaches ahead of the base, kept out "
                  "of a pull door's swing (the arms are on the handle)", FieldRange(0.05, 0.5, "m")),
    ParameterSpec("stand_handle_offset", 0.20, "base to handle along the wall, towards the hinge",
                  FieldRange(-0.5, 0.8, "m")),
    ParameterSpec("handle_standoff", 0.06, "door face behind the handle grasp point", FieldRange(0.0, 0.3, "m")),
    ParameterSpec("beyond_door", 1.0, "goal distance past the door plane", FieldRange(0.3, 5.0, "m")),
    ParameterSpec("passage_door_angle", 1.57, "door angle assumed while passing: the body pushes the "
                  "leaf open ([Banerjee 2015] used a potential field for the swinging door)", FieldRange(0.0, 2.0, "rad")),
    ParameterSpec("push_passage", "sideways", "how a push door is passed: 'sideways' opens it standing "
                  "sideways beside the doorway, its back to the hinge, and side-steps through "
                  "(footstep_planner.push_passage); 'facing' opens it facing the door and walks through facing "
                  "the doorway, the body pushing the leaf (TALOS's shoulders wedge the leaf: 0/20 on the rig)",
                  choices=("sideways", "facing")),
    ParameterSpec("push_side_reach", 0.50, "sideways push: base to door plane when opening (at 0.45 the last "
                  "steps of the walk there swayed the door-side arm into the handle)", FieldRange(0.2, 1.5, "m")),
    ParameterSpec("push_stand_offset", 0.12, "sideways push: the stand pose and side-step line from the "
                  "opening's centre towards the latch (the leaf swings past the back)", FieldRange(-0.5, 0.5, "m")),
    ParameterSpec("push_side_beyond", 0.9, "sideways push: the side-step through ends this far past the door "
                  "plane", FieldRange(0.3, 3.0, "m")),
    ParameterSpec("push_step_away", 0.5, "sideways push: then the robot steps this far forward, away from the "
                  "hinge, out of the closing leaf's sweep (side-stepping on, the handle hooked the pelvis)",
                  FieldRange(0.0, 2.0, "m")),
    ParameterSpec("push_tuck_min_width", 0.90, "sideways push: a door at least this wide is walked through in "
                  "two parts, the pushing arm tucked in between (footstep_planner.push_passage; on the passage rig "
                  "doors of 0.91-0.95 m went 17/18 against 9/18 in one walk, narrower ones 10/12 against 12/12); "
                  "a narrower one in one walk", FieldRange(0.5, 2.0, "m")),
    ParameterSpec("push_tuck_at", -0.05, "sideways push: the doorway walk of a door that wide is the passage's "
                  "plan up to its first stance at most this far before the door plane (negative: past it) after "
                  "an even number of steps", FieldRange(-0.5, 0.5, "m")),
    ParameterSpec("pull_passage", "sideways", "how a blocked pull door is passed: 'sideways' side-steps "
                  "through facing the hinge, the blocking hand on the leaf until the arm tucks; 'facing' turns to "
                  "face the doorway (the hand leaves the leaf, which swings into the body: a study option)",
                  choices=("sideways", "facing")),
    ParameterSpec("pull_passage_shift", 0.0, "sideways pull passage: the side-step line from the opening's "
                  "centre towards the body's back (a study option: see footstep_planner.narrow.hold_leaf_line)",
                  FieldRange(0.0, 0.3, "m")),
    ParameterSpec("tuck_at", 0.45, "a pull door's doorway walk ends this far before the door plane, where the "
                  "blocking arm tucks (footstep_planner.pull_passage)", FieldRange(0.3, 1.0, "m")),
)
