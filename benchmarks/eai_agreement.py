"""Differential test of homesim's plan scoring against EAI's own evaluator.

    python benchmarks/eai_agreement.py [--sample 60] [--seed 0] [--setup] [--golden FILE]

Plans: the gold program of every EAI-annotated program (342) and, for `--sample` of them,
a seeded perturbation of each kind in `PERTURBATIONS`: the systematic ones (drop, swap,
duplicate a step; wrong object; unknown object; wrong arity) and one for each difference
issue 41 found (U1: an unknown object after an arity error; U2: a trailing comma, a
missing ``}``; U3: a mixed-case key; U4: a key with a space; U5: PUT for PUTBACK; U6:
watching from another room; U7: a PUTBACK repeated; U8: washing a room; U9: typing on an
object that has no keys). Both evaluators score the same plans, homesim in its default
mode and with ``--strict-eai``; the script prints per-plan agreement on task success and
on the error kind for each mode, the disagreements by kind, and the time each took to
score the gold plans of all tasks (ratio in the same run; EAI's verdicts and time are
cached by the plans' hash under ``~/.cache/homesim/eai-reference``, ``--fresh`` measures
again). ``--golden FILE`` writes the plans with EAI's verdicts and the fault that explains
each plan EAI gets wrong: ``tests/goals/test_eai_agreement.py`` checks homesim against
that file without EAI.

EAI's evaluator runs in a side environment (``/tmp/eai``, or ``$EAI_VENV``) with PyPI
``eai-eval==1.0.5``; it is never a homesim dependency. Without it the script says so and
exits 0; ``--setup`` creates it (``python -m venv`` + ``pip install eai-eval==1.0.5``).
"""

from __future__ import annotations

import argparse
import gzip
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
PERTURBATIONS = ("drop", "swap", "duplicate", "wrong_object", "unknown_object", "wrong_arity",
                 "unknown_after_arity", "trailing_comma", "missing_brace", "mixed_case",
                 "spaced_key", "put_alias", "watch_elsewhere", "repeated_putback",
                 "wash_room", "type_object")
ROOMS = frozenset({"bathroom", "bedroom", "kitchen", "livingroom", "home_office",
                   "dining_room"})


def gold_pairs(context: TaskContext, program) -> list[tuple[str, list[str]]]:
    """The program's steps as EAI (action, [name, id, ...]) pairs."""
    return [(s.action.key, [x for r in s.args for x in (r.name, str(r.node_id))])
            for s in program.steps]


def to_text(pairs: list[tuple[str, list[str]]]) -> str:
    """EAI's output format: one JSON object, keys repeated in order."""
    return "{" + ", ".join(f"{json.dumps(a)}: {json.dumps(p)}" for a, p in pairs) + "}"


def perturb(pairs: list[tuple[str, list[str]]], how: str, context: TaskContext,
            rng: random.Random) -> str | None:
    """One perturbation of a plan, as plan text; None when it does not apply to the task."""
    if how in ("drop", "swap", "duplicate", "wrong_object", "unknown_object", "wrong_arity"):
        return to_text(_systematic(pairs, how, context, rng))
    text = to_text(pairs)
    if how == "trailing_comma":
        return text[:-1] + ",}"
    if how == "missing_brace":
        return text[:-1]
    out = [(a, list(p)) for a, p in pairs]
    k = rng.randrange(len(out))
    if how == "mixed_case":
        out[k] = (out[k][0].capitalize(), out[k][1])
    elif how == "spaced_key":
        out[k] = (out[k][0][:2] + " " + out[k][0][2:], out[k][1])
    elif how in ("put_alias", "repeated_putback"):
        puts = [i for i, (a, _) in enumerate(out) if a == "PUTBACK"]
        if not puts:
            return None
        i = rng.choice(puts)
        if how == "put_alias":
            out[i] = ("PUT", out[i][1])
        else:
            out.insert(i + 1, (out[i][0], list(out[i][1])))
    elif how == "unknown_after_arity":
        with_args = [i for i, (_, p) in enumerate(out) if p]
        if not with_args:
            return None
        i = rng.choice(with_args)
        out[i] = (out[i][0], out[i][1] + out[i][1][:2])
        out.insert(rng.randrange(i + 1, len(out) + 1), ("GRAB", ["unicorn", "99999"]))
    else:
        return _inserted(out, how, context, rng)
    return to_text(out)


