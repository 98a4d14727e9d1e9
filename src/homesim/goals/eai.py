"""Load the goal annotations of the Embodied Agent Interface (PyPI ``eai-eval==1.0.5``).

``resources/task_state_LTL_formula_accurate.json`` (fetched by ``homesim data fetch``) maps
``scene_1 -> task title -> program id ("27_2") -> {vh_goal, tl_goal}``; homesim names the
same program ``file27_2`` (`homesim.knowledge.datasets`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from homesim.errors import DataError, GoalError
from homesim.goals.check import GoalSet
from homesim.goals.formula import Formula, parse_formula
from homesim.knowledge.fetch import dataset_dir

GOALS_FILE = "resources/task_state_LTL_formula_accurate.json"
SCENE = "scene_1"


@dataclass(frozen=True)
class TaskGoals:
    """The goals of one annotated program.

    Attributes:
        program: homesim's program id (``file27_2``).
        task: the task title (``Wash clothes``).
        goals: the flat goals (`GoalSet`).
        formula: the temporal formula, or None where EAI has none.
        text: the formula as EAI wrote it ("" when none).
    """

    program: str
    task: str
    goals: GoalSet
    formula: Formula | None
    text: str


def eai_id(program: str) -> str:
    """``file27_2`` -> ``27_2`` (EAI's identifier)."""
    return program[4:] if program.startswith("file") else program


def load_eai_goals(directory: Path | None = None) -> dict[str, TaskGoals]:
    """Every annotated program's goals, keyed by homesim program id (``file27_2``)."""
    path = (directory or dataset_dir()) / GOALS_FILE
    if not path.is_file():
        raise DataError(f"{path}: EAI's goal annotations are not here; run 'homesim data fetch'")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))[SCENE]
    except (ValueError, KeyError, TypeError) as e:
        raise DataError(f"{path}: not EAI's goal file ({e})") from None
    out = {}
    for task, programs in data.items():
        for pid, entry in programs.items():
            where = f"{path.name}: {task} / {pid}"
            out[f"file{pid}"] = task_goals(entry, f"file{pid}", task, where)
    return out


def task_goals(entry: object, program: str, task: str, where: str) -> TaskGoals:
    """One ``{vh_goal, tl_goal}`` entry as `TaskGoals`; `GoalError` naming `where` if bad."""
    if not isinstance(entry, dict) or not isinstance(entry.get("vh_goal"), dict):
        raise GoalError(f"{where}: expected an object with 'vh_goal' and 'tl_goal'")
    vh = entry["vh_goal"]
    states, relations = [], []
    for k, goal in enumerate(vh.get("goal", [])):
        if not isinstance(goal, dict):
            raise GoalError(f"{where}: goal {k + 1} is not an object")
        if {"id", "class_name", "state"} <= goal.keys():
            item = (_int(goal["id"], where), str(goal["class_name"]), str(goal["state"]))
            if item not in states:  # EAI drops duplicates too
                states.append(item)
        elif {"from_id", "relation_type", "to_id"} <= goal.keys():
            item2 = (_int(goal["from_id"], where), str(goal["relation_type"]),
                     _int(goal["to_id"], where))
            if item2 not in relations:
                relations.append(item2)
        else:
            raise GoalError(f"{where}: goal {k + 1} is neither a state goal (id, class_name, "
                            "state) nor a relation goal (from_id, relation_type, to_id)")
    actions = tuple(tuple(str(a).split("|")) for a in dict.fromkeys(vh.get("actions", [])))
    text = entry.get("tl_goal") or ""
    try:
        formula = parse_formula(text) if text else None
    except GoalError as e:
        raise GoalError(f"{where}: {e}", e.column) from None
    return TaskGoals(program, task, GoalSet(tuple(states), tuple(relations), actions),
                     formula, text)


def _int(value: object, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise GoalError(f"{where}: node id {value!r} is not an integer")
    return value
