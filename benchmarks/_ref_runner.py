"""Run the VirtualHome reference simulator on the real programs (inside its side venv).

This file is executed by the interpreter of the side venv that holds
``virtualhome==2.3.0`` (see reference.py); it must not import homesim. It prints one
JSON object on stdout.

    python _ref_runner.py DATASET_DIR time [--repeat N] [--unpatched]
    python _ref_runner.py DATASET_DIR dump OUT.jsonl [--unpatched]

Unless --unpatched, three known bugs of 2.3.0 are fixed in memory first:
JoinedExecutor.execute drops the modify/in_place arguments (TypeError on every Find that
has to walk), the character node is read from the initial graph instead of the current
state (stale SITTING/LYING after Sit/StandUp), and PutOffExecutor calls its check with
the wrong arguments (TypeError on every PutOff).
"""

from __future__ import annotations

import importlib.util
import json
import re
import sys
import time
from pathlib import Path

_spec = importlib.util.find_spec("virtualhome")
if _spec is None or not _spec.submodule_search_locations:
    sys.exit("virtualhome is not installed in this interpreter")
# The package __init__ fails to import; load evolving_graph from its folder instead.
sys.path.insert(0, str(Path(next(iter(_spec.submodule_search_locations))) / "simulation"))

from evolving_graph import environment as env  # noqa: E402
from evolving_graph import execution as ex  # noqa: E402
from evolving_graph import scripts as sc  # noqa: E402

_GROUNDED_ID = re.compile(r"\((\d+)\.(\d+)\)")


def patch_reference() -> None:
    """Fix the three crashing bugs of virtualhome 2.3.0 in memory."""

    def joined_execute(self, script, state, info, char_index, modify=True, in_place=False):
        for executor in self.executors:
            yield from executor.execute(script, state, info, char_index, modify, in_place)

    ex.JoinedExecutor.execute = joined_execute

    def current_character(state, char_index):
        node = next(state.get_char_node(char_index), None)
        return None if node is None else state.get_node(node.id)

    ex._get_character_node = current_character

    def check_putoff(self, state, node, info, char_index=0):
        char = current_character(state, char_index)
        worn = state.evaluate(env.ExistsRelation(env.NodeInstance(node), env.Relation.ON,
                                                 env.NodeInstanceFilter(char)))
        if not worn:
            info.error("{} is not on {}", node, char)
            return False
        if env.Property.CLOTHES not in node.properties:
            info.error("{} is not clothes", node)
            return False
        return True

    ex.PutOffExecutor.check_putoff = check_putoff


def load(dataset: Path):
    """(id, EnvironmentGraph, Script) for every program, ids sorted."""
    items = []
    for path in sorted((dataset / "programs").glob("*.txt")):
        lines = [_GROUNDED_ID.sub(r"(\2)", line.strip())
                 for line in path.read_text().splitlines() if line.strip().startswith("[")]
        graphs = json.loads((dataset / "graphs" / f"{path.stem}.json").read_text())
        items.append((path.stem, env.EnvironmentGraph(graphs["init_graph"]),
                      sc.read_script_from_list_string(lines)))
    return items


def run_one(graph, script, equivalences, w_graph_list):
    executor = ex.ScriptExecutor(graph, equivalences)
    try:
        ok, state, _ = executor.execute(script, w_graph_list=w_graph_list)
    except Exception as e:  # the unpatched reference crashes on many programs
        return "crash", f"{type(e).__name__}: {e}", None
    return ("ok" if ok else "fail"), executor.info.get_error_string(), state


def main(argv: list[str]) -> None:
    dataset, mode = Path(argv[0]), argv[1]
    if "--unpatched" not in argv:
        patch_reference()
    equivalences = json.loads((dataset / "resources" / "class_name_equivalence.json")
                              .read_text())
    items = load(dataset)
    if mode == "time":
        repeat = int(argv[argv.index("--repeat") + 1]) if "--repeat" in argv else 1
        out = {"programs": len(items)}
        for label, w_graph_list, reps in (("execute", False, repeat), ("graph_list", True, 1)):
            best = float("inf")
            for _ in range(reps):
                t0 = time.perf_counter()
                outcomes = [run_one(g, s, equivalences, w_graph_list)[0] for _, g, s in items]
                best = min(best, time.perf_counter() - t0)
            out[label] = {"seconds": best, "executable": outcomes.count("ok"),
                          "crashed": outcomes.count("crash")}
        print(json.dumps(out))
    elif mode == "dump":
        with open(argv[2], "w") as f:
            for pid, graph, script in items:
                status, message, state = run_one(graph, script, equivalences, False)
                record = {"id": pid, "status": status, "message": message}
                if state is not None and status == "ok":
                    d = state.to_dict()
                    record["states"] = sorted([n["id"], s] for n in d["nodes"]
                                              for s in n["states"])
                    record["edges"] = sorted([e["from_id"], e["relation_type"], e["to_id"]]
                                             for e in d["edges"])
                f.write(json.dumps(record) + "\n")
        print(json.dumps({"programs": len(items), "out": argv[2]}))
    else:
        sys.exit(f"unknown mode {mode!r}")


if __name__ == "__main__":
    main(sys.argv[1:])
