"""A trained description -> program model with its vocabularies, and its checkpoint file."""

from __future__ import annotations

import pickle
from dataclasses import dataclass, field
from pathlib import Path

import torch

from homesim.errors import HomesimError
from homesim.files import atomic_write
from homesim.learn import embeddings as emb
from homesim.learn.data import Example
from homesim.learn.execution import StepRunner
from homesim.learn.text import decode
from homesim.learn.text.seq2seq import Seq2Seq, Seq2SeqConfig
from homesim.learn.vocabularies import StepVocab, WordVocab
from homesim.program.model import Program


@dataclass
class Text2Prog:
    """The model, its word and step vocabularies, and how it was trained."""

    model: Seq2Seq
    words: WordVocab
    steps: StepVocab
    meta: dict = field(default_factory=dict)

    @classmethod
    def create(cls, train: list[Example], seed: int, config: dict | None = None,
               embeddings: str = "minilm", device: str = "cpu") -> Text2Prog:
        """A fresh model whose vocabularies come from the training examples.

        `embeddings` initialises the word embeddings: "minilm" (pretrained token
        embeddings), "word2vec" (trained on the training descriptions) or "none" (random).
        Decoding stops after the longest training program's length.
        """
        if embeddings not in emb.EMBEDDINGS:
            raise HomesimError(f"unknown embeddings {embeddings!r}: choose from "
                               f"{', '.join(emb.EMBEDDINGS)}")
        torch.manual_seed(seed)
        words = WordVocab.build(e.text for e in train)
        steps = StepVocab.build(e.program for e in train)
        longest = max((len(e.program) for e in train), default=1)
        cfg = Seq2SeqConfig(len(words), len(steps.actions), len(steps.objects),
                            **{"max_steps": longest, **(config or {})})
        vectors = None
        if embeddings == "minilm":
            vectors = emb.word_vectors(words.words)
        elif embeddings == "word2vec":
            vectors = emb.word2vec_vectors(words.words, [e.text for e in train], seed)
        if vectors is not None:
            cfg.word_dim = vectors.shape[1]
        torch.manual_seed(seed)
        model = Seq2Seq(cfg, torch.tensor(steps.table), vectors).to(device)
        return cls(model, words, steps, {"seed": seed, "embeddings": embeddings})

    @property
    def device(self) -> torch.device:
        """Where the model's weights are."""
        return next(self.model.parameters()).device

    def batch(self, examples: list[Example]) -> tuple[torch.Tensor, torch.Tensor]:
        """Padded word ids (batch, words) and their mask."""
        encoded = [self.words.encode(e.text) for e in examples]
        width = max(len(w) for w in encoded)
        words = torch.zeros(len(encoded), width, dtype=torch.long)
        for i, w in enumerate(encoded):
            words[i, :len(w)] = torch.tensor(w)
        words = words.to(self.device)
        return words, words != 0

    @torch.no_grad()
    def predict(self, examples: list[Example], constrained: bool = False,
                batch_size: int = 64) -> list[Program]:
        """Greedy programs for the examples (constrained: executable in their homes)."""
        self.model.eval()
        out: list[Program] = []
        for i in range(0, len(examples), batch_size):
            chunk = examples[i:i + batch_size]
            words, mask = self.batch(chunk)
            if constrained:
                runners = [StepRunner(e) for e in chunk]
                ids = decode.constrained(self.model, words, mask, self.steps, runners)
            else:
                ids = decode.greedy(self.model, words, mask)
            out.extend(self.steps.decode(p) for p in ids)
        return out

    def save(self, path: Path, force: bool = True) -> None:
        """Weights, config and vocabularies in one file, written atomically (an interrupted
        save leaves the old file); `force=False` refuses to replace one."""
        with atomic_write(path, "wb", force=force) as f:
            torch.save({"config": self.model.config.to_dict(),
                        "state": self.model.state_dict(), "words": self.words.words,
                        "steps": self.steps.to_json(), "meta": self.meta}, f)

    @classmethod
    def load(cls, path: Path, device: str = "cpu") -> Text2Prog:
        """A checkpoint written by `save`, its weights on `device`."""
        try:
            data = torch.load(path, map_location=device, weights_only=True)
            cfg = Seq2SeqConfig(**data["config"])
            steps = StepVocab.from_json(data["steps"])
            model = Seq2Seq(cfg, torch.tensor(steps.table)).to(device)
            model.load_state_dict(data["state"])
        except (OSError, KeyError, TypeError, RuntimeError, pickle.UnpicklingError) as e:
            raise HomesimError(f"{path}: not a text2prog checkpoint ({e})") from None
        return cls(model, WordVocab(data["words"]), steps, data.get("meta", {}))
