"""One run of the evaluation: a data set, a split and a seed; every row scored per example.

A run folder ``OUT/<data set>/<split>/seed<k>/`` holds the MLE checkpoint (``mle.pt``) and
the per-example scores of every row (``scores.json``); both are reused when present and
made with the same settings, so a table over many seeds can be built in pieces.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass
from pathlib import Path

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn.data import Example, Splits, real_examples, synthetic_examples
from homesim.learn.embeddings import preload_sentence_vectors
from homesim.learn.eval import baselines
from homesim.learn.eval.rules import parse
from homesim.learn.eval.scores import example_scores
from homesim.learn.eval.splits import SPLIT_VERSIONS, check_unlocked, make_split
from homesim.learn.eval.summary import gaps, summarize_rows
from homesim.learn.eval.titles import title_only
from homesim.learn.execution import cross_home_rate, executable
from homesim.learn.rerank.program_writer import FORMAT
from homesim.learn.rerank.reranker import CHOICE, Reranker
from homesim.learn.rerank.retrieve import RetrieveEdit
from homesim.learn.text.consensus import Consensus
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import BestOnDev, TrainConfig, train_mle
from homesim.learn.vocabularies import StepVocab
from homesim.program.model import Program

DATASETS = ("real", "synthetic", "synthetic-people")
"""The real programs; the synthetic ones with template text; the same synthetic programs
described by the paraphrase grammar (`homesim.synth.describe`)."""
MLE_DATASETS = ("real",)
"""Data sets the seq2seq rows are trained on (CPU budget: docs/learn.md)."""
RERANK_DATASETS = ("real", "synthetic-people")
"""Data sets the reranker row is scored on (on template text the rule parser is exact)."""
Report = Callable[[str, int, int, float], None]
"""Progress callback: (stage, done, total, running loss or score)."""


@dataclass(frozen=True)
class RunSpec:
    """What one run is: data, split, seed, and how its model trains."""

    dataset: str
    split: str
    seed: int
    synth_n: int = 5000
    mle_epochs: int = 12  # CPU budget: 10 models on a shared 2-core machine (docs/learn.md)
    batch_size: int = 32
    mle_lr: float = 4e-3
    embeddings: str = "minilm"

    def folder(self, out: Path) -> Path:
        return out / self.dataset / self.split / f"seed{self.seed}"

    def to_dict(self) -> dict:
        return {**asdict(self), "split_version": SPLIT_VERSIONS.get(self.split, 1)}

    def matches(self, stored: dict | None) -> bool:
        """Whether `stored` (a saved `to_dict`) describes this run, split definition included
        (saved before versions were: 1); the synthetic-set size does not matter for real data."""
        if not isinstance(stored, dict):
            return False
        stored, mine = {"split_version": 1, **stored}, self.to_dict()
        if self.dataset == "real":
            stored, mine = {**stored, "synth_n": None}, {**mine, "synth_n": None}
        return stored == mine


SYNTH_SEED = 0
"""The synthetic programs are one generated set (this seed); each run's seed splits them."""


def load_examples(dataset: str, synth_n: int = 5000) -> list[Example]:
    """The real programs, or `synth_n` synthetic ones generated with `SYNTH_SEED`."""
    if dataset == "real":
        return real_examples()
    if dataset == "synthetic":
        return synthetic_examples(synth_n, SYNTH_SEED)
    if dataset == "synthetic-people":
        return synthetic_examples(synth_n, SYNTH_SEED, style="people")
    raise HomesimError(f"unknown data set {dataset!r}: choose from {', '.join(DATASETS)}")


def load_run_splits(spec: RunSpec, vectors: Path, final: bool = False) -> Splits:
    """The train/dev/test examples of a run, after `preload_vectors` of its whole data set
    (cached in `vectors`); a locked seed only with `final` (`splits.check_unlocked`)."""
    check_unlocked(spec.seed, final)
    examples = load_examples(spec.dataset, spec.synth_n)
    preload_vectors(examples, vectors)
    return make_split(spec.split, examples, spec.seed, spec.dataset, final)


def mle_model(spec: RunSpec, splits: Splits, folder: Path, device: str = "cpu",
              report: Report | None = None) -> Text2Prog:
    """The run's MLE model: loaded from ``mle.pt`` when trained with this spec, else trained
    (keeping the best dev epoch) and saved."""
    path = folder / "mle.pt"
    if path.is_file():
        t2p = Text2Prog.load(path, device)
        if spec.matches(t2p.meta.get("spec")):
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


Job = tuple[str, Callable[[], list[Program]]]
"""A table row: its name and how to make its predictions on the test split."""


ORACLE_ROW = "Oracle retrieval (reads the truth)"


