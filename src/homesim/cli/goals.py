"""`homesim goals check` and `homesim eval plans`: judge runs and plans against EAI goals."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.markup import escape
from rich.table import Table

from homesim.cli.common import console, read_graph, read_program
from homesim.errors import DataError, HomesimError
from homesim.files import check_target, read_text_limited, write_text
from homesim.limits import MAX_DATA_FILE_BYTES, MAX_PLAN_DEPTH, deeper_than
from homesim.world.graph import EnvironmentGraph

if TYPE_CHECKING:
    from homesim.goals.eai import TaskGoals

app = typer.Typer(help="Goals (EAI format) checked on execution traces.",
                  no_args_is_help=True)
eval_app = typer.Typer(help="Evaluate planners on EAI's VirtualHome tasks.",
                       no_args_is_help=True)


@app.command("check")
def check(
    program: Annotated[str, typer.Argument(help="Program file; '-' reads stdin.")],
    task: Annotated[str | None, typer.Option(
        help="EAI program id whose goals to check (27_2 or file27_2); its stored initial "
             "graph is the home unless --graph or --home is given.")] = None,
    formula: Annotated[str | None, typer.Option(
        help="A goal formula to check, e.g. 'ON(tv.410) then SITTING(character.65)'.")]
    = None,
    graph: Annotated[str | None, typer.Option(help="Environment graph JSON file.")] = None,
    home: Annotated[str | None, typer.Option(help="Built-in home.")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON.")] = False,
    strict_eai: Annotated[bool, typer.Option(
        "--strict-eai", help="Refuse formulas EAI refuses (an 'and' of state and temporal "
                             "goals).")] = False,
    with_repair: Annotated[bool, typer.Option(
        "--repair/--no-repair", help="Repair the program when it cannot run as written "
                                     "(default), as 'homesim run' does.")] = True,
) -> None:
    """Run a program and say which goals of a task (and which formula) its trace meets."""
    from homesim.goals import Trajectory, check_goals, holds, parse_formula
    from homesim.ground.pipeline import run_program

    if task is None and formula is None:
        raise HomesimError("goals check: give --task ID, --formula TEXT or both")
    prog = read_program(program)
    goals = _task_goals(task) if task is not None else None
    extra = parse_formula(formula, strict_eai) if formula is not None else None
    if graph is None and home is None and task is not None:
        env = _task_home(task)
    else:
        env, _ = read_graph(graph, home, "scene1")
    run = run_program(prog, env, trace=True, repair=with_repair)
    records = run.result.trace if run.result is not None and run.result.trace else []
    tr = Trajectory(run.graph, records)
    out: dict = {"run": run.message, "executable": run.executable,
                 "inserted": [f"{i.step}: {i.reason}" for i in run.insertions]}
    if goals is not None:
        report = check_goals(goals.goals, tr)
        out.update(task=goals.task, goals=report.to_dict(), formula=goals.text or None,
                   formula_holds=None if goals.formula is None else holds(goals.formula, tr))
    if extra is not None:
        out["given_formula"] = str(extra)
        out["given_formula_holds"] = holds(extra, tr)
    if as_json:
        console.print_json(json.dumps(out))
    else:
        _print_report(out)


def _task_key(task: str) -> str:
    return task if task.startswith("file") else f"file{task}"


def _task_goals(task: str) -> TaskGoals:
    """The EAI goals of program `task` (``27_2`` or ``file27_2``)."""
    from homesim.goals import load_eai_goals

    all_goals = load_eai_goals()
    key = _task_key(task)
    if key not in all_goals:
        raise DataError(f"--task {task}: no EAI goals for this program (ids look like "
                        "27_2; see resources/task_state_LTL_formula_accurate.json)")
    return all_goals[key]


def _task_home(task: str) -> EnvironmentGraph:
    """The stored initial graph of program `task`, the home its goals refer to."""
    from homesim.knowledge.datasets import real_programs

    key = _task_key(task)
    found = [p for p in real_programs() if p.id == key]
    if not found:
        raise DataError(f"--task {task}: the program is not in the fetched data set; "
                        "run 'homesim data fetch' or give --graph/--home")
    return found[0].graph()


def _print_report(out: dict) -> None:
    console.print(f"run: {escape(out['run'])}")
    if "task" in out:
        console.print(f"task: {escape(out['task'])}")
        for g in out["goals"]["met"]:
            console.print(f"  [green]met[/]   {escape(g)}")
        for g in out["goals"]["unmet"]:
            console.print(f"  [red]unmet[/] {escape(g)}")
        if out["formula_holds"] is not None:
            console.print(f"formula {_verdict(out['formula_holds'])}: {escape(out['formula'])}")
    if "given_formula" in out:
        console.print(f"formula {_verdict(out['given_formula_holds'])}: "
                      f"{escape(out['given_formula'])}")


def _verdict(ok: bool) -> str:
    return "[green]holds[/]" if ok else "[red]does not hold[/]"


@eval_app.command("plans")
def plans(
    path: Annotated[Path, typer.Argument(
        help="EAI action-sequencing outputs: a JSON list of {identifier, llm_output}.")],
    out: Annotated[Path | None, typer.Option(
        help="Write the per-plan report (JSON) here.")] = None,
    force: Annotated[bool, typer.Option(help="Replace --out if it exists.")] = False,
    strict_eai: Annotated[bool, typer.Option(
        "--strict-eai", help="EAI's verdicts where EAI is lenient or strict by choice: its "
                             "plan reader, its action table, a repeated step that fails is "
                             "not skipped, additional steps counted per step "
                             "(docs/goals.md).")] = False,
) -> None:
    """Score plans with EAI's metrics; print the table, write per-plan reasons."""
    from homesim.goals.contexts import load_contexts
    from homesim.goals.plans import score_plans

    if out is not None:
        check_target(out, force)
    records = _read_plans(path)
    ids = {str(r.get("identifier")) for r in records if isinstance(r, dict)}
    report = score_plans(records, load_contexts(ids), strict_eai=strict_eai)
    summary = report.summary()
    table = Table(title=f"{summary['plans']} plans")
    table.add_column("metric")
    table.add_column("%", justify="right")
    for group, values in (("goal", summary["goal_evaluation"]),
                          ("trajectory", summary["trajectory_evaluation"])):
        for name, value in _flat(values):
            table.add_row(f"{group} {name}", f"{value:.2f}")
    console.print(table)
    if out is not None:
        data = {"summary": summary, "plans": [s.to_dict() for s in report.scores]}
        write_text(out, json.dumps(data, indent=1), force=force)
        console.print(f"per-plan report: {escape(str(out))}")


