"""Table 2 as markdown, kept in its own section of docs/results.md (between markers), so
the description -> program tables around it are left as they are."""

from __future__ import annotations

import json
from pathlib import Path

from homesim.files import write_text

START = "<!-- table2:start -->"
END = "<!-- table2:end -->"
PAPER_CLIPS = {"seen": (70.3, 23.8), "unseen-homes": (31.3, 11.5)}
"""The paper's TRN clip accuracy (action, steps) %, Table 2 left, by our test row."""
PAPER_PROGRAMS = {
    "seen": {"PG (LCS+Sim)": (".528", "24.6")},
    "unseen-homes": {"PG (LCS+Sim)": (".236", "20.9")},
    "all": {"MLE": (".341", ""), "PG (LCS)": (".364", ""), "PG (LCS+Sim)": (".358", "22.4")},
}
"""The paper's steps LCS and Simulator %, Table 2 right, by our test row and method."""
GENERATE_OPTIONS = ("n", "seed", "width", "height", "fps", "gt_stride", "shard_size",
                    "programs")


def generate_command(folder: str) -> str:
    """The `homesim dataset generate` command that made a data set or plan folder (from its
    dataset.json or plan.json), or a note when it has none."""
    root = Path(folder)
    plan = root / "plan.json"
    if plan.is_file():
        record = json.loads(plan.read_text(encoding="utf-8"))
        part = next(iter(record["parts"]))
        config = json.loads((root / part / "dataset.json").read_text(encoding="utf-8"))
        options = _options(config["config"], ("programs", "width", "height", "fps",
                                              "gt_stride", "shard_size"))
        name = record["plan"]["name"]
        return (f"nice -n 5 homesim dataset generate --plan {name} --n {record['n']} "
                f"--seed {record['seed']} {options} --out {folder}")
    try:
        config = json.loads((root / "dataset.json").read_text(encoding="utf-8"))["config"]
    except (OSError, ValueError, KeyError):
        return f"# {folder}: no dataset.json here"
    options = _options(config, GENERATE_OPTIONS)
    return (f"nice homesim dataset generate {options} --homes {','.join(config['homes'])} "
            f"--out {folder}")


def _options(config: dict, names: tuple[str, ...]) -> str:
    options = [f"--{k.replace('_', '-')} {config[k]}" for k in names if k in config]
    return " ".join([*options, f"--modalities {','.join(config['modalities'])}"])


def commands(result: dict) -> list[str]:
    """The commands that make the data, train and score this table."""
    cfg = result["train"]["config"]
    seeds = cfg["seeds"]
    runs = result.get("runs", "out/video")
    train = (f"nice homesim learn train --task video2prog --data {cfg['data']} --out {runs} "
             f"--seed {seeds[0]} --seeds {len(seeds)} --frame-size {cfg['frame_size']} "
             f"--frame-epochs {cfg['frame_epochs']} --seg-epochs {cfg['seg_epochs']} "
             f"--clip-epochs {cfg['clip_epochs']} --mle-epochs {cfg['mle_epochs']} "
             f"--pg-epochs {cfg['pg_epochs']} --batch-size {cfg['batch_size']}")
    return [*(generate_command(f) for f in cfg["data"].split(",")), train,
            f"nice homesim learn eval --task video2prog --runs {runs} "
            "--markdown docs/results.md"]


def _cell(s: dict, fmt: str) -> str:
    """mean ± sd (over seeds that differ) [bootstrap interval]."""
    text = format(s["mean"], fmt)
    if len(set(s["seeds"])) > 1:
        text += f" ± {format(s['sd'], fmt)}"
    return text + f" [{format(s['lo'], fmt)}, {format(s['hi'], fmt)}]"


def _clip_lines(result: dict) -> list[str]:
    lines = ["| Method | Test episodes | Clips | Action | Steps |", "|---|---|---:|---:|---:|"]
    for row, label in result["labels"].items():
        for method, s in result["clips"].get(row, {}).items():
            lines.append(f"| {method} | {label} | {s['n']} | {_cell(s['action'], '.1f')} | "
                         f"{_cell(s['step'], '.1f')} |")
        if row in PAPER_CLIPS and row in result["clips"]:
            paper = PAPER_CLIPS[row]
            lines.append(f"| *paper: TRN* | {label} | | *{paper[0]}* | *{paper[1]}* |")
    return lines


def _percent(s: dict) -> dict:
    """A summary of a share (0-1) as a percentage."""
    return {"mean": 100 * s["mean"], "sd": 100 * s["sd"], "lo": 100 * s["lo"],
            "hi": 100 * s["hi"], "seeds": [100 * x for x in s["seeds"]]}


