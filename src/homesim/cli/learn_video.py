"""`homesim learn train/eval --task video2prog`: the paper's Table 2 (see docs/learn.md)."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import TYPE_CHECKING

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import write_text

if TYPE_CHECKING:
    from homesim.learn.video.table import VideoRunConfig


def train_video2prog(out: Path, config: VideoRunConfig, mle_epochs: int | None,
                     pg_epochs: int | None, force: bool, device: str) -> None:
    """Train the frame, clip and video -> program models into OUT; run again with the
    same options, it goes on where an earlier sitting stopped (`--force`: other options
    in the same folder)."""
    from homesim.learn.video.table import train_video

    for folder in config.data.split(","):
        if not Path(folder).is_dir():
            raise HomesimError(f"--data {folder}: with --task video2prog, name a plan folder "
                               "or data set folders written by 'homesim dataset generate' "
                               "(commas between several)")
    config.format  # noqa: B018 - a bad --frame-size fails here, before any work
    if mle_epochs is not None:
        config.mle_epochs = mle_epochs
    if pg_epochs is not None:
        config.pg_epochs = pg_epochs
    start = time.perf_counter()
    summary = train_video(config, out, device, report=lambda line: console.print(line),
                          force=force)
    console.print(f"[green]ok[/]: {out} ({summary['episodes']}) in "
                  f"{time.perf_counter() - start:.0f} s wall time")


def eval_video2prog(runs: Path, markdown: Path | None, device: str, machine: str) -> None:
    """Score Table 2, print it, write RUNS/results.json and the markdown section."""
    from homesim.learn.video.eval import evaluate_video
    from homesim.learn.video.report import table2_markdown, write_section

    result = evaluate_video(runs, device)
    result["runs"] = str(runs)
    write_text(runs / "results.json", json.dumps(result, indent=2) + "\n")
    section = table2_markdown(result, machine)
    console.print(section)
    if markdown is not None:
        write_section(markdown, section)
        console.print(f"[green]ok[/]: wrote the Table 2 section of {markdown}")
