"""The paper's Table 3 for one data set: train the three models, score every row.

Rows: random sampling, random retrieval, nearest-neighbour retrieval, MLE, PG(LCS),
PG(LCS+Sim), and the two simulator-constrained decodings (of MLE and of PG(LCS+Sim)).
Everything is scored on the test split of `data.split` with the same seed.
"""

from __future__ import annotations

import copy
import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import ClassVar

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn.data import Splits, real_examples, split, synthetic_examples
from homesim.learn.eval import baselines
from homesim.learn.eval.scores import Scores, score
from homesim.learn.execution import executable
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import BestOnDev, TrainConfig, train_mle, train_pg
from homesim.program.model import Program

DATASETS = ("real", "synthetic")
MODELS = {"mle": "MLE", "pg_lcs": "PG (LCS)", "pg_lcs_sim": "PG (LCS+Sim)"}
"""Checkpoint name -> table row."""
ROWS = ("Random sampling", "Random retrieval", "NN retrieval (MiniLM)", "MLE", "PG (LCS)",
        "PG (LCS+Sim)", "MLE + constrained decoding", "PG (LCS+Sim) + constrained decoding")

Report = Callable[[str, int, int, float], None]
"""Progress callback: (stage, done, total, running loss or reward)."""


@dataclass
class RunConfig:
    """What `train_dataset` does; saved in every checkpoint's meta.

    Epochs and PG learning rate left at None take the data set's defaults. Each model keeps the
    weights of its best epoch on the dev split (`train.BestOnDev`).
    """

    dataset: str
    seed: int = 0
    synth_n: int = 5000
    mle_epochs: int | None = None
    pg_epochs: int | None = None
    batch_size: int = 32
    mle_lr: float = 2e-3
    pg_lr: float | None = None
    embeddings: str = "minilm"
    epochs_of: ClassVar[dict[str, tuple[int, int]]] = {"real": (40, 5), "synthetic": (10, 2)}
    """Default (MLE epochs, PG epochs per PG model) of each data set (others: 20, 5)."""
    pg_lr_of: ClassVar[dict[str, float]] = {"real": 1e-4, "synthetic": 5e-4}
    """Default policy-gradient learning rate (chosen on dev: 5e-4 lowered dev LCS on real;
    others: 5e-4)."""

    def __post_init__(self) -> None:
        mle, pg = self.epochs_of.get(self.dataset, (20, 5))
        self.mle_epochs = mle if self.mle_epochs is None else self.mle_epochs
        self.pg_epochs = pg if self.pg_epochs is None else self.pg_epochs
        if self.pg_lr is None:
            self.pg_lr = self.pg_lr_of.get(self.dataset, 5e-4)

    def mle_config(self) -> TrainConfig:
        """How the MLE model trains (defaults already filled in by `__post_init__`)."""
        assert self.mle_epochs is not None
        return TrainConfig(self.mle_epochs, self.batch_size, self.mle_lr, self.seed)

    def pg_config(self) -> TrainConfig:
        """How the policy-gradient models train from the MLE one."""
        assert self.pg_epochs is not None and self.pg_lr is not None
        return TrainConfig(self.pg_epochs, self.batch_size, self.pg_lr, self.seed)


def load_splits(dataset: str, seed: int, synth_n: int = 5000) -> Splits:
    """The data set's train/dev/test splits (synthetic programs are generated with `seed`)."""
    if dataset == "real":
        return split("real", real_examples(), seed)
    if dataset == "synthetic":
        return split("synthetic", synthetic_examples(synth_n, seed), seed)
    raise HomesimError(f"unknown data set {dataset!r}: choose from {', '.join(DATASETS)}")


