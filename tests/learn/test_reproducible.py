"""Same seed, same numbers: training reproduces itself bit for bit (docs/learn.md)."""

import hashlib
import json
import os
import subprocess
import sys

import torch

from homesim.learn.text2prog import Text2Prog
from homesim.learn.train import TrainConfig, train_mle, train_pg
from tests.cli.subprocess_cli import SRC

TRAIN_TWICE = """
import hashlib, json, sys
import torch
torch.set_num_threads(1)
from homesim.learn.data import split, synthetic_examples
from homesim.learn.table import RunConfig, train_dataset
from homesim.learn.text2prog import Text2Prog
from pathlib import Path
out = Path(sys.argv[1])
splits = split("synthetic", synthetic_examples(40, seed=11), seed=11)
config = RunConfig("synthetic", seed=11, mle_epochs=2, pg_epochs=1, batch_size=8,
                   embeddings="none")
paths = train_dataset(config, out, splits=splits)
digest = {}
for name, path in sorted(paths.items()):
    t2p = Text2Prog.load(path)
    h = hashlib.sha256()
    for key, value in sorted(t2p.model.state_dict().items()):
        h.update(key.encode() + value.numpy().tobytes())
    preds = t2p.predict(splits.test, constrained=True)
    digest[name] = [h.hexdigest(), t2p.meta["history"], t2p.meta["dev"],
                    [str(p) for p in preds]]
print(json.dumps(digest))
"""


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


def _train_in_a_process(tmp_path, hash_seed: str) -> dict:
    env = {**os.environ, "PYTHONHASHSEED": hash_seed,
           "PYTHONPATH": os.pathsep.join([SRC, os.environ.get("PYTHONPATH", "")])}
    out = tmp_path / f"run{hash_seed}"
    proc = subprocess.run([sys.executable, "-c", TRAIN_TWICE, str(out)], env=env,
                          capture_output=True, text=True, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.splitlines()[-1])


def test_same_seed_same_weights_and_scores_across_processes(tmp_path):
    """Two processes with different string hash seeds train the same three checkpoints."""
    first = _train_in_a_process(tmp_path, "1")
    second = _train_in_a_process(tmp_path, "2")
    assert set(first) == {"mle", "pg_lcs", "pg_lcs_sim"}
    assert first == second
