"""`homesim render`: animate a program in a home and record video with ground truth.

The recording is made in a temporary folder beside ``--out`` and moved into place once it
is complete (with its preview): Ctrl-C, SIGTERM or an error leave ``--out`` as it was, and
what a SIGKILL leaves (``.homesim-render-NAME-pPID-*``) is removed by the next render to
the same folder."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

from homesim.cli.common import console, demo_program, read_graph, read_program
from homesim.errors import HomesimError
from homesim.examples import DEMO_HOME
from homesim.files import temp_dir
from homesim.ground.pipeline import run_program


def _render_module():
    """Import homesim.render lazily: the CLI works without the 'render' extra."""
    try:
        import homesim.render as render
    except ImportError as e:
        raise HomesimError(f"rendering needs the 'render' extra: pip install "
                           f"'homesim[render]' (missing {e.name or e})") from None
    return render


def render(
    program: Annotated[str | None, typer.Argument(
        help="Program file: grounded (<tv> (1.410)) or not (<tv> (1)), which is then "
             "prepared and grounded in the home first; '-' reads stdin. Without it, "
             "renders the demo.")] = None,
    out: Annotated[Path, typer.Option(
        help="Output folder (must not hold a recording); it appears when the recording is "
             "complete.")] = Path("out/render"),
    home: Annotated[str | None, typer.Option(
        help="Built-in home with geometry (scene1..scene5); default scene1.")] = None,
    graph: Annotated[str | None, typer.Option(help="Environment graph JSON with 3D boxes.")]
    = None,
    seed: Annotated[int, typer.Option(help="Seed for cameras, agent and placements.")] = 0,
    width: Annotated[int, typer.Option(help="Image width, pixels (even).")] = 640,
    height: Annotated[int, typer.Option(help="Image height, pixels (even).")] = 480,
    fps: Annotated[int, typer.Option(help="Frames per second.")] = 30,
    agent: Annotated[str | None, typer.Option(
        help="male1, female1, male2 or female2 (default: chosen by the seed).")] = None,
    preview: Annotated[bool, typer.Option(
        help="Also write preview.png: a contact sheet of each step's last frame.")] = False,
    no_ground: Annotated[bool, typer.Option(
        "--no-ground", help="Render an ungrounded program as is, reading (N) as node N.")]
    = False,
    with_repair: Annotated[bool, typer.Option(
        "--repair/--no-repair", help="Insert the steps a program misses when it cannot run "
                                     "as written (default), or refuse it.")] = True,
) -> None:
    """Animate a program in 3D and record RGB video, depth, segmentation, flow and poses."""
    r = _render_module()
    check_out(out)
    g, gname = read_graph(graph, home, DEMO_HOME)
    prog = read_program(program) if program else demo_program(gname)
    # The program meets the simulator here, once: render animates this run's trace.
    ran = run_program(prog, g, seed=seed, reference=no_ground, repair=with_repair, trace=True)
    if ran.stage == "grounding":
        raise HomesimError(f"cannot ground the program in {gname}: {ran.message}")
    for ins in ran.insertions:
        console.print(f"inserted step {ins.index + 1} {ins.step}: {ins.reason}", markup=False)
    if ran.prepared is not None:
        added = ", ".join(ran.graph.node(a.node_id).label() for a in ran.prepared.added)
        console.print(f"grounded in {gname} (seed {seed})" + (f"; added {added}" if added else ""),
                      markup=False)
    bar = Progress(TextColumn("rendering"), BarColumn(), MofNCompleteColumn(),
                   TimeRemainingColumn(), console=console)
    task = None

    def progress(done: int, total: int) -> None:
        nonlocal task
        if task is None:  # start the bar with the first frame (errors come before it)
            bar.start()
            task = bar.add_task("frames", total=total)
        bar.update(task, completed=done, total=total)

    out.parent.mkdir(parents=True, exist_ok=True)
    with temp_dir(out.parent, f"render-{out.name}") as made:
        try:
            result = r.render_program(ran, made, width=width, height=height, fps=fps,
                                      seed=seed, progress=progress, agent=agent, home=gname)
        finally:
            if task is not None:
                bar.stop()
        if preview:
            rec = r.load_recording(made)  # streamed: only each step's last frame is kept
            rgb = rec.rgb_frames(s.end_frame for s in rec.steps)
            frames = [(f"{s.index + 1}. {s.step}", rgb[s.end_frame]) for s in rec.steps]
            r.contact_sheet(frames, made / "preview.png", columns=3, title=prog.title or None)
        move_into_place(made, out)
    console.print(f"[green]ok[/]: {result.num_frames} frames ({result.num_frames / fps:.1f} s "
                  f"of video) of {len(result.steps)} steps in {gname}, agent {result.agent}, "
                  f"written to {out} in {result.seconds:.1f} s "
                  f"({result.num_frames / result.seconds:.1f} frames/s)")
    if preview:
        console.print(f"preview: {out / 'preview.png'}")


RECORDING = ("meta.json", "video.mp4", "frames", "frames.npz", "preview.png")
"""What a recording folder holds (`homesim.render.groundtruth`), meta.json first."""


def check_out(out: Path) -> None:
    """Refuse, before any work, an --out that is a file or holds (part of) a recording."""
    if out.exists() and not out.is_dir():
        raise HomesimError(f"{out}: not a folder; give a folder for the recording")
    if out.is_dir() and any((out / name).exists() for name in RECORDING):
        raise HomesimError(f"{out}: already holds a recording; choose another folder")


def move_into_place(made: Path, out: Path) -> None:
    """Move the complete recording in `made` to `out`: the folder itself when `out` is
    missing or empty, else entry by entry with meta.json last (a reader takes a folder
    without meta.json for no recording)."""
    if out.is_dir() and not any(out.iterdir()):
        out.rmdir()
    if not out.exists():
        os.rename(made, out)
        return
    for name in reversed(RECORDING):
        if (made / name).exists():
            os.replace(made / name, out / name)
