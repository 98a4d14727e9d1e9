"""Differential test of homesim's plan scoring against EAI's own evaluator.

    python benchmarks/eai_agreement.py [--sample 60] [--seed 0] [--setup]

Plans: the gold program of every EAI-annotated program (342) and, for `--sample` of them,
six perturbations each (drop, swap, duplicate a step; wrong object; unknown object; wrong
arity), seeded. Both evaluators score the same plans; the script prints per-plan agreement
on task success and on the error kind, the disagreements by kind, and the time each took to
score the gold plans of all tasks (ratio in the same run; EAI's verdicts and time are
cached by the plans' hash under ``~/.cache/homesim/eai-reference``, ``--fresh`` measures
again).

EAI's evaluator runs in a side environment (``/tmp/eai``, or ``$EAI_VENV``) with PyPI
``eai-eval==1.0.5``; it is never a homesim dependency. Without it the script says so and
exits 0; ``--setup`` creates it (``python -m venv`` + ``pip install eai-eval==1.0.5``).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import random
import re
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from homesim.goals.contexts import TaskContext, load_contexts
from homesim.goals.plans import score_plans

HERE = Path(__file__).parent
VENV = Path(os.environ.get("EAI_VENV", "/tmp/eai"))
CACHE = Path.home() / ".cache" / "homesim" / "eai-reference"
PERTURBATIONS = ("drop", "swap", "duplicate", "wrong_object", "unknown_object", "wrong_arity")


def gold_pairs(context: TaskContext, program) -> list[tuple[str, list[str]]]:
    """The program's steps as EAI (action, [name, id, ...]) pairs."""
    return [(s.action.key, [x for r in s.args for x in (r.name, str(r.node_id))])
            for s in program.steps]


def to_text(pairs: list[tuple[str, list[str]]]) -> str:
    """EAI's output format: one JSON object, keys repeated in order."""
    return "{" + ", ".join(f"{json.dumps(a)}: {json.dumps(p)}" for a, p in pairs) + "}"


def perturb(pairs: list[tuple[str, list[str]]], how: str, context: TaskContext,
            rng: random.Random) -> list[tuple[str, list[str]]]:
    """One systematic perturbation of a plan."""
    out = [(a, list(p)) for a, p in pairs]
    with_args = [i for i, (_, p) in enumerate(out) if p]
    k = rng.randrange(len(out))
    if how == "drop" and len(out) > 1:
        del out[k]
    elif how == "swap" and len(out) > 1:
        k = min(k, len(out) - 2)
        out[k], out[k + 1] = out[k + 1], out[k]
    elif how == "duplicate":
        out.insert(k + 1, (out[k][0], list(out[k][1])))
    elif how in ("wrong_object", "unknown_object") and with_args:
        k = rng.choice(with_args)
        old = (out[k][1][0], int(out[k][1][1]))
        others = sorted(o for o in context.objects if o != old)
        name, node = rng.choice(others) if how == "wrong_object" and others else (
            "unicorn", 99999)
        out[k][1][0:2] = [name, str(node)]
    elif how == "wrong_arity" and with_args:
        k = rng.choice(with_args)
        out[k] = (out[k][0], out[k][1] + out[k][1][:2])
    return out


def build_plans(contexts: dict[str, TaskContext], sample: int, seed: int) -> list[dict]:
    """Gold plans for all, perturbed plans for `sample` programs (seeded)."""
    from homesim.knowledge.datasets import real_programs

    programs = {p.id: p.program for p in real_programs()}
    plans = []
    for pid, context in contexts.items():
        pairs = gold_pairs(context, programs[f"file{pid}"])
        plans.append({"identifier": pid, "kind": "gold", "llm_output": to_text(pairs)})
    rng = random.Random(seed)
    for pid in sorted(rng.sample(sorted(contexts), min(sample, len(contexts)))):
        pairs = gold_pairs(contexts[pid], programs[f"file{pid}"])
        for how in PERTURBATIONS:
            r = random.Random(f"{seed}-{pid}-{how}")
            plans.append({"identifier": pid, "kind": how,
                          "llm_output": to_text(perturb(pairs, how, contexts[pid], r))})
    return plans


def run_eai(plans_path: Path, out_path: Path, fresh: bool = False) -> dict:
    """EAI's verdicts, from the side environment (kept in `CACHE` by the plans' hash:
    EAI takes minutes; `fresh` runs it again)."""
    key = hashlib.sha256(plans_path.read_bytes() + (HERE / "eai_reference.py").read_bytes()
                         ).hexdigest()[:16]
    cached = CACHE / f"{key}.json"
    if cached.exists() and not fresh:
        return {**json.loads(cached.read_text()), "cached": str(cached)}
    env = {**os.environ, "PYTHONHASHSEED": "0"}  # EAI orders action goals by set()
    env.pop("PYTHONPATH", None)
    subprocess.run([str(VENV / "bin" / "python"), str(HERE / "eai_reference.py"),
                    str(plans_path), str(out_path)], check=True, env=env)
    CACHE.mkdir(parents=True, exist_ok=True)
    cached.write_text(out_path.read_text())
    return json.loads(out_path.read_text())


EAI_ONLY_ACTIONS = ("PLUGIN", "PLUGOUT", "RELEASE")  # run by EAI's simulator, refused by its
# hallucination check (not in its valid_actions table)


_NOT_OPEN = re.compile(r"\((\d+)\) is not open or is not openable")


