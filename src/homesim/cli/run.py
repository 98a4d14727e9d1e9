"""`homesim run`: execute a program on a home and show each step's outcome."""

from __future__ import annotations

import json
from typing import Annotated

import typer
from rich.table import Table

from homesim.cli.common import console, read_graph, read_program
from homesim.errors import HomesimError
from homesim.examples import DEMO_HOME, load_example
from homesim.sim.execute import ExecutionResult, execute
from homesim.sim.state import Changes
from homesim.world.vocab import CLOSE


def _describe(changes: Changes, label, all_changes: bool) -> str:
    parts = []
    for node, before, after in changes.states:
        gone = ",".join(sorted(before - after)) or "-"
        new = ",".join(sorted(after - before)) or "-"
        parts.append(f"{label(node)}: {gone} → {new}")
    for sign, edges in (("+", changes.added), ("-", changes.removed)):
        shown = [e for e in edges if all_changes or e[1] != CLOSE]
        parts += [f"{sign}{label(a)} {r} {label(b)}" for a, r, b in shown]
        hidden = len(edges) - len(shown)
        if hidden:
            parts.append(f"{sign}{hidden} CLOSE")
    parts += [f"added {label(n)}" for n in changes.nodes]
    return "; ".join(parts)


def result_to_json(result: ExecutionResult) -> dict:
    """A machine-readable summary of an execution (with its trace, if recorded)."""
    steps = []
    for rec in result.trace or []:
        steps.append({
            "index": rec.index,
            "step": str(rec.step),
            "nodes": list(rec.nodes),
            "ok": rec.ok,
            "reason": rec.reason,
            "changes": {
                "added": [list(e) for e in rec.changes.added],
                "removed": [list(e) for e in rec.changes.removed],
                "states": [[n, sorted(a), sorted(b)] for n, a, b in rec.changes.states],
                "nodes": list(rec.changes.nodes),
            },
        })
    return {
        "program": str(result.program),
        "executable": result.executable,
        "failed_step": result.failed_step,
        "reason": result.reason,
        "message": result.message,
        "steps": steps,
    }


def run(
    program: Annotated[str | None, typer.Argument(
        help="Program file (ActivityPrograms format or steps only); '-' reads stdin. "
             "Without it, runs the built-in demo.")] = None,
    graph: Annotated[str | None, typer.Option(help="Environment graph JSON file.")] = None,
    home: Annotated[str | None, typer.Option(
        help="Built-in home (see 'homesim homes'); default scene1.")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")]
    = False,
    all_changes: Annotated[bool, typer.Option(
        "--all-changes", help="List every CLOSE edge instead of counting them.")] = False,
) -> None:
    """Execute a program step by step and show what each step did or why it failed."""
    prog = read_program(program) if program else load_example("watch_tv")
    g, gname = read_graph(graph, home, DEMO_HOME)
    if not prog.steps:
        raise HomesimError(f"{program or 'demo'}: the program has no steps")
    result = execute(prog, g, trace=True)
    if as_json:
        console.print_json(json.dumps(result_to_json(result)))
        raise typer.Exit(0 if result.executable else 1)
    label = result.state.label
    title = prog.title or (program or "demo")
    table = Table(title=f"{title} — {gname} ({len(g)} nodes)", title_justify="left",
                  show_header=False, box=None, pad_edge=False)
    table.add_column(justify="right", style="dim")
    table.add_column()
    table.add_column()
    table.add_column(overflow="fold")
    for rec in result.trace or []:
        mark = "[green]✓[/]" if rec.ok else "[red]✗[/]"
        detail = (_describe(rec.changes, label, all_changes) or "no change") if rec.ok \
            else f"[red]{rec.reason}[/]"
        table.add_row(str(rec.index + 1), mark, str(rec.step), detail)
    for index in range(result.steps_run + 1, len(prog.steps)):
        table.add_row(str(index + 1), "[dim]·[/]", f"[dim]{prog.steps[index]}[/]",
                      "[dim]not run[/]")
    console.print(table)
    if result.executable:
        console.print(f"[green]executable[/]: all {len(prog.steps)} steps ran")
    else:
        console.print(f"[red]not executable[/]: {result.message}")
        raise typer.Exit(1)
