"""Turn descriptions into step ids: greedy, sampled, and simulator-constrained decoding."""

from __future__ import annotations

import torch

from homesim.learn.execution import StepRunner
from homesim.learn.text.seq2seq import Seq2Seq, Seq2SeqConfig
from homesim.learn.vocabularies import END, StepVocab


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
    logp = torch.zeros(batch, device=words.device)
    alive = torch.ones(batch, dtype=torch.bool, device=words.device)
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


def penalized(log_probs: torch.Tensor, emitted: list[int], config: Seq2SeqConfig
              ) -> torch.Tensor:
    """(steps,) log-probabilities less `config.repeat_penalty` per earlier use of each step,
    and minus infinity for a step that would make a run longer than `config.max_run`."""
    out = log_probs.clone()
    max_run = config.max_run
    if emitted:
        used = torch.bincount(torch.tensor(emitted, device=out.device),
                              minlength=out.shape[0]).to(out.dtype)
        out -= config.repeat_penalty * used
        tail = emitted[-max_run:]
        if len(tail) == max_run and len(set(tail)) == 1:
            out[tail[0]] = float("-inf")
    out[END] = log_probs[END]
    return out


@torch.no_grad()
def constrained(model: Seq2Seq, words: torch.Tensor, mask: torch.Tensor, vocab: StepVocab,
                runners: list[StepRunner], max_steps: int | None = None) -> list[list[int]]:
    """Greedy decoding that only emits steps whose preconditions hold in the simulated home,
    with a repetition penalty (`penalized`) so that it cannot loop.

    At each position the steps are tried from best to worst penalized score; the first that
    runs in the example's `StepRunner` (END always may) is emitted, so every program is
    executable by construction. Decoding stops at END or after `max_steps` (the longest
    training program, `Seq2SeqConfig.max_steps`).
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
        log_probs = logits.log_softmax(1)
        choice = [END] * batch
        for b in range(batch):
            if alive[b]:
                scores = penalized(log_probs[b], out[b], model.config)
                choice[b] = _first_runnable(scores, vocab, runners[b])
                alive[b] = choice[b] != END
                if alive[b]:
                    out[b].append(choice[b])
        if not any(alive):
            break
        prev = torch.tensor(choice, device=words.device)
    return out


def _first_runnable(scores: torch.Tensor, vocab: StepVocab, runner: StepRunner) -> int:
    """The best-scoring step the runner accepts (appending it), or END."""
    for i in scores.argsort(descending=True).tolist():
        if i == END or scores[i] == float("-inf"):
            return END
        if runner.try_step(vocab.steps[i]):
            return int(i)
    return END
