"""Probe (not kept): a cross-encoder reading the description and a candidate program together,
as the reranker's 23rd feature; measured by cross-validation and dev only (docs/learn.md,
"Tried for the reranker and not kept").

    python tools/cross_encoder_probe.py export --out .ce             # here: candidates, labels
    python3 .ce/cross_encoder_probe.py train .ce stratified-0 ...    # on a GPU (CPU: hours)
    python tools/cross_encoder_probe.py evaluate --data .ce --scores DIR

`export` writes, per stratified seed, every query's candidates as text with their steps LCS
(`SEED.jsonl.gz`) and the reranker's features (`SEED-features.npz`), plus all-MiniLM-L6-v2
with its weights rounded to float16 (the device takes 64 MiB) and this file. `train` fits,
per seed, one cross-encoder per cross-validation fold of the training queries (scoring that
fold) and one on all of them (scoring dev and test); it imports only torch and
transformers. `evaluate` prints cross-validated and dev top-candidate LCS of the trees with
and without the score, and of the score alone.
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import re
import shutil
import sys
import time
from pathlib import Path

import numpy as np

FOLDS = 5
EPOCHS, QUERIES_PER_STEP, CANDIDATES_PER_QUERY = 4, 8, 16
TAU, LEARNING_RATE, MAX_TOKENS = 0.05, 3e-5, 192
"""Listwise loss: cross-entropy to softmax(LCS / TAU) over a query's sampled candidates."""


def program_text(program) -> str:
    """'walk living room, switchon television, ...' from a program's steps."""
    parts = []
    for step in program.steps:
        action = re.match(r"\[(\w+)\]", str(step))
        names = " ".join(re.findall(r"<([^>]+)>", str(step))).replace("_", " ")
        parts.append(f"{action.group(1).lower() if action else ''} {names}".strip())
    return ", ".join(parts)


def export(out: Path, seeds: int, vectors: Path) -> None:
    """Candidates, labels and features of every stratified run, the model, this script."""
    from safetensors.torch import load_file, save_file

    from homesim.learn.embeddings import minilm_dir

    out.mkdir(parents=True, exist_ok=True)
    (out / "minilm").mkdir(exist_ok=True)
    source = minilm_dir()
    for name in ("config.json", "tokenizer.json", "tokenizer_config.json", "vocab.txt",
                 "special_tokens_map.json"):
        shutil.copy(source / name, out / "minilm" / name)
    weights = load_file(str(source / "model.safetensors"))
    save_file({k: v.half().contiguous() for k, v in weights.items()},
              str(out / "minilm" / "model.safetensors"))
    shutil.copy(__file__, out / Path(__file__).name)
    for seed in range(seeds):
        export_run(out, seed, vectors)


def export_run(out: Path, seed: int, vectors: Path) -> None:
    sys.path.insert(0, str(Path(__file__).parent))
    from homesim.learn.eval.experiment import RunSpec, load_run_splits
    from homesim.learn.rerank.base import Bank, Query, labelled
    from rerank_dev import training_queries

    splits = load_run_splits(RunSpec("real", "stratified", seed), vectors)
    bank = Bank(splits.train)
    everything = np.ones(len(splits.train), bool)
    rows, arrays = [], {}
    queries = [("train", *query) for query in training_queries(bank, "stratified")]
    queries += [(kind, i, e, everything, -1) for kind in ("dev", "test")
                for i, e in enumerate(getattr(splits, kind))]
    for kind, i, example, allowed, fold in queries:
        query = Query(bank, example, allowed)
        if not query.candidates:
            continue
        features, labels = labelled(query)
        key = f"{kind}-{i}"
        arrays[f"{key}/features"], arrays[f"{key}/labels"] = features, labels
        rows.append({"key": key, "kind": kind, "fold": fold,
                     "text": f"{example.title}. {example.description}",
                     "candidates": [program_text(c.program) for c in query.candidates],
                     "labels": labels.tolist()})
    with gzip.open(out / f"stratified-{seed}.jsonl.gz", "wt") as f:
        f.writelines(json.dumps(r) + "\n" for r in rows)
    np.savez_compressed(out / f"stratified-{seed}-features.npz", **arrays)
    print(f"seed {seed}: {len(rows)} queries, {sum(len(r['labels']) for r in rows)} pairs",
          flush=True)