_LOOKABLE = frozenset({"tv", "television", "computer", "laptop", "cpuscreen", "painting"})


def _inserted(out: list[tuple[str, list[str]]], how: str, context: TaskContext,
              rng: random.Random) -> str | None:
    """U6, U8, U9: a step on a task object inserted at a random place."""
    objects = sorted(context.objects)
    if how == "wash_room":
        rooms = [o for o in objects if o[0] in ROOMS]
        if not rooms:
            return None
        name, node = rng.choice(rooms)
        k = rng.randrange(len(out) + 1)
        out[k:k] = [("WALK", [name, str(node)]), ("WASH", [name, str(node)])]
        return to_text(out)
    if how == "watch_elsewhere":
        targets = [o for o in objects if o[0] in _LOOKABLE]
        step = "WATCH"
    else:  # type_object: a task object without keys or a switch
        home = context.home
        targets = [o for o in objects if o[0] not in ROOMS and o[0] != "character"
                   and o[0] != "keyboard" and "HAS_SWITCH" not in home.node(o[1]).properties]
        step = "TYPE"
    if not targets:
        return None
    name, node = rng.choice(targets)
    out.insert(0 if how == "watch_elsewhere" else rng.randrange(len(out) + 1),
               (step, [name, str(node)]))
    return to_text(out)


