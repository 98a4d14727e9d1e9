"""Goals: EAI goal formulas and goal sets, checked on execution traces; plan scoring."""

from homesim.goals.check import GoalReport, GoalSet, Trajectory, check_goals, holds
from homesim.goals.eai import TaskGoals, load_eai_goals
from homesim.goals.formula import Formula, parse_formula

__all__ = ["Formula", "GoalReport", "GoalSet", "TaskGoals", "Trajectory", "check_goals",
           "holds", "load_eai_goals", "parse_formula"]
