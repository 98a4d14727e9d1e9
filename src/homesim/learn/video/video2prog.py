"""Video -> program: the text model's decoder and training code over clip features.

An episode is read as the sequence of its 2-second clips' features (the TRN clip
model's feature over the frame CNN's descriptors, `homesim.learn.video.clips`); `Seq2Seq` with
`feature_dim` set encodes that sequence with its video encoder and decodes steps exactly
as for descriptions, so MLE, policy gradient (`homesim.learn.text.train`) and constrained
decoding are shared.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import torch

from homesim.learn.data import Example
from homesim.learn.text.seq2seq import Seq2Seq, Seq2SeqConfig
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.video.clips import CLIP_SECONDS, ClipModel, clip_features, clip_rows
from homesim.learn.video.store import StoredEpisode
from homesim.learn.vocabularies import StepVocab, WordVocab


def episode_features(model: ClipModel, ep: StoredEpisode, features: np.ndarray
                     ) -> torch.Tensor:
    """(clips, feature): the clip features of the episode's consecutive 2-second windows
    (the last one shorter if the episode is), from the frame features of the store
    (`features`: (store rows, width))."""
    length = max(1, round(CLIP_SECONDS * ep.fps))
    starts = range(0, max(1, ep.length - length + 1), length)
    rows = np.stack([ep.start + clip_rows(a, min(a + length, ep.length)) for a in starts])
    return clip_features(model, features, rows)


@dataclass
class Video2Prog(Text2Prog):
    """A `Text2Prog` whose inputs are clip-feature sequences, looked up by example id."""

    features: dict[str, torch.Tensor] = field(default_factory=dict)

    @classmethod
    def create_video(cls, train: list[Example], feature_dim: int, seed: int,
                     device: str = "cpu", *, word_dim: int, hidden: int, step_dim: int
                     ) -> Video2Prog:
        """A fresh model whose step vocabulary comes from the training programs, of the
        given sizes (the clip features are projected to `word_dim`; `VideoRunConfig`)."""
        steps = StepVocab.build(e.program for e in train)
        longest = max((len(e.program) for e in train), default=1)
        cfg = Seq2SeqConfig(2, len(steps.actions), len(steps.objects), max_steps=longest,
                            feature_dim=feature_dim, word_dim=word_dim, hidden=hidden,
                            step_dim=step_dim)
        torch.manual_seed(seed)
        model = Seq2Seq(cfg, torch.tensor(steps.table)).to(device)
        return cls(model, WordVocab(["<pad>", "<unk>"]), steps, {"seed": seed,
                                                                  "task": "video2prog"})

    def batch(self, examples: list[Example]) -> tuple[torch.Tensor, torch.Tensor]:
        """Padded clip features (batch, clips, feature) and their mask."""
        seqs = [self.features[e.id] for e in examples]
        width = max(len(s) for s in seqs)
        x = torch.zeros(len(seqs), width, seqs[0].shape[1])
        mask = torch.zeros(len(seqs), width, dtype=torch.bool)
        for i, s in enumerate(seqs):
            x[i, :len(s)] = s
            mask[i, :len(s)] = True
        return x.to(self.device), mask.to(self.device)