def train_dataset(config: RunConfig, out_dir: Path, report: Report | None = None,
                  splits: Splits | None = None, device: str = "cpu") -> dict[str, Path]:
    """Train MLE, then PG(LCS) and PG(LCS+Sim) from it; save the three checkpoints."""
    splits = splits or load_splits(config.dataset, config.seed, config.synth_n)
    out_dir.mkdir(parents=True, exist_ok=True)

    def progress(stage: str) -> Callable[[int, int, float], None] | None:
        return None if report is None else (lambda d, t, v: report(stage, d, t, v))

    meta = {"task": "text2prog", "run": asdict(config)}
    start = time.perf_counter()
    mle = Text2Prog.create(splits.train, config.seed, embeddings=config.embeddings,
                           device=device)
    best = BestOnDev(mle, splits.dev)
    history = train_mle(mle, splits.train, config.mle_config(), progress("MLE"), best)
    best.restore()
    mle.meta.update(meta, model="mle", history=history, dev=best.scores,
                    best_epoch=best.epoch, seconds=time.perf_counter() - start)
    paths = {"mle": out_dir / "mle.pt"}
    mle.save(paths["mle"])
    for name, use_sim in (("pg_lcs", False), ("pg_lcs_sim", True)):
        start = time.perf_counter()
        model = copy.deepcopy(mle)
        pg = config.pg_config()
        best = BestOnDev(model, splits.dev, use_sim, pg.sim_weight)
        history = train_pg(model, splits.train, pg, use_sim, progress(MODELS[name]), best)
        best.restore()
        model.meta.update(meta, model=name, history=history, dev=best.scores,
                          best_epoch=best.epoch, seconds=time.perf_counter() - start)
        paths[name] = out_dir / f"{name}.pt"
        model.save(paths[name])
    return paths


def trained(run_dir: Path) -> bool:
    """Whether `run_dir` holds any checkpoint of `train_dataset`."""
    return any((run_dir / f"{name}.pt").is_file() for name in MODELS)


def _scored(preds: list[Program], test: list) -> Scores:
    flags = [executable(p, e) for p, e in zip(preds, test, strict=True)]
    return score(preds, [e.program for e in test], flags)


def evaluate_dataset(run_dir: Path, report: Report | None = None, device: str = "cpu"
                     ) -> dict:
    """Score every row on the test split of the data set trained in `run_dir`."""
    paths = {name: run_dir / f"{name}.pt" for name in MODELS}
    missing = [str(p) for p in paths.values() if not p.is_file()]
    if missing:
        raise HomesimError(f"{missing[0]}: checkpoint not found; run 'homesim learn train' "
                           "first")
    models = {name: Text2Prog.load(p, device) for name, p in paths.items()}
    run = models["mle"].meta.get("run", {})
    splits = load_splits(run.get("dataset", run_dir.name), run.get("seed", 0),
                         run.get("synth_n", 5000))
    train, test, seed = splits.train, splits.test, run.get("seed", 0)
    rows: dict[str, Scores] = {}
    seconds: dict[str, float] = {}
    jobs: list[tuple[str, Callable[[], list[Program]]]] = [
        ("Random sampling", lambda: baselines.random_sampling(train, test, seed)),
        ("Random retrieval", lambda: baselines.random_retrieval(train, test, seed)),
        ("NN retrieval (MiniLM)", lambda: baselines.nn_retrieval(train, test)),
        ("MLE", lambda: models["mle"].predict(test)),
        ("PG (LCS)", lambda: models["pg_lcs"].predict(test)),
        ("PG (LCS+Sim)", lambda: models["pg_lcs_sim"].predict(test)),
        ("MLE + constrained decoding", lambda: models["mle"].predict(test, constrained=True)),
        ("PG (LCS+Sim) + constrained decoding",
         lambda: models["pg_lcs_sim"].predict(test, constrained=True)),
    ]
    for done, (row, job) in enumerate(jobs):
        start = time.perf_counter()
        rows[row] = _scored(job(), test)
        seconds[row] = time.perf_counter() - start
        if report:
            report(splits.name, done + 1, len(jobs), rows[row].steps)
    return {"dataset": splits.name, "run": run, "n_train": len(train), "n_test": len(test),
            "train_seconds": {n: m.meta.get("seconds") for n, m in models.items()},
            "eval_seconds": seconds, "rows": {k: v.to_dict() for k, v in rows.items()}}


def write_json(result: dict, path: Path) -> None:
    """Write a result as JSON, atomically (`homesim.files`)."""
    write_text(path, json.dumps(result, indent=2) + "\n")
