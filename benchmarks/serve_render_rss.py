"""Peak memory and time of the largest render jobs ``/api/render`` accepts.

Runs the render worker (`homesim.serve.renders.run_job`, the code a job's process runs)
in a fresh process for requests right at `MAX_RENDER_PIXEL_FRAMES`: many small frames
and few large ones, plus the editor's usual request (watch TV, 5 frames of 320x240) as the
reference. Prints wall seconds, the worker's peak RSS (MiB), the PNG bytes written and the
ratio of each to the reference.

    nice python benchmarks/serve_render_rss.py
"""

from __future__ import annotations

import multiprocessing
import resource
import tempfile
import time
from pathlib import Path

from homesim.examples import DEMO_HOME, load_example
from homesim.limits import MAX_RENDER_PIXEL_FRAMES
from homesim.serve.programs import render_frames, render_plan
from homesim.serve.renders import run_job
from homesim.serve.schemas import RenderRequest


def steps_program(steps: int) -> str:
    """`steps` walks back and forth between the tv and the sofa of scene1."""
    pair = ["[Walk] <tv> (1.410)\n", "[Walk] <sofa> (1.352)\n"]
    return "".join(pair[i % 2] for i in range(steps))


def measure(request: RenderRequest) -> tuple[float, float, int]:
    """Seconds, peak RSS in MiB and PNG bytes of one job in its own process."""
    render_plan(request)  # the same check as the API: within the limits
    with tempfile.TemporaryDirectory() as out:
        worker = multiprocessing.get_context("spawn").Process(
            target=_job_with_rss, args=(request, out))
        t0 = time.perf_counter()
        worker.start()
        worker.join()
        seconds = time.perf_counter() - t0
        folder = Path(out)
        assert (folder / "done.json").is_file(), (folder / "error.json").read_text()
        png = sum(p.stat().st_size for p in folder.glob("*.png"))
        rss = float((folder / "rss").read_text())
    return seconds, rss, png


def _job_with_rss(request: RenderRequest, out: str) -> None:
    run_job(render_frames, request, out)
    peak_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    (Path(out) / "rss").write_text(str(peak_kib / 1024))


def main() -> None:
    cases = [("editor: 5 x 320x240", str(load_example("watch_tv")), 320, 240)]
    for width, height in [(320, 240), (1280, 960)]:
        steps = MAX_RENDER_PIXEL_FRAMES // (width * height)
        cases.append((f"limit: {steps} x {width}x{height}", steps_program(steps), width, height))
    rows = []
    for name, program, width, height in cases:
        request = RenderRequest(program=program, home=DEMO_HOME, width=width, height=height)
        rows.append((name, *measure(request)))
    ref = rows[0]
    print(f"render jobs at MAX_RENDER_PIXEL_FRAMES = {MAX_RENDER_PIXEL_FRAMES:,} "
          "(one worker process each)")
    print(f"{'request':<24} {'seconds':>8} {'peak RSS MiB':>13} {'PNG KiB':>8}  ratios to editor")
    for name, seconds, rss, png in rows:
        print(f"{name:<24} {seconds:8.1f} {rss:13.0f} {png / 1024:8.0f}  "
              f"time {seconds / ref[1]:.1f}x, RSS {rss / ref[2]:.2f}x")


if __name__ == "__main__":
    main()