def train_all(data: Path, tags: list[str], out: Path, budget: float) -> None:
    """Cross-fitted scores of each run `tag` as `out/ce-TAG.json`; skips runs once `budget`
    seconds have passed."""
    start = time.time()
    for tag in tags:
        if time.time() - start > budget:
            print("time budget spent, skipping", tag, flush=True)
            continue
        with gzip.open(data / f"{tag}.jsonl.gz", "rt") as f:
            rows = [json.loads(line) for line in f]
        train = [r for r in rows if r["kind"] == "train"]
        scores: dict[str, list[float]] = {}
        for k in range(FOLDS):
            model = fit(data, [r for r in train if r["fold"] != k], seed=k)
            scores |= score(model, [r for r in train if r["fold"] == k])
        model = fit(data, train, seed=FOLDS)
        scores |= score(model, [r for r in rows if r["kind"] != "train"])
        out.mkdir(parents=True, exist_ok=True)
        (out / f"ce-{tag}.json").write_text(json.dumps(scores))
        print(tag, f"done at {time.time() - start:.0f} s", flush=True)


class _Model:
    """MiniLM, mean-pooled, and a linear head: one score per (text, program) pair."""

    def __init__(self, data: Path, device: str):
        import torch
        from transformers import AutoModel, AutoTokenizer

        self.device = device
        self.tokenizer = AutoTokenizer.from_pretrained(str(data / "minilm"))
        self.encoder = AutoModel.from_pretrained(str(data / "minilm")).float().to(device)
        self.head = torch.nn.Linear(384, 1).to(device)

    def parameters(self) -> list:
        return [*self.encoder.parameters(), *self.head.parameters()]

    def __call__(self, texts: list[str], programs: list[str]):
        import torch

        batch = self.tokenizer(texts, programs, truncation=True, max_length=MAX_TOKENS,
                               padding=True, return_tensors="pt").to(self.device)
        with torch.autocast(self.device, dtype=torch.bfloat16, enabled=self.device == "cuda"):
            hidden = self.encoder(**batch).last_hidden_state
            mask = batch["attention_mask"].unsqueeze(-1).to(hidden.dtype)
            return self.head((hidden * mask).sum(1) / mask.sum(1)).squeeze(-1).float()