def eai_bug(plan: dict, context: TaskContext, eai: dict) -> str | None:
    """Which documented fault of EAI's evaluator (docs/goals.md) touches this plan, if any
    (the first that applies, in the order of that list)."""
    text = plan["llm_output"]
    goals = context.goals.goals
    if not eai["gold_test"]:
        return "relation goals: at most one counts"
    if eai["error"] == "hallucination" and any(f'"{a}"' in text for a in EAI_ONLY_ACTIONS):
        return "PLUGIN/PLUGOUT/RELEASE refused"
    if ": []" in text:
        return "zero-argument steps dropped"
    if len(goals.actions) > 1:
        return "action-goal order from set()"
    if eai["error"] is not None and eai["error"].startswith("code"):
        return "failure without an error kind"
    return _eai_runtime_bug(context, eai)


def _eai_runtime_bug(context: TaskContext, eai: dict) -> str | None:
    """Faults of EAI's run-time error kinds, from what `eai_reference.py` recorded."""
    message = eai.get("message") or ""
    if eai["error"] == "missing_step" and eai.get("runs_earlier"):
        return "wrong order judged on the literal edge"
    if eai["error"] == "missing_step" and eai.get("self_close") and "is not close" in message:
        return "Grab: the character close to itself"
    closed = _NOT_OPEN.search(message)
    if eai["error"] == "affordance" and closed and int(closed[1]) in context.home and (
            "CAN_OPEN" in context.home.node(int(closed[1])).properties):
        return "closed container counted as affordance"
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sample", type=int, default=60)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--setup", action="store_true", help="create the side venv first")
    parser.add_argument("--report", type=Path, help="write per-plan disagreements here")
    parser.add_argument("--fresh", action="store_true",
                        help="run EAI again even when its verdicts on these plans are cached")
    args = parser.parse_args()
    if args.setup and not (VENV / "bin" / "python").exists():
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(VENV / "bin" / "pip"), "install", "-q", "eai-eval==1.0.5"],
                       check=True)
    if not (VENV / "bin" / "python").exists():
        print(f"skipped: no side environment with eai-eval at {VENV} (run with --setup)")
        return

    t0 = time.perf_counter()
    contexts = load_contexts(cache=False)  # parse and index the 342 homes
    cold_s = time.perf_counter() - t0
    load_contexts()  # writes the cache if it is missing
    t0 = time.perf_counter()
    contexts = load_contexts()
    load_s = time.perf_counter() - t0  # from the cache
    plans = build_plans(contexts, args.sample, args.seed)
    gold = [p for p in plans if p["kind"] == "gold"]
    t0 = time.perf_counter()
    score_plans(gold, contexts)
    gold_s = time.perf_counter() - t0
    ours = score_plans(plans, contexts).scores

    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "gold.json").write_text(json.dumps(gold))
        eai_gold = run_eai(Path(tmp) / "gold.json", Path(tmp) / "gold_out.json",
                           args.fresh)
        (Path(tmp) / "plans.json").write_text(json.dumps(plans[len(gold):]))
        eai_rest = run_eai(Path(tmp) / "plans.json", Path(tmp) / "out.json", args.fresh)
    theirs = eai_gold["plans"] + eai_rest["plans"]

    print(f"plans: {len(plans)} ({len(gold)} gold, {len(plans) - len(gold)} perturbed on "
          f"{args.sample} programs, seed {args.seed})")
    bugs = [eai_bug(p, contexts[p["identifier"]], e) for p, e in zip(plans, theirs, strict=True)]
    for scope, keep in (("all plans", lambda b: True),
                        ("untouched by EAI's faults", lambda b: b is None)):
        for kind in ("gold", "perturbed"):
            pairs = [(o, e) for p, o, e, b in zip(plans, ours, theirs, bugs, strict=True)
                     if keep(b) and (p["kind"] == "gold") == (kind == "gold")]
            succ = sum(o.success == e["success"] for o, e in pairs)
            err = sum(o.error == e["error"] for o, e in pairs)
            n = len(pairs) or 1
            print(f"{scope:26s} {kind:9s} n={len(pairs):4d}  success agree {succ:4d} "
                  f"({100 * succ / n:5.1f} %)  error kind agree {err:4d} ({100 * err / n:5.1f} %)")
    print("plans touched by EAI's faults:", dict(Counter(b for b in bugs if b)))
    diff: Counter = Counter()
    rows = []
    for p, o, e, b in zip(plans, ours, theirs, bugs, strict=True):
        if o.error != e["error"] or o.success != e["success"]:
            diff[(b or "-", p["kind"], o.error, e["error"], o.success, e["success"])] += 1
            rows.append({"plan": p, "eai_fault": b, "homesim": o.to_dict(), "eai": e})
    print("disagreements (EAI fault, plan kind, homesim error, EAI error, homesim success, "
          "EAI success): count")
    for key, count in diff.most_common():
        print(f"  {key}: {count}")
    eai_s = eai_gold["seconds"]
    for how, load in (("cached homes", load_s), ("homes parsed", cold_s)):
        total = load + gold_s
        print(f"homesim ({how}): load {load:.2f} s + score {gold_s:.2f} s = {total:.2f} s for "
              f"{len(gold)} gold plans; EAI: {eai_s:.2f} s; ratio EAI/homesim "
              f"{eai_s / total:.1f}x")
    if "cached" in eai_gold:
        print(f"  (EAI's time from its cached run {eai_gold['cached']}; --fresh measures again)")
    if args.report:
        args.report.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