def _read_plans(path: Path) -> list:
    """The records of a plan file; `DataError` naming the file when it is not a JSON list
    or nests deeper than `MAX_PLAN_DEPTH` (one plan's text is checked when it is scored)."""
    too_deep = DataError(f"{path}: nested deeper than {MAX_PLAN_DEPTH} levels "
                         "(MAX_PLAN_DEPTH); expected a JSON list of {identifier, llm_output}")
    try:
        records = json.loads(read_text_limited(path, MAX_DATA_FILE_BYTES,
                                               "MAX_DATA_FILE_BYTES", "plans"))
    except RecursionError:  # deeper than the parser goes
        raise too_deep from None
    except ValueError as e:
        raise DataError(f"{path}: cannot read plans ({e})") from None
    if deeper_than(records, MAX_PLAN_DEPTH):
        raise too_deep
    if not isinstance(records, list):
        raise DataError(f"{path}: expected a JSON list of {{identifier, llm_output}}")
    return records


def _flat(values: dict, prefix: str = "") -> list[tuple[str, float]]:
    rows = []
    for k, v in values.items():
        if isinstance(v, dict):
            rows += _flat(v, f"{prefix}{k} ")
        else:
            rows.append((prefix + k, v))
    return rows


@eval_app.command("titles")
def titles(
    predictions: Annotated[Path | None, typer.Option(
        help="JSON {program id: program text} answering the prompts; scored beside the "
             "baselines.")] = None,
    prompts_out: Annotated[Path | None, typer.Option(
        "--prompts-out", help="Write the test prompts ({id, prompt} per line) here.")] = None,
    baselines: Annotated[str, typer.Option(
        help="Comma-separated baselines to score (random_sampling, random_retrieval, "
             "nn_retrieval); '' for none.")] = "random_sampling,random_retrieval",
    seed: Annotated[int, typer.Option(help="Seed of the split and the baselines.")] = 0,
    force: Annotated[bool, typer.Option(help="Replace --prompts-out if it exists.")] = False,
) -> None:
    """Title -> program on the real data ("Task: Watch TV"): LCS and executability."""
    from homesim.learn.eval.titles import (
        baseline,
        evaluate,
        prompts,
        read_predictions,
        title_splits,
    )

    if prompts_out is not None:
        check_target(prompts_out, force)
    splits = title_splits(seed)
    if prompts_out is not None:
        lines = [json.dumps(p) for p in prompts(splits)]
        prompts_out.write_text("\n".join(lines) + "\n", encoding="utf-8")
        console.print(f"{len(lines)} prompts: {escape(str(prompts_out))}")
    rows = [(name, baseline(name, splits, seed)) for name in baselines.split(",") if name]
    if predictions is not None:
        rows.append((predictions.name, read_predictions(predictions, splits)))
    table = Table(title=f"title -> program: LCS and executability, {len(splits.test)} test "
                        f"programs (seed {seed})")
    for col in ("planner", "actions", "objects", "steps", "mean", "exec %"):
        table.add_column(col, justify="left" if col == "planner" else "right")
    for name, preds in rows:
        s = evaluate(preds, splits)
        table.add_row(escape(name), f"{s.action:.3f}", f"{s.objects:.3f}", f"{s.steps:.3f}",
                      f"{s.mean:.3f}", f"{s.simulator:.1f}")
    console.print(table)
