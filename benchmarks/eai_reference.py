"""EAI's own action-sequencing evaluator, per plan (run with the side venv's Python).

Usage: /tmp/eai/bin/python benchmarks/eai_reference.py PLANS.json OUT.json [--as-shipped]

Not part of homesim and never imported by it: `benchmarks/eai_agreement.py` runs it in a
side environment where ``eai-eval==1.0.5`` is installed. It follows the loop of
``virtualhome_eval/evaluation/action_sequencing/scripts/evaluate_results.py`` step by step,
calling EAI's functions, and records each plan's verdict (that script only keeps totals).
One change: plans equal to the gold program are executed and judged like any other (the
script counts them executable and never checks their goals); ``--as-shipped`` keeps the
script's shortcut (for timing it as shipped: such plans are not executed). A plan on which
EAI's code raises (a mixed-case key: KeyError in its arity check) is recorded with the
error ``crash: <exception>``. Beyond the verdict it records,
for a failed plan, the failing step, EAI's message, whether EAI's character was CLOSE to
itself then (`self_close`), and for a ``missing_step``, whether the failing step runs in
EAI's own simulator after some earlier prefix of the run (`runs_earlier`), which
`eai_agreement.py` uses to name EAI's faults.
"""

from __future__ import annotations

import copy
import json
import logging
import os.path as osp
import sys
import time
from pathlib import Path


def _load(path: str) -> object:
    return json.loads(Path(path).read_text())


def _runs_earlier(planner: object, history: list, action: object) -> bool:
    """Whether `action` runs in EAI's own simulator right after some proper prefix of the
    steps that ran (what EAI's wrong-order check means to find)."""
    for k in range(len(history)):
        planner.reset()
        for past in history[:k]:
            planner.my_execute_primitive_action_eval(past)
        if planner.my_execute_primitive_action_eval(action)[0]:
            return True
    return False


def main(plans_path: str, out_path: str, as_shipped: bool = False) -> None:
    logging.disable(logging.CRITICAL)
    import virtualhome_eval
    import virtualhome_eval.simulation.evolving_graph.utils as utils
    from virtualhome_eval.simulation.evolving_graph import eval_utils as eu

    root = osp.dirname(virtualhome_eval.__file__)
    resources = osp.join(root, "resources", "virtualhome")
    data_dir = osp.join(root, "dataset", "programs_processed_precond_nograb_morepreconds")
    tasks = _load(osp.join(resources, "task_state_LTL_formula_accurate.json"))
    tasks = tasks["scene_1"]
    id2task = _load(osp.join(resources, "id2task.json"))
    properties, placing, names = (utils.load_properties_data(), utils.load_object_placing(),
                                  utils.load_name_equivalence())
    kinds = {0: "wrong_order", 1: "missing_step", 2: "affordance", 4: "additional_step"}
    plans = _load(plans_path)
    out = []
    start = time.perf_counter()
    for plan in plans:
        pid = plan["identifier"]
        goals = tasks[id2task[pid]][pid]["vh_goal"]
        nodes = eu.remove_duplicate_dicts([g for g in goals["goal"] if "state" in g])
        edges = eu.remove_duplicate_dicts([g for g in goals["goal"] if "relation_type" in g])
        actions_goal = list(set(goals["actions"]))
        planner, _, gold_actions, _, _ = eu.construct_planner(
            names, properties, placing, scenegraph_id=1, script_id=pid, dataset_root=data_dir)
        *_, relevant = planner.get_symbolic_goal_nl(nodes, edges, action_goals=actions_goal)
        gold_ok = eu.scene_evaluate_wID(planner.final_state_dict, nodes, edges,
                                        planner.acting_char_id)[3]
        record = {"identifier": pid, "kind": plan.get("kind"), "gold_test": gold_ok,
                  "error": None, "executable": False, "success": False, "additional": 0}
        out.append(record)
        try:
            _judge(plan["llm_output"], record, planner, relevant, nodes, edges, actions_goal,
                   gold_actions if as_shipped else None, kinds)
        except Exception as e:  # EAI's own code failed on this plan
            record["error"] = f"crash: {type(e).__name__}"
    elapsed = time.perf_counter() - start
    Path(out_path).write_text(json.dumps({"seconds": elapsed, "plans": out}, indent=1))


def _judge(text: str, record: dict, planner: object, relevant: dict, nodes: list,
           edges: list, actions_goal: list, gold_actions: list | None, kinds: dict) -> None:
    """EAI's checks and execution of one plan, as its script does; fills `record`."""
    from virtualhome_eval.simulation.evolving_graph import eval_utils as eu
    from virtualhome_eval.simulation.evolving_graph.checker import TemporalOrderChecker

    if text.startswith("```json"):
        text = text[7:]
    text = text.strip().replace("\n", "").replace("'", '"')
    try:
        acts = eu.load_json_preserving_order(text)
    except Exception:
        acts = None
    if acts is None or len(acts) == 0 or not eu.check_name_id_format(acts)[0]:
        record["error"] = "format"
        return
    if not (eu.check_no_hallucination_in_action(acts)
            and eu.check_no_hallucination_in_arg(acts, relevant)):
        record["error"] = "hallucination"
        return
    if not eu.check_action_grammar(acts)[0]:
        record["error"] = "arity"
        return
    acts = eu.json_to_action(acts, relevant_name_to_id=relevant)
    if gold_actions is not None and acts == gold_actions:  # the script's shortcut
        record["executable"] = True
        return
    planner.reset()
    history, executable, failed = [], True, None
    states = [copy.deepcopy(planner.env_state.to_dict())]
    for step, action in enumerate(acts, start=1):
        ok, info = planner.my_execute_primitive_action_eval(action)
        if ok:
            history.append(action)
            states.append(copy.deepcopy(planner.env_state.to_dict()))
            continue
        code = TemporalOrderChecker(info, copy.deepcopy(states)).run_checker()
        code = code.get_error_type()
        if code == 4:
            record["additional"] += 1
            continue
        record["error"] = kinds.get(code, f"code {code}")
        record["failed_step"] = step
        record["message"] = " ".join(str(m) for m in info.messages)[:300]
        char = planner.acting_char_id
        record["self_close"] = any(
            e["from_id"] == e["to_id"] == char and e["relation_type"] == "CLOSE"
            for e in states[-1]["edges"])
        failed = action
        executable = False
        break
    if executable and record["additional"]:
        record["error"] = "additional_step"
    record["executable"] = executable
    record["success"] = bool(eu.scene_evaluate_wID(
        planner.env_state.to_dict(), nodes, edges, planner.acting_char_id,
        action_seq=history, action_goals=actions_goal)[3])
    if record["error"] == "missing_step":
        record["runs_earlier"] = _runs_earlier(planner, history, failed)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], "--as-shipped" in sys.argv[3:])
