"""`homesim run`: execute a program on a home and show each step's outcome."""

from __future__ import annotations

import json
from typing import Annotated

import typer
from rich.markup import escape
from rich.table import Table

from homesim.cli.common import console, read_graph, read_program
from homesim.errors import GroundingError, HomesimError
from homesim.examples import DEMO_HOME, load_example
from homesim.ground.prepare import Prepared
from homesim.ground.search import Grounding, prepare_and_ground
from homesim.sim.execute import ExecutionResult, execute
from homesim.world.graph import EnvironmentGraph


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


def grounding_to_json(prepared: Prepared, grounding: Grounding) -> dict:
    """What preparation added and which instances grounding chose, for ``--json``."""
    return {
        "added": [{"node_id": a.node_id, "class_name": a.class_name,
                   "destination_id": a.destination_id, "relation": a.relation,
                   "room": a.room} for a in prepared.added],
        "states": [[n, sorted(a), sorted(b)] for n, a, b in prepared.states],
        "bindings": [{"object": f"<{name}> ({inst})", "node_id": node}
                     for (name, inst), node in grounding.bindings.items()],
        "standing": None if grounding.standing is None else
        {str(i): [round(x, 3), round(z, 3)] for i, (x, z) in grounding.standing.items()},
    }


def _show_grounding(g: EnvironmentGraph, prepared: Prepared, grounding: Grounding) -> None:
    def where(node: int) -> str:
        room = g.room_of(node)
        return "" if room is None or room == node else f" in {g.node(room).label()}"

    for a in prepared.added:
        dest = "the floor" if a.destination_id == a.room else g.node(a.destination_id).label()
        console.print(f"[cyan]added[/] {g.node(a.node_id).label()} {a.relation} {dest}"
                      f"{where(a.node_id)}")
    for node, before, after in prepared.states:
        gone = ",".join(sorted(before - after)) or "-"
        new = ",".join(sorted(after - before)) or "-"
        console.print(f"[cyan]initial state[/] {g.node(node).label()}: {gone} → {new}")
    chosen = ", ".join(f"<{name}> ({inst}) → {g.node(node).label()}{where(node)}"
                       for (name, inst), node in grounding.bindings.items())
    console.print(f"[cyan]grounded[/] {chosen}")
    if grounding.standing:
        spots = ", ".join(f"{i + 1}: ({x:.2f}, {z:.2f})"
                          for i, (x, z) in sorted(grounding.standing.items()))
        console.print(f"[cyan]agent stands at[/] (x, z per step) {spots}")


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
    seed: Annotated[int, typer.Option(
        help="Seed of scene preparation and grounding (ungrounded programs).")] = 0,
    no_ground: Annotated[bool, typer.Option(
        "--no-ground", help="Run an ungrounded program as is, reading (N) as node N, as "
                            "the reference simulator does.")] = False,
) -> None:
    """Execute a program step by step and show what each step did or why it failed.

    An ungrounded program (``<cup> (1)``, no node ids) is first prepared (objects the home
    lacks are added) and grounded (each object bound to an instance of the home).
    """
    prog = read_program(program) if program else load_example("watch_tv")
    g, gname = read_graph(graph, home, DEMO_HOME)
    if not prog.steps:
        raise HomesimError(f"{program or 'demo'}: the program has no steps")
    prepared = grounding = None
    if not prog.is_grounded and not no_ground:
        try:
            prepared, grounding = prepare_and_ground(prog, g, seed=seed)
        except GroundingError as e:
            if as_json:
                console.print_json(json.dumps({"program": str(prog), "executable": False,
                                               "grounding_error": str(e)}))
            else:
                console.print(f"[red]cannot ground[/] in {escape(gname)}: {escape(str(e))}")
            raise typer.Exit(1) from None
        g = prepared.graph
        prog = grounding.program
    result = execute(prog, g, trace=True)
    if as_json:
        data = result_to_json(result)
        if prepared is not None and grounding is not None:
            data["grounding"] = grounding_to_json(prepared, grounding)
        console.print_json(json.dumps(data))
        raise typer.Exit(0 if result.executable else 1)
    if prepared is not None and grounding is not None:
        _show_grounding(g, prepared, grounding)
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
        detail = rec.changes.describe(label, all_changes) if rec.ok \
            else f"[red]{escape(rec.reason or '')}[/]"
        table.add_row(str(rec.index + 1), mark, escape(str(rec.step)), detail)
    for index in range(result.steps_run + 1, len(prog.steps)):
        table.add_row(str(index + 1), "[dim]·[/]", f"[dim]{escape(str(prog.steps[index]))}[/]",
                      "[dim]not run[/]")
    console.print(table)
    if result.executable:
        console.print(f"[green]executable[/]: all {len(prog.steps)} steps ran")
    else:
        console.print(f"[red]not executable[/]: {escape(result.message)}")
        raise typer.Exit(1)