def baseline_jobs(splits: Splits, seed: int) -> list[Job]:
    """Rows that learn nothing, the ground truth and the empty program first, the oracle
    retrieval (the ceiling of returning a training program) last."""
    train, test = splits.train, splits.test
    return [
        ("Ground truth", lambda: [e.program for e in test]),
        ("Empty program", lambda: [Program(()) for _ in test]),
        ("Random sampling", lambda: baselines.random_sampling(train, test, seed)),
        ("Random retrieval", lambda: baselines.random_retrieval(train, test, seed)),
        ("Title-medoid", lambda: baselines.title_medoid(train, test)),
        ("Title-median", lambda: baselines.title_median(train, test)),
        ("NN (title)", lambda: baselines.nn_title(train, test)),
        ("NN (description)", lambda: baselines.nn_description(train, test)),
        (ORACLE_ROW, lambda: baselines.oracle_retrieval(train, test)),
    ]


HOLDOUT = {"stratified": "program", "leave-activities-out": "activity"}
"""Split -> what the reranker's training queries may not see of the rest of training
(`rerank.HOLDOUTS`), so that they are built the way the split builds its test set."""
RERANK_ROW = "Reranker (retrieve, substitute, rerank)"


def model_jobs(splits: Splits, seed: int, t2p: Text2Prog) -> list[Job]:
    """Rows that learn with the seq2seq model or beside it: greedy and constrained decoding,
    retrieve-and-edit, consensus."""
    test = splits.test
    fitted: dict[str, RetrieveEdit] = {}

    def retrieval() -> RetrieveEdit:
        if "model" not in fitted:
            fitted["model"] = RetrieveEdit.fit(splits.train, splits.dev)
        return fitted["model"]

    return list(zip(MLE_ROWS, (
        lambda: t2p.predict(test),
        lambda: t2p.predict(test, constrained=True),
        lambda: retrieval().predict(test),
        lambda: Consensus.fit(t2p, retrieval(), splits.dev, seed).predict(test)), strict=True))


MLE_ROWS = ("MLE (seq2seq)", "MLE + constrained decoding", "Retrieve-and-edit",
            "Consensus (MLE + retrieval)")
"""The rows of `model_jobs`, in order."""


def _not_scored(name: str) -> Callable[[], list[Program]]:
    def job() -> list[Program]:
        raise HomesimError(f"{name}: not scored, and no seq2seq model trained (--no-mle)")
    return job


TITLE_ROW = "Reranker, title only"
"""The reranker given each test program's title as its only text (`titles.title_only`)."""
TITLE_ONLY_ROWS = ("Title-medoid", "Title-median", "NN (title)", TITLE_ROW)
"""The rows that read only the title (the three baselines always do)."""
ROW_VERSIONS: dict[str, int | str] = {RERANK_ROW: f"{FORMAT}.{CHOICE}",
                                     TITLE_ROW: f"{FORMAT}.{CHOICE}"}
"""Row -> the version of its model; a cached row of another version is scored again (the
reranker's is the writer's model `FORMAT` and its choice's version, `reranker.CHOICE`; a
row not named here is version 1)."""


def rerank_jobs(splits: Splits, split_name: str) -> list[Job]:
    """The learned reranker (`rerank`), fitted once the way `split_name` hides test from
    train, given each test example's title and description, and given its title only."""
    fitted: dict[str, Reranker] = {}

    def model() -> Reranker:
        if "model" not in fitted:
            fitted["model"] = Reranker.fit(splits.train, HOLDOUT[split_name])
        return fitted["model"]

    return [(RERANK_ROW, lambda: model().predict(splits.test)),
            (TITLE_ROW, lambda: model().predict([title_only(e) for e in splits.test]))]


def rule_job(splits: Splits) -> Job:
    """The hand-written parser of the synthetic phrasings (an upper bound, `rules`)."""
    return ("Rule parser (upper bound)", lambda: [parse(e.description) for e in splits.test])


def score_rows(splits: Splits, jobs: list[Job], rows: dict[str, dict],
               save: Callable[[], None] | None = None, report: Report | None = None) -> None:
    """Per-example scores of every row not yet in `rows`, or there from another version of
    its model (`ROW_VERSIONS`): LCS, executes here and in the other homes, repetition;
    calling `save` after each row."""
    for done, (name, job) in enumerate(jobs):
        version = ROW_VERSIONS.get(name, 1)
        if name not in rows or rows[name].get("version", 1) != version:
            start = time.perf_counter()
            preds = job()
            predicted = time.perf_counter() - start
            rows[name] = {
                "examples": [example_scores(p, e.program, executable(p, e),
                                            cross_home_rate(p, e))
                             for p, e in zip(preds, splits.test, strict=True)],
                "predict_seconds": predicted, "seconds": time.perf_counter() - start,
                "version": version}
            if save:
                save()
        if report:
            report(splits.name, done + 1, len(jobs), 0.0)


def preload_vectors(examples: list[Example], cache: Path) -> None:
    """Embed every title, description and activity of the whole data set (`examples`, not
    one run's splits: those differ between seeds) in one go, cached on disk, so that the
    vectors depend neither on the seed nor on which runs came before."""
    preload_sentence_vectors([t for e in examples for t in (e.title, e.description, e.activity)],
                             cache)


