"""Render the programs shown in docs/render.md and write their contact sheets.

    .venv/bin/python tools/render_docs.py [--out out/docs] [--width 320 --height 240]

Each program is rendered with all ground truth into OUT/<name>/ (video, depth,
segmentation, flow, poses); the sheet shows the last frame of every step.
"""

from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path

import homesim
from homesim.examples import load_example
from homesim.knowledge import real_programs
from homesim.render import contact_sheet, load_recording, render_program

DOCS = Path(__file__).resolve().parents[1] / "docs" / "render"

# (name, home, where the program comes from)
PROGRAMS = [
    ("scene1_watch_tv", "scene1", "example:watch_tv"),
    ("scene1_real_go_to_sleep", "scene1", "real:file875_1"),  # grab, put back, lie
    ("scene1_real_go_to_toilet", "scene1", "real:file323_2"),  # open, sit
    ("scene1_real_browse_internet", "scene1", "real:file169_2"),  # sit, grab, switch on
    ("scene3_glass_in_fridge", "scene3", "file:scene3_glass_in_fridge.txt"),  # grab, open, put
    ("scene3_watch_tv", "scene3", "file:scene3_watch_tv.txt"),
]


def load(source: str) -> homesim.Program:
    kind, _, name = source.partition(":")
    if kind == "example":
        return load_example(name)
    if kind == "real":
        return next(r.program for r in real_programs() if r.id == name)
    return homesim.parse_program((DOCS / name).read_text(encoding="utf-8"), source=name)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/docs")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--fps", type=int, default=15)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--only", default=None, help="render only this name")
    args = ap.parse_args()
    for name, home, source in PROGRAMS:
        if args.only and name != args.only:
            continue
        program = load(source)
        out = Path(args.out) / name
        shutil.rmtree(out, ignore_errors=True)
        # Real programs name scene1's nodes by id (as the reference simulator reads them).
        run = homesim.run_program(program, homesim.load_home(home), trace=True,
                                  reference=not program.is_grounded)
        result = render_program(run, out, width=args.width,
                                height=args.height, fps=args.fps, seed=args.seed)
        rec = load_recording(out)
        rgb = rec.rgb()
        frames = [(f"{s.index + 1}. {s.step}", rgb[s.end_frame]) for s in rec.steps]
        title = f"{program.title or name} - {home} ({source}), agent {result.agent}"
        sheet = contact_sheet(frames, DOCS / f"{name}.png", columns=4, title=title)
        print(f"{name}: {result.num_frames} frames in {result.seconds:.1f} s "
              f"({result.num_frames / result.seconds:.1f} frames/s) -> {sheet}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