def fit(data: Path, rows: list[dict], seed: int) -> _Model:
    import torch

    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    model = _Model(data, "cuda" if torch.cuda.is_available() else "cpu")
    optimiser = torch.optim.AdamW(model.parameters(), lr=LEARNING_RATE, weight_decay=0.01)
    steps = EPOCHS * -(-len(rows) // QUERIES_PER_STEP)
    schedule = torch.optim.lr_scheduler.LambdaLR(
        optimiser, lambda s: min(1.0, (s + 1) / (0.1 * steps)) * max(0.0, 1 - s / steps))
    for _ in range(EPOCHS):
        order = rng.permutation(len(rows))
        for b in range(0, len(rows), QUERIES_PER_STEP):
            texts, programs, targets = [], [], []
            for q in order[b:b + QUERIES_PER_STEP]:
                row = rows[q]
                size = min(CANDIDATES_PER_QUERY, len(row["candidates"]))
                pick = rng.choice(len(row["candidates"]), size=size, replace=False)
                texts += [row["text"]] * size
                programs += [row["candidates"][j] for j in pick]
                targets.append(torch.tensor([row["labels"][j] for j in pick]))
            scores = model(texts, programs)
            parts = torch.split(scores, [len(t) for t in targets])
            loss = -sum((torch.softmax(t.to(s.device) / TAU, 0) * torch.log_softmax(s, 0)).sum()
                        for s, t in zip(parts, targets, strict=True)) / len(targets)
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            schedule.step()
    return model


def score(model: _Model, rows: list[dict]) -> dict[str, list[float]]:
    import torch

    out = {}
    with torch.no_grad():
        for row in rows:
            values: list[float] = []
            for b in range(0, len(row["candidates"]), 256):
                part = row["candidates"][b:b + 256]
                values += model([row["text"]] * len(part), part).cpu().tolist()
            out[row["key"]] = values
    return out


def evaluate(data: Path, scores: Path) -> None:
    """Cross-validated and dev top-candidate LCS: trees, trees + score, the score alone."""
    sys.path.insert(0, str(Path(__file__).parent))
    from homesim.learn.rerank.trees import fit_trees
    from rerank_dev import CONFIG, cross_validated_each, top_lcs

    means = []
    for path in sorted(scores.glob("ce-stratified-*.json")):
        tag = path.stem.removeprefix("ce-")
        ce = json.loads(path.read_text())
        arrays = np.load(data / f"{tag}-features.npz")
        groups: dict[str, list] = {"train": [], "dev": []}
        for key in ce:
            kind = key.split("-")[0]
            if kind in groups:
                groups[kind].append((int(key.split("-")[1]), arrays[f"{key}/features"],
                                     arrays[f"{key}/labels"], np.array(ce[key])))
        train = sorted(groups["train"], key=lambda g: g[0])
        dev = groups["dev"]
        folds = [i % FOLDS for i, *_ in train]
        plain = [(f, t) for _, f, t, _ in train]
        more = [(np.column_stack([f, c]), t) for _, f, t, c in train]
        row = [float(cross_validated_each(plain, folds).mean()),
               float(cross_validated_each(more, folds).mean()),
               float(np.mean([t[int(np.argmax(c))] for _, _, t, c in train])),
               float(np.mean(top_lcs(fit_trees(plain, CONFIG), [(f, t) for _, f, t, _ in dev]))),
               float(np.mean(top_lcs(fit_trees(more, CONFIG), [(np.column_stack([f, c]), t)
                                                       for _, f, t, c in dev]))),
               float(np.mean([t[int(np.argmax(c))] for _, _, t, c in dev]))]
        means.append(row)
        print(f"{tag}: CV trees {row[0]:.4f}, + score {row[1]:.4f}, score alone {row[2]:.4f}; "
              f"dev {row[3]:.4f}, {row[4]:.4f}, {row[5]:.4f}", flush=True)
    mean = np.mean(means, axis=0)
    print(f"mean of {len(means)}: CV trees {mean[0]:.4f}, + score {mean[1]:.4f}, score alone "
          f"{mean[2]:.4f}; dev {mean[3]:.4f}, {mean[4]:.4f}, {mean[5]:.4f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    verbs = parser.add_subparsers(dest="verb", required=True)
    p = verbs.add_parser("export")
    p.add_argument("--out", type=Path, default=Path(".ce"))
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    p = verbs.add_parser("train")
    p.add_argument("data", type=Path)
    p.add_argument("tags", nargs="+")
    p.add_argument("--budget", type=float, default=420.0, help="Seconds; then stop.")
    p = verbs.add_parser("evaluate")
    p.add_argument("--data", type=Path, default=Path(".ce"))
    p.add_argument("--scores", type=Path, required=True)
    args = parser.parse_args()
    if args.verb == "export":
        export(args.out, args.seeds, args.vectors)
    elif args.verb == "train":
        train_all(args.data, args.tags, Path(os.environ.get("OUT", "ce-scores")), args.budget)
    else:
        evaluate(args.data, args.scores)


if __name__ == "__main__":
    main()