def cached_run(spec: RunSpec, out: Path, final: bool = False) -> dict | None:
    """The scores a run already has (``scores.json`` for this spec), or None; a locked seed
    only with `final`."""
    check_unlocked(spec.seed, final)
    cache = spec.folder(out) / "scores.json"
    if not cache.is_file():
        return None
    data = json.loads(cache.read_text())
    return data if spec.matches(data.get("spec")) and data.get("rows") else None


def run(spec: RunSpec, out: Path, device: str = "cpu", with_model: bool = True,
        report: Report | None = None, final: bool = False, with_mle: bool = True) -> dict:
    """Score every row of one run (`with_model`: also the learned rows this data set gets,
    `MLE_DATASETS` and `RERANK_DATASETS`); rows already in ``scores.json`` for the same spec are
    kept (so baselines scored without the model are reused, and an interrupted run resumes).
    Without `with_mle` no seq2seq model is trained: its rows are those already scored, if any.
    A locked seed only with `final` (`splits.check_unlocked`).
    """
    check_unlocked(spec.seed, final)
    folder = spec.folder(out)
    cache = folder / "scores.json"
    rows: dict[str, dict] = {}
    if cache.is_file():
        old = json.loads(cache.read_text())
        if spec.matches(old.get("spec")):
            rows = old["rows"]
    splits = load_run_splits(spec, out / spec.dataset / "vectors.npz", final)
    mle = with_model and spec.dataset in MLE_DATASETS
    t2p = mle_model(spec, splits, folder, device, report) if mle and with_mle else None
    jobs = baseline_jobs(splits, spec.seed)
    if t2p is not None:
        jobs += model_jobs(splits, spec.seed, t2p)
    elif mle:  # not trained this time: the seq2seq rows already scored keep their place
        jobs += [(name, _not_scored(name)) for name in MLE_ROWS if name in rows]
    if with_model and spec.dataset in RERANK_DATASETS:
        jobs += rerank_jobs(splits, spec.split)
    if spec.dataset != "real":
        jobs.append(rule_job(splits))
    unseen = StepVocab.build(e.program for e in splits.train).unseen_share(
        e.program for e in splits.test)
    data = {"spec": spec.to_dict(), "n_train": len(splits.train), "n_dev": len(splits.dev),
            "n_test": len(splits.test), "test_ids": [e.id for e in splits.test],
            "unseen_step_share": unseen,
            "train_seconds": None if t2p is None else t2p.meta.get("seconds"), "rows": rows}

    def save() -> None:
        folder.mkdir(parents=True, exist_ok=True)
        write_text(cache, json.dumps(data) + "\n", force=True)

    score_rows(splits, jobs, rows, save, report)
    ordered = {name: rows[name] for name, _ in jobs}  # the table's order
    data["rows"] = {**ordered, **{k: v for k, v in rows.items() if k not in ordered}}
    save()
    return {**data, "rows": ordered}


def run_all(specs: list[RunSpec], out: Path, workers: int, device: str = "cpu",
            with_model: bool = True, final: bool = False, with_mle: bool = True,
            threads: int = 1) -> Iterator[RunSpec]:
    """Score every spec's run (`run`) in `workers` processes at once (spawned, torch at
    `threads` threads each), yielding each spec as its run is done; the scores land in
    each run's ``scores.json``, where `run` and `cached_run` read them. Each run is the
    same as alone. The data sets' sentence vectors must be cached already
    (`preload_vectors`), so that no two processes write them."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {pool.submit(_run_in_worker, spec, out, device, with_model, final, with_mle,
                               threads): spec for spec in specs}
        for future in as_completed(futures):
            future.result()
            yield futures[future]


def _run_in_worker(spec: RunSpec, out: Path, device: str, with_model: bool, final: bool,
                   with_mle: bool, threads: int) -> None:
    import os

    # scikit-learn's trees use every core through OpenMP unless told: beside other workers
    # on a loaded machine its threads wait on each other (set before OpenMP starts)
    os.environ["OMP_NUM_THREADS"] = str(threads)
    import torch

    torch.set_num_threads(threads)  # as the CLI sets its own process (`cli.learn._torch`)
    torch.use_deterministic_algorithms(True)
    run(spec, out, device, with_model, None, final, with_mle)


def block(runs: list[dict], beat: dict[str, tuple[str, ...]]) -> dict:
    """The summary of one data set and split over its runs (one per seed), with the gaps of
    each model row of `beat` to its baselines (row -> baselines)."""
    def mean(key: str) -> float:
        values = [r[key] for r in runs if r.get(key) is not None]
        return round(sum(values) / len(values), 1) if values else 0.0

    out = {"seeds": [r["spec"]["seed"] for r in runs], "rows": summarize_rows(runs),
           "sizes": {"train": mean("n_train"), "dev": mean("n_dev"), "test": mean("n_test"),
                     "unseen": sum(r["unseen_step_share"] for r in runs) / len(runs)},
           "gaps": {row: gaps(runs, row, baselines) for row, baselines in beat.items()
                    if any(row in r["rows"] for r in runs)}}
    return out
