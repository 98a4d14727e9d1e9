"""One run of the evaluation: a data set, a split and a seed; every row scored per example.

A run folder ``OUT/<data set>/<split>/seed<k>/`` holds the MLE checkpoint (``mle.pt``) and
the per-example scores of every row (``scores.json``); both are reused when present and
made with the same settings, so a table over many seeds can be built in pieces.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn import baselines
from homesim.learn.data import Example, Splits, real_examples, synthetic_examples
from homesim.learn.execution import cross_home_rate, executable
from homesim.learn.metrics import example_scores
from homesim.learn.splits import make_split
from homesim.learn.text2prog import Text2Prog
from homesim.learn.train import BestOnDev, TrainConfig, train_mle
from homesim.program.model import Program

DATASETS = ("real", "synthetic")
Report = Callable[[str, int, int, float], None]
"""Progress callback: (stage, done, total, running loss or score)."""


@dataclass(frozen=True)
class RunSpec:
    """What one run is: data, split, seed, and how its model trains."""

    dataset: str
    split: str
    seed: int
    synth_n: int = 5000
    mle_epochs: int = 25  # dev steps LCS plateaus by epoch ~16-20 on real data
    batch_size: int = 32
    mle_lr: float = 2e-3
    embeddings: str = "minilm"

    def folder(self, out: Path) -> Path:
        return out / self.dataset / self.split / f"seed{self.seed}"

    def to_dict(self) -> dict:
        return asdict(self)


def load_examples(dataset: str, seed: int = 0, synth_n: int = 5000) -> list[Example]:
    """The real programs, or `synth_n` synthetic ones generated with `seed`."""
    if dataset == "real":
        return real_examples()
    if dataset == "synthetic":
        return synthetic_examples(synth_n, seed)
    raise HomesimError(f"unknown data set {dataset!r}: choose from {', '.join(DATASETS)}")


def load_run_splits(spec: RunSpec) -> Splits:
    """The train/dev/test examples of a run."""
    examples = load_examples(spec.dataset, spec.seed, spec.synth_n)
    return make_split(spec.split, examples, spec.seed, spec.dataset)


def mle_model(spec: RunSpec, splits: Splits, folder: Path, device: str = "cpu",
              report: Report | None = None) -> Text2Prog:
    """The run's MLE model: loaded from ``mle.pt`` when trained with this spec, else trained
    (keeping the best dev epoch) and saved."""
    path = folder / "mle.pt"
    if path.is_file():
        t2p = Text2Prog.load(path, device)
        if t2p.meta.get("spec") == spec.to_dict():
            return t2p
    start = time.perf_counter()
    t2p = Text2Prog.create(splits.train, spec.seed, embeddings=spec.embeddings, device=device)
    best = BestOnDev(t2p, splits.dev)
    config = TrainConfig(spec.mle_epochs, spec.batch_size, spec.mle_lr, spec.seed)
    progress = None if report is None else (lambda d, t, v: report("MLE", d, t, v))
    history = train_mle(t2p, splits.train, config, progress, best)
    best.restore()
    t2p.meta.update(spec=spec.to_dict(), history=history, dev=best.scores,
                    best_epoch=best.epoch, seconds=time.perf_counter() - start)
    folder.mkdir(parents=True, exist_ok=True)
    t2p.save(path)
    return t2p


def row_jobs(splits: Splits, seed: int, t2p: Text2Prog | None
             ) -> list[tuple[str, Callable[[], list[Program]]]]:
    """(row name, predictions) of every row of the table, in order."""
    from homesim.learn.retrieve import RetrieveEdit

    train, test = splits.train, splits.test
    jobs: list[tuple[str, Callable[[], list[Program]]]] = [
        ("Ground truth", lambda: [e.program for e in test]),
        ("Empty program", lambda: [Program(()) for _ in test]),
        ("Random sampling", lambda: baselines.random_sampling(train, test, seed)),
        ("Random retrieval", lambda: baselines.random_retrieval(train, test, seed)),
        ("Title-medoid", lambda: baselines.title_medoid(train, test)),
        ("NN (title)", lambda: baselines.nn_title(train, test)),
        ("NN (description)", lambda: baselines.nn_description(train, test)),
    ]
    if t2p is not None:
        jobs += [("MLE (seq2seq)", lambda: t2p.predict(test)),
                 ("MLE + constrained decoding", lambda: t2p.predict(test, constrained=True))]
    jobs.append(("Retrieve-and-edit", lambda: RetrieveEdit.fit(train, splits.dev).predict(test)))
    return jobs


def score_rows(splits: Splits, jobs: list[tuple[str, Callable[[], list[Program]]]],
               report: Report | None = None) -> dict[str, dict]:
    """Per-example scores of every row: LCS, executable here and elsewhere, repetition."""
    rows: dict[str, dict] = {}
    for done, (name, job) in enumerate(jobs):
        start = time.perf_counter()
        preds = job()
        rows[name] = {
            "examples": [example_scores(p, e.program, executable(p, e), cross_home_rate(p, e))
                         for p, e in zip(preds, splits.test, strict=True)],
            "seconds": time.perf_counter() - start}
        if report:
            report(splits.name, done + 1, len(jobs), 0.0)
    return rows


def run(spec: RunSpec, out: Path, device: str = "cpu", with_model: bool = True,
        report: Report | None = None) -> dict:
    """Score every row of one run (cached in ``scores.json`` for the same spec)."""
    folder = spec.folder(out)
    cache = folder / "scores.json"
    if cache.is_file():
        data = json.loads(cache.read_text())
        if data.get("spec") == spec.to_dict() and data.get("with_model") == with_model:
            return data
    splits = load_run_splits(spec)
    t2p = mle_model(spec, splits, folder, device, report) if with_model else None
    unseen = None if t2p is None else t2p.steps.unseen_share(e.program for e in splits.test)
    data = {"spec": spec.to_dict(), "with_model": with_model,
            "n_train": len(splits.train), "n_dev": len(splits.dev), "n_test": len(splits.test),
            "test_ids": [e.id for e in splits.test], "unseen_step_share": unseen,
            "train_seconds": None if t2p is None else t2p.meta.get("seconds"),
            "rows": score_rows(splits, row_jobs(splits, spec.seed, t2p), report)}
    folder.mkdir(parents=True, exist_ok=True)
    write_text(cache, json.dumps(data) + "\n", force=True)
    return data
