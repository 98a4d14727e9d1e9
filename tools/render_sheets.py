"""Contact sheets of the look programs (docs/render/programs/*.txt) in several homes.

    python tools/render_sheets.py --tag after [--homes scene1 scene4 scene5]
                                  [--width 640 --height 480 --seed 0 --only watch_tv]

Each program is prepared and grounded in each home (`homesim.run_program`, the same seed),
animated, and the key frame of every step (`render_keyframes`: a hands-on step at its
effect from its close-up, any other at its end from the camera that sees the agent best)
is drawn at WIDTH x HEIGHT. The sheet goes to
``docs/render/sheets/<home>_<program>_<tag>.jpg``. ``--tag before`` run with
``PYTHONPATH`` on another checkout's ``src`` makes the "before" sheets of that code (this
tool uses only the public API).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

from PIL import Image

import homesim
from homesim.errors import HomesimError
from homesim.ground.pipeline import run_program
from homesim.render import contact_sheet, render_keyframes

DOCS = Path(__file__).resolve().parents[1] / "docs" / "render"
PROGRAMS = ["watch_tv", "make_coffee", "glass_in_fridge", "read_book_in_bed", "brush_teeth",
            "wash_dishes"]
HOMES = ["scene1", "scene4", "scene5"]


def sheet(name: str, home: str, tag: str, args: argparse.Namespace) -> Path:
    """Render one program's key frames in one home and write its sheet."""
    text = (DOCS / "programs" / f"{name}.txt").read_text(encoding="utf-8")
    program = homesim.parse_program(text, source=name)
    ran = run_program(program, homesim.load_home(home), seed=args.seed, trace=True)
    if ran.grounding is None or ran.graph is None:
        raise HomesimError(f"cannot ground it: {ran.message}")
    grounded = ran.grounding.program
    frames = render_keyframes(ran, width=args.width, height=args.height, seed=args.seed)
    labelled = [(f"{i + 1}. {grounded.steps[i]}", rgb) for i, rgb in frames]
    title = f"{program.title} - {home}, seed {args.seed} ({tag})"
    out = DOCS / "sheets" / f"{home}_{name}_{tag}.jpg"
    with tempfile.TemporaryDirectory() as tmp:
        png = contact_sheet(labelled, Path(tmp) / "sheet.png", columns=4, title=title)
        out.parent.mkdir(parents=True, exist_ok=True)
        Image.open(png).convert("RGB").save(out, format="JPEG", quality=82, optimize=True)
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tag", default="after", help="suffix of the sheet names")
    ap.add_argument("--homes", nargs="+", default=HOMES)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--only", default=None, help="only this program")
    args = ap.parse_args()
    failed = 0
    for home in args.homes:
        for name in PROGRAMS:
            if args.only and name != args.only:
                continue
            t0 = time.perf_counter()
            try:
                out = sheet(name, home, args.tag, args)
            except HomesimError as e:  # one program that cannot be shown: say so, go on
                failed += 1
                print(f"{home} {name}: FAILED: {e}", flush=True)
                continue
            print(f"{home} {name}: {time.perf_counter() - t0:.1f} s -> {out}", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