def _program_lines(result: dict) -> list[str]:
    lines = ["| Method | Test episodes | Episodes | Action | Objects | Steps | Mean | "
             "Simulator % |", "|---|---|---:|---:|---:|---:|---:|---:|"]
    for row, label in result["labels"].items():
        for method, s in result["programs"].get(row, {}).items():
            cells = [_cell(s[m], ".3f") for m in ("action", "objects", "steps", "mean")]
            lines.append(f"| {method} | {label} | {s['n']} | {' | '.join(cells)} | "
                         f"{_cell(_percent(s['simulator']), '.1f')} |")
        for method, (steps, sim) in PAPER_PROGRAMS.get(row, {}).items():
            if row in result["programs"]:
                lines.append(f"| *paper: {method}* | {label} | | | | *{steps}* | | "
                             f"{f'*{sim}*' if sim else ''} |")
    return lines


def _segment_line(result: dict) -> str:
    scores = result["segment"]["scores"]
    parts = "; ".join(f"{part} {s['pixel_accuracy']:.1f} % / {s['miou']:.1f} % "
                      f"({s['classes']} classes)" for part, s in scores.items())
    return f"Segmentation network (pixel accuracy / mean IoU): {parts}."


def _pose_line(result: dict) -> str:
    """The pose network's scores (a run trained before it had one has none)."""
    if not result.get("pose"):
        return "Pose network: none in this run."
    parts = "; ".join(f"{part} {s['error_px']:.1f} px / {s['pck']:.1f} % / "
                      f"{s['visibility']:.1f} %" for part, s in result["pose"]["scores"].items())
    return ("Pose network (mean joint error in frame pixels / PCK within a fifth of the "
            f"body's height / visibility right): {parts}.")


def _times(train: dict) -> str:
    return ", ".join(f"{k} {v:.0f} s" for k, v in train["seconds"].items())


def table2_markdown(result: dict, machine: str) -> str:
    """The section: how it was made, both halves, wall times."""
    train = result["train"]
    cfg = train["config"]
    sizes = ", ".join(f"{k} ({train['roles'][k]}) {v} episodes / {train['clips'][k]} clips"
                      for k, v in train["episodes"].items())
    return "\n".join([
        START, "# Table 2: videos to programs", "",
        "Generated by `homesim learn eval --task video2prog`; regenerate with", "",
        *(f"    {c}" for c in commands(result)), "",
        f"Data: `{cfg['data']}`, {train['frames']} frames at {cfg['frame_size']}, "
        f"{cfg['fps']} frames/s; parts: {sizes}. Seeds "
        f"{', '.join(map(str, cfg['seeds']))}: each cell is the mean ± sample sd over "
        "seeds and [the 95 % bootstrap interval over test episodes]; the frame encoders "
        f"and the segmentation network are trained once (seed {cfg['backbone_seed']}). "
        "Every model keeps its best epoch on the validation part, which no test row "
        f"pools. Measured on: {machine}.", "",
        _segment_line(result), "", _pose_line(result), "",
        "## Left: step recognition in 2-second clips (mean per-class accuracy, %)", "",
        *_clip_lines(result), "",
        "## Right: whole videos to programs (LCS; Simulator % executes in the episode's "
        "home)", "",
        *_program_lines(result), "",
        f"Wall time: {_times(train)}; evaluation {result['eval_seconds']:.0f} s.", "",
        "See docs/learn.md (\"Videos to programs\") for the method and how these compare "
        "with the paper.", END, ""])


def with_table2(path: Path, text: str) -> str:
    """`text` followed by the Table 2 section `path` holds now, if any: the text task's
    writers replace the file but keep the video task's section."""
    old = path.read_text(encoding="utf-8") if path.is_file() else ""
    if START not in old or END not in old or START in text:
        return text
    section = START + old.split(START, 1)[1].split(END, 1)[0] + END + "\n"
    return text.rstrip("\n") + "\n\n" + section


def write_section(path: Path, section: str) -> None:
    """Replace the Table 2 section of `path` (or append it); the rest is kept."""
    text = path.read_text(encoding="utf-8") if path.is_file() else ""
    if START in text and END in text:
        head, rest = text.split(START, 1)
        tail = rest.split(END, 1)[1].lstrip("\n")
        text = head + section + tail
    else:
        text = text.rstrip("\n") + ("\n\n" if text else "") + section
    write_text(path, text, force=True)
