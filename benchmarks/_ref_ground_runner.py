"""Run the VirtualHome reference's scene preparation and grounding (inside its side venv).

Executed by the side venv's interpreter (see reference.py); must not import homesim.
For each program of a JSON list (ungrounded step lines), on a fresh copy of one home's
graph, it runs the reference pipeline ``check_programs.check_one_program``: add the
missing objects, pick instances, execute (the random distractor objects of the original
pipeline are not placed). Prints one JSON object: per program, seconds and executable.

    python _ref_ground_runner.py DATASET_DIR GRAPH.json PROGRAMS.json SEED
"""

from __future__ import annotations

import copy
import importlib
import json
import random
import sys
import time
import types
from pathlib import Path

# check_programs imports two display helpers the side venv does not install.
sys.modules.setdefault("termcolor", types.SimpleNamespace(colored=lambda s, *a, **k: s))
sys.modules.setdefault("tqdm", types.SimpleNamespace(tqdm=lambda x, *a, **k: x))
sys.path.insert(0, str(Path(__file__).resolve().parent))

_ref_runner = importlib.import_module("_ref_runner")  # puts evolving_graph on the path

from evolving_graph import check_programs, utils  # noqa: E402
from evolving_graph.scripts import read_script_from_list_string  # noqa: E402


def main(argv: list[str]) -> None:
    dataset, graph_path, programs_path, seed = (Path(argv[0]), Path(argv[1]), Path(argv[2]),
                                                int(argv[3]))
    _ref_runner.patch_reference()
    resources = dataset / "resources"
    # The wheel ships without its resources folder; read the same files from eai-eval.
    for loader, name in (("load_name_equivalence", "class_name_equivalence.json"),
                         ("load_object_states", "object_states.json"),
                         ("load_object_placing", "object_script_placing.json"),
                         ("load_properties_data", "properties_data.json")):
        getattr(utils, loader).__defaults__ = (str(resources / name),)
    graph = json.loads(graph_path.read_text())
    programs = json.loads(programs_path.read_text())
    helper = utils.graph_dict_helper(max_nodes=check_programs.max_nodes)
    seconds, executable = [], []
    for lines in programs:
        random.seed(seed)
        g = copy.deepcopy(graph)  # not timed: the reference edits the dict in place
        t0 = time.perf_counter()
        try:
            script = read_script_from_list_string(lines)
            ok = check_programs.check_one_program(helper, script, [], g, w_graph_list=False,
                                                  place_other_objects=False)[1]
        except Exception:  # the reference raises on some programs: count as not executable
            ok = False
        seconds.append(time.perf_counter() - t0)
        executable.append(bool(ok))
    print(json.dumps({"seconds": seconds, "executable": executable}))


if __name__ == "__main__":
    main(sys.argv[1:])
