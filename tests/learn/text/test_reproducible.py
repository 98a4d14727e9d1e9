"""Same seed, same numbers: training reproduces itself bit for bit (docs/learn.md)."""

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import torch

from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import TrainConfig, train_mle, train_pg
from tests.cli.subprocess_cli import SRC

ROOT = str(Path(__file__).resolve().parents[2])


def fingerprint(out: Path) -> dict:
    """Train three tiny checkpoints into `out`; their weights, histories, dev scores and
    constrained predictions."""
    from homesim.learn.data import split, synthetic_examples
    from homesim.learn.eval.paper_table import RunConfig, train_dataset

    splits = split("synthetic", synthetic_examples(40, seed=11), seed=11)
    config = RunConfig("synthetic", seed=11, mle_epochs=2, pg_epochs=1, batch_size=8,
                       embeddings="none")
    paths = train_dataset(config, out, splits=splits)
    digest = {}
    for name, path in sorted(paths.items()):
        t2p = Text2Prog.load(path)
        preds = t2p.predict(splits.test[:4], constrained=True)
        digest[name] = [_weights(t2p), t2p.meta["history"], t2p.meta["dev"],
                        [str(p) for p in preds]]
    return digest


def _weights(t2p: Text2Prog) -> str:
    h = hashlib.sha256()
    for key, value in sorted(t2p.model.state_dict().items()):
        h.update(key.encode() + value.numpy().tobytes())
    return h.hexdigest()


def test_policy_gradient_does_not_depend_on_what_ran_before(tiny_splits):
    train = tiny_splits.train[:12]
    runs = []
    for noise in (0, 7):
        t2p = Text2Prog.create(train, seed=0, embeddings="none")
        train_mle(t2p, train, TrainConfig(epochs=1, batch_size=6, lr=1e-2))
        torch.rand(noise)  # another model trained in between draws from the global RNG
        train_pg(t2p, train, TrainConfig(epochs=1, batch_size=6, lr=1e-3), use_sim=False)
        runs.append(_weights(t2p))
    assert runs[0] == runs[1]


def test_same_seed_same_weights_and_scores_across_processes(tmp_path):
    """A process with another string hash seed trains the same three checkpoints."""
    here = fingerprint(tmp_path / "here")
    other_seed = "2" if os.environ.get("PYTHONHASHSEED") == "1" else "1"
    env = {**os.environ, "PYTHONHASHSEED": other_seed,
           "PYTHONPATH": os.pathsep.join([SRC, ROOT, os.environ.get("PYTHONPATH", "")])}
    code = ("import json, sys, torch\ntorch.set_num_threads(1)\n"
            "from pathlib import Path\nfrom tests.learn.text.test_reproducible import fingerprint\n"
            "print(json.dumps(fingerprint(Path(sys.argv[1]))))")
    proc = subprocess.run([sys.executable, "-c", code, str(tmp_path / "there")], env=env,
                          capture_output=True, text=True, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    there = json.loads(proc.stdout.splitlines()[-1])
    assert set(here) == {"mle", "pg_lcs", "pg_lcs_sim"}
    assert json.loads(json.dumps(here)) == there