def _systematic(pairs: list[tuple[str, list[str]]], how: str, context: TaskContext,
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


ISSUE_PLANS = [
    # U1: an arity error (step 1) before an unknown object (step 2): hallucination first.
    ("60_1", "U1", '{"WALK": ["home_office", "319", "home_office", "319"], '
                   '"GRAB": ["unicorn", "99999"]}'),
    # U9: typing on a table, far from it and next to it.
    ("84_1", "U9", '{"TYPE": ["table", "355"]}'),
    ("84_1", "U9", '{"WALK": ["table", "355"], "TYPE": ["table", "355"]}'),
    # U8: washing the bedroom after walking there.
    ("1003_2", "U8", '{"WALK": ["bedroom", "67"], "WASH": ["bedroom", "67"]}'),
    # U6: watching the TV from another room.
    ("1049_1", "U6", '{"WATCH": ["television", "410"]}'),
    # U2, U3, U4, U5, U7 on 156_1 (drink; its goals touch none of EAI's faults): see
    # `_issue_variants`.
]
VARIANTS_TASK = "156_1"


def _issue_variants(pairs: list[tuple[str, list[str]]]) -> list[tuple[str, str]]:
    """U2 (trailing comma, missing brace), U3 (mixed-case key), U4 (a key with a space),
    U5 (PUT), U7 (a repeated PUTBACK), made from a gold plan."""
    text = to_text(pairs)
    first = pairs[0][0]
    put = next(i for i, (a, _) in enumerate(pairs) if a == "PUTBACK")
    return [("U2", text[:-1] + ",}"), ("U2", text[:-1]),
            ("U3", to_text([(first.capitalize(), pairs[0][1]), *pairs[1:]])),
            ("U4", to_text([(f"{first[:2]} {first[2:]}", pairs[0][1]), *pairs[1:]])),
            ("U5", to_text([*pairs[:put], ("PUT", pairs[put][1]), *pairs[put + 1:]])),
            ("U7", to_text([*pairs[:put + 1], pairs[put], *pairs[put + 1:]]))]


def issue_plans(contexts: dict[str, TaskContext]) -> list[dict]:
    """The plans of issue 41's differences (U1-U9), on the tasks it names where it names
    one."""
    from homesim.knowledge.datasets import real_programs

    gold = gold_pairs(contexts[VARIANTS_TASK], next(
        p.program for p in real_programs() if p.id == f"file{VARIANTS_TASK}"))
    plans = [{"identifier": pid, "kind": f"issue {u}", "llm_output": text}
             for pid, u, text in ISSUE_PLANS if pid in contexts]
    plans += [{"identifier": VARIANTS_TASK, "kind": f"issue {u}", "llm_output": text}
              for u, text in _issue_variants(gold)]
    return plans


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
            text = perturb(pairs, how, contexts[pid], r)
            if text is not None:
                plans.append({"identifier": pid, "kind": how, "llm_output": text})
    return plans


def run_eai(plans_path: Path, out_path: Path, fresh: bool = False, *flags: str) -> dict:
    """EAI's verdicts, from the side environment (kept in `CACHE` by the plans' hash:
    EAI takes minutes; `fresh` runs it again). `flags` go to `eai_reference.py`."""
    key = hashlib.sha256(plans_path.read_bytes() + (HERE / "eai_reference.py").read_bytes()
                         + " ".join(flags).encode()).hexdigest()[:16]
    cached = CACHE / f"{key}.json"
    if cached.exists() and not fresh:
        return {**json.loads(cached.read_text()), "cached": str(cached)}
    env = {**os.environ, "PYTHONHASHSEED": "0"}  # EAI orders action goals by set()
    env.pop("PYTHONPATH", None)
    subprocess.run([str(VENV / "bin" / "python"), str(HERE / "eai_reference.py"),
                    str(plans_path), str(out_path), *flags], check=True, env=env)
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
    if eai["error"] is not None and eai["error"].startswith("crash"):
        return "mixed-case key: EAI's arity check raises"
    if plan["kind"] in ("watch_elsewhere", "issue U6") and eai["error"] == "affordance":
        return "watching from another room counted as affordance"
    return _eai_runtime_bug(context, eai)


_EXECUTING = re.compile(r'executing "\[(\w+)\] <[^>]*> \((\d+)\)')


def _cannot(context: TaskContext, message: str) -> bool:
    """Whether the step EAI failed on (its message names it) is one whose object cannot
    take the action in homesim, wherever the character is (an affordance)."""
    from homesim.program.actions import lookup_action
    from homesim.sim import EFFECTS, FailureKind, SimState

    m = _EXECUTING.search(message)
    action = lookup_action(m[1]) if m else None
    if m is None or action is None or action.arity != 1 or int(m[2]) not in context.home:
        return False
    failure = EFFECTS[action.key](SimState(context.home), int(m[2]))
    return failure is not None and failure.kind is FailureKind.AFFORDANCE


def _eai_runtime_bug(context: TaskContext, eai: dict) -> str | None:
    """Faults of EAI's run-time error kinds, from what `eai_reference.py` recorded."""
    message = eai.get("message") or ""
    if eai["error"] == "missing_step" and eai.get("runs_earlier"):
        return "wrong order judged on the literal edge"
    if eai["error"] == "missing_step" and eai.get("self_close") and "is not close" in message:
        return "Grab: the character close to itself"
    if eai["error"] in ("missing_step", "wrong_order") and _cannot(context, message):
        return "reach checked before affordance"
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
    parser.add_argument("--golden", type=Path,
                        help="write the plans with EAI's verdicts and faults here (gzip JSON)")
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
    rest = plans[len(gold):]
    issue = issue_plans(contexts)
    plans += issue
    t0 = time.perf_counter()
    score_plans(gold, contexts)
    gold_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    score_plans(rest, contexts)
    rest_s = time.perf_counter() - t0
    ours = {mode: score_plans(plans, contexts, strict_eai=mode == "strict").scores
            for mode in ("default", "strict")}

    with tempfile.TemporaryDirectory() as tmp:
        def eai(name: str, items: list[dict], *flags: str) -> dict:
            (Path(tmp) / f"{name}.json").write_text(json.dumps(items))
            return run_eai(Path(tmp) / f"{name}.json", Path(tmp) / f"{name}_out.json",
                           args.fresh, *flags)

        eai_gold = eai("gold", gold)
        eai_shipped = eai("gold", gold, "--as-shipped")
        eai_rest = eai("plans", rest)
        eai_issue = eai("issue", issue)
    theirs = eai_gold["plans"] + eai_rest["plans"] + eai_issue["plans"]
    bugs = [eai_bug(p, contexts[p["identifier"]], e) for p, e in zip(plans, theirs, strict=True)]

    print(f"plans: {len(plans)} ({len(gold)} gold, {len(rest)} perturbed on {args.sample} "
          f"programs, seed {args.seed}, {len(issue)} of issue 41; kinds: "
          f"{dict(Counter(p['kind'] for p in rest))})")
    print("plans touched by EAI's faults:", dict(Counter(b for b in bugs if b)))
    for mode in ("default", "strict"):
        _agreement(mode, plans, ours[mode], theirs, bugs)
    for p, e, o, st in zip(plans[-len(issue):], eai_issue["plans"], ours["default"][-len(issue):],
                           ours["strict"][-len(issue):], strict=True):
        print(f"  {p['kind']} {p['identifier']}: EAI {e['error']} {e['success']}, homesim "
              f"{o.error} {o.success}, --strict-eai {st.error} {st.success}: "
              f"{p['llm_output'][:90]}")
    _speed(len(gold), len(rest), load_s, cold_s, gold_s, rest_s, eai_gold, eai_shipped, eai_rest)
    if args.report:
        rows = [{"plan": p, "eai_fault": b, "homesim": o.to_dict(),
                 "homesim_strict": s.to_dict(), "eai": e}
                for p, o, s, e, b in zip(plans, ours["default"], ours["strict"], theirs, bugs,
                                         strict=True)
                if (o.error, o.success) != (e["error"], e["success"])
                or (s.error, s.success) != (e["error"], e["success"])]
        args.report.write_text(json.dumps(rows, indent=1))
    if args.golden:
        rows = [{**p, "eai": {k: e[k] for k in ("error", "success", "executable")},
                 "eai_fault": b} for p, e, b in zip(plans, theirs, bugs, strict=True)]
        args.golden.write_bytes(gzip.compress(json.dumps(
            {"eai": "eai-eval 1.0.5", "seed": args.seed, "sample": args.sample,
             "plans": rows}, indent=0).encode(), mtime=0))
        print(f"golden verdicts: {args.golden}")


def _agreement(mode: str, plans: list[dict], ours: list, theirs: list[dict],
               bugs: list[str | None]) -> None:
    """Agreement of one homesim mode with EAI, and its disagreements by kind."""
    print(f"homesim {mode} mode:")
    for scope, keep in (("all plans", lambda b: True),
                        ("untouched by EAI's faults", lambda b: b is None)):
        for kind in ("gold", "perturbed"):
            pairs = [(o, e) for p, o, e, b in zip(plans, ours, theirs, bugs, strict=True)
                     if keep(b) and (p["kind"] == "gold") == (kind == "gold")]
            succ = sum(o.success == e["success"] for o, e in pairs)
            err = sum(o.error == e["error"] for o, e in pairs)
            n = len(pairs) or 1
            print(f"  {scope:26s} {kind:9s} n={len(pairs):4d}  success agree {succ:4d} "
                  f"({100 * succ / n:5.1f} %)  error kind agree {err:4d} ({100 * err / n:5.1f} %)")
    diff: Counter = Counter()
    for p, o, e, b in zip(plans, ours, theirs, bugs, strict=True):
        if o.error != e["error"] or o.success != e["success"]:
            diff[(b or "-", p["kind"], o.error, e["error"], o.success, e["success"])] += 1
    print("  disagreements (EAI fault, plan kind, homesim error, EAI error, homesim success, "
          "EAI success): count")
    for key, count in diff.most_common():
        print(f"    {key}: {count}")


def _speed(n_gold: int, n_rest: int, load_s: float, cold_s: float, gold_s: float,
           rest_s: float, eai_gold: dict, eai_shipped: dict, eai_rest: dict) -> None:
    """Both ratios of issue 41: against EAI's script as shipped (gold plans are counted,
    not executed) and against a loop that scores every plan."""
    for how, load in (("cached homes", load_s), ("homes parsed", cold_s)):
        total = load + gold_s
        print(f"gold plans ({n_gold}), homesim ({how}): load {load:.2f} s + score "
              f"{gold_s:.2f} s = {total:.2f} s; EAI scoring every plan {eai_gold['seconds']:.2f}"
              f" s (ratio {eai_gold['seconds'] / total:.1f}x); EAI's script as shipped "
              f"{eai_shipped['seconds']:.2f} s (ratio {eai_shipped['seconds'] / total:.1f}x)")
    total = load_s + rest_s
    print(f"perturbed plans ({n_rest}), homesim (cached homes): load {load_s:.2f} s + score "
          f"{rest_s:.2f} s = {total:.2f} s; EAI {eai_rest['seconds']:.2f} s (ratio "
          f"{eai_rest['seconds'] / total:.1f}x; its script as shipped is the same loop here)")
    for name, run in (("gold", eai_gold), ("as shipped", eai_shipped),
                      ("perturbed", eai_rest)):
        if "cached" in run:
            print(f"  (EAI's {name} time from its cached run {run['cached']}; --fresh "
                  "measures again)")


if __name__ == "__main__":
    main()
