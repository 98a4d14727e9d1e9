"""Turn descriptions into step ids: greedy, sampled, and simulator-constrained decoding."""

from __future__ import annotations

import torch

from homesim.learn.execution import StepRunner
from homesim.learn.seq2seq import Seq2Seq
from homesim.learn.vocab import END, StepVocab


def greedy(model: Seq2Seq, words: torch.Tensor, mask: torch.Tensor,
           max_steps: int | None = None) -> list[list[int]]:
    """The most likely step at each position, until END."""
    ids, _ = _rollout(model, words, mask, max_steps, sample=False)
    return ids


def sample(model: Seq2Seq, words: torch.Tensor, mask: torch.Tensor,
           generator: torch.Generator, max_steps: int | None = None
           ) -> tuple[list[list[int]], torch.Tensor]:
    """Sampled programs and the sum of their log-probabilities (batch,), differentiable."""
    return _rollout(model, words, mask, max_steps, sample=True, generator=generator)


def _rollout(model: Seq2Seq, words: torch.Tensor, mask: torch.Tensor, max_steps: int | None,
             sample: bool, generator: torch.Generator | None = None
             ) -> tuple[list[list[int]], torch.Tensor]:
    max_steps = max_steps or model.config.max_steps
    state = model.encode(words, mask)
    steps = model.step_embeddings()
    batch = words.shape[0]
    out: list[list[int]] = [[] for _ in range(batch)]
    logp = torch.zeros(batch)
    alive = torch.ones(batch, dtype=torch.bool)
    prev = None
    for _ in range(max_steps):
        logits, state = model.decode_step(state, prev, steps)
        log_probs = logits.log_softmax(1)
        if sample:
            choice = torch.multinomial(log_probs.exp(), 1, generator=generator).squeeze(1)
        else:
            choice = log_probs.argmax(1)
        logp = logp + torch.where(alive, log_probs.gather(1, choice[:, None]).squeeze(1), 0.0)
        for b in torch.nonzero(alive).flatten().tolist():
            if choice[b].item() != END:
                out[b].append(choice[b].item())
        alive = alive & (choice != END)
        if not alive.any():
            break
        prev = choice
    return out, logp


@torch.no_grad()
def constrained(model: Seq2Seq, words: torch.Tensor, mask: torch.Tensor, vocab: StepVocab,
                runners: list[StepRunner], max_steps: int | None = None) -> list[list[int]]:
    """Greedy decoding that only emits steps whose preconditions hold in the simulated home.

    At each position the steps are tried from most to least likely; the first that runs in
    the example's `StepRunner` (END always may) is emitted, so every program is executable
    by construction.
    """
    max_steps = max_steps or model.config.max_steps
    state = model.encode(words, mask)
    steps = model.step_embeddings()
    batch = words.shape[0]
    out: list[list[int]] = [[] for _ in range(batch)]
    alive = [True] * batch
    prev = None
    for _ in range(max_steps):
        logits, state = model.decode_step(state, prev, steps)
        order = logits.argsort(1, descending=True)
        choice = torch.full((batch,), END, dtype=torch.long)
        for b in range(batch):
            if not alive[b]:
                continue
            for i in order[b].tolist():
                if i == END or runners[b].try_step(vocab.steps[i]):
                    choice[b] = i
                    break
            if choice[b].item() == END:
                alive[b] = False
            else:
                out[b].append(int(choice[b].item()))
        if not any(alive):
            break
        prev = choice
    return out
