"""The paper's description -> program model: LSTM encoder, attentive LSTM step decoder.

Glossary:
    step embedding: e(s) = mean of the action embedding and the object embeddings of step s
        (an object's embedding is its class's plus its instance number's, zero for
        instance 1).
    step score: normalize(e(s)) · W_v [h_t ‖ x_t], where h_t is the decoder state and x_t
        the attention read of the encoder states; a softmax over all vocabulary steps
        (index 0 ends the program) gives the next-step distribution.
The decoder is fed the embedding of the step it emitted before and its last attention read.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.vocabularies import MAX_INSTANCE


@dataclass
class Seq2SeqConfig:
    """Sizes of the model and how it decodes; saved with every checkpoint."""

    n_words: int
    n_actions: int
    n_objects: int
    word_dim: int = 384  # MiniLM token embeddings
    hidden: int = 100  # encoder states and decoder state (the paper's 100-d LSTM)
    step_dim: int = 100
    dropout: float = 0.2
    max_steps: int = 40
    feature_dim: int = 0  # > 0: a video encoder reads (batch, clips, feature_dim) features
    repeat_penalty: float = 1.0
    """Constrained decoding takes this log-probability off a step for each time the program
    already has it (coverage; `decode.penalized`)."""
    max_run: int = 1
    """The longest run of one step constrained decoding emits: 1, a step never directly
    follows itself (people's programs repeat the step before in 0.3-1.5 % of steps,
    unconstrained decoding in 2-8 %)."""

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class DecoderState:
    enc: torch.Tensor  # (batch, words, hidden)
    mask: torch.Tensor  # (batch, words) True on real words
    h: torch.Tensor  # (batch, hidden)
    c: torch.Tensor  # (batch, hidden)
    read: torch.Tensor  # (batch, hidden) last attention read

    def select(self, rows: torch.Tensor) -> DecoderState:
        return DecoderState(self.enc[rows], self.mask[rows], self.h[rows], self.c[rows],
                            self.read[rows])


class Seq2Seq(nn.Module):
    """Encoder-decoder over word ids and step ids (see the module glossary)."""

    def __init__(self, config: Seq2SeqConfig, step_table: torch.Tensor,
                 word_vectors: torch.Tensor | None = None):
        super().__init__()
        self.config = config
        cfg = config
        self.words = nn.Embedding(cfg.n_words, cfg.word_dim, padding_idx=0)
        if word_vectors is not None:
            self.words.weight.data.copy_(word_vectors)
        # the second encoder's input: clip features projected to the word embedding size
        self.features = nn.Linear(cfg.feature_dim, cfg.word_dim) if cfg.feature_dim else None
        self.encoder = nn.LSTM(cfg.word_dim, cfg.hidden // 2, batch_first=True,
                               bidirectional=True)
        self.init_h = nn.Linear(cfg.hidden, cfg.hidden)
        self.actions = nn.Embedding(cfg.n_actions, cfg.step_dim)
        self.objects = nn.Embedding(cfg.n_objects, cfg.step_dim, padding_idx=0)
        self.instances = nn.Embedding(MAX_INSTANCE, cfg.step_dim, padding_idx=0)
        self.start = nn.Parameter(torch.zeros(cfg.step_dim))
        self.decoder = nn.LSTMCell(cfg.step_dim + cfg.hidden, cfg.hidden)
        self.attend = nn.Linear(cfg.hidden, cfg.hidden, bias=False)
        self.out = nn.Linear(2 * cfg.hidden, cfg.step_dim)  # W_v
        self.drop = nn.Dropout(cfg.dropout)
        self.register_buffer("step_table", step_table.long())  # (steps, 5): a, o, o, i, i

    # ------------------------------------------------------------------ pieces
    def step_embeddings(self) -> torch.Tensor:
        """(steps, step_dim): mean of each step's action and object embeddings."""
        t: torch.Tensor = self.step_table  # type: ignore[assignment]  # a registered buffer
        n_parts = 1 + (t[:, 1:3] > 0).sum(1, keepdim=True)
        total = (self.actions(t[:, 0]) + self.objects(t[:, 1]) + self.objects(t[:, 2])
                 + self.instances(t[:, 3]) + self.instances(t[:, 4]))
        return total / n_parts

    def encode(self, words: torch.Tensor, mask: torch.Tensor) -> DecoderState:
        """Read the descriptions: words (batch, words) ids, mask (batch, words).

        With a video encoder (`Seq2SeqConfig.feature_dim`), `words` may instead be float
        clip features (batch, clips, feature_dim): they are projected and read the same way.
        """
        if words.is_floating_point():
            if self.features is None:
                raise ValueError("this model has no video encoder (feature_dim is 0)")
            x = self.drop(torch.tanh(self.features(words)))  # (batch, clips, word_dim)
        else:
            x = self.drop(self.words(words))  # (batch, words, word_dim)
        lengths = mask.sum(1).cpu()
        packed = nn.utils.rnn.pack_padded_sequence(x, lengths, batch_first=True,
                                                   enforce_sorted=False)
        out, (h, _) = self.encoder(packed)
        enc, _ = nn.utils.rnn.pad_packed_sequence(out, batch_first=True,
                                                  total_length=mask.shape[1])
        last = torch.cat([h[0], h[1]], dim=1)  # (batch, hidden) both directions' ends
        h0 = torch.tanh(self.init_h(last))
        return DecoderState(enc, mask, h0, torch.zeros_like(h0), torch.zeros_like(h0))

    def decode_step(self, state: DecoderState, prev: torch.Tensor | None,
                    steps: torch.Tensor) -> tuple[torch.Tensor, DecoderState]:
        """Scores of every step (batch, steps) after emitting `prev` (None at the start).

        `steps` is `step_embeddings()`, computed once per batch.
        """
        # (batch, step_dim): the start vector, or the embedding of the step emitted before
        e_prev = self.start.expand(state.h.shape[0], -1) if prev is None else steps[prev]
        h, c = self.decoder(torch.cat([e_prev, state.read], 1), (state.h, state.c))
        scores = torch.einsum("bwh,bh->bw", state.enc, self.attend(h))
        scores = scores.masked_fill(~state.mask, float("-inf"))
        read = torch.einsum("bw,bwh->bh", scores.softmax(1), state.enc)  # (batch, hidden)
        query = self.out(self.drop(torch.cat([h, read], 1)))  # (batch, step_dim)
        logits = query @ F.normalize(steps, dim=1).T  # (batch, steps)
        return logits, DecoderState(state.enc, state.mask, h, c, read)

    # ------------------------------------------------------------------ training
    def forward(self, words: torch.Tensor, mask: torch.Tensor,
                targets: torch.Tensor) -> torch.Tensor:
        """Teacher-forced mean cross-entropy; targets (batch, len) padded with -100."""
        state = self.encode(words, mask)
        steps = self.step_embeddings()
        prev = None
        losses = []
        for t in range(targets.shape[1]):
            logits, state = self.decode_step(state, prev, steps)
            gold = targets[:, t]
            losses.append(F.cross_entropy(logits, gold, ignore_index=-100, reduction="sum"))
            prev = gold.clamp(min=0)
        return torch.stack(losses).sum() / (targets != -100).sum()
