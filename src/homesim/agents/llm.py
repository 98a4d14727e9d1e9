"""An adapter that lets a language model act in `HomeEnv`: prompt in, step out.

A model is any callable ``model(prompt: str) -> str`` (a local model, an API client
wrapped in a function, or `FakeModel`, which replays fixed replies and needs no network).
`LLMPolicy` builds the prompt from the observation text (which states the goal), the
catalog's actions and the last steps with their outcomes, calls the model, and takes the
first line of the reply that looks like a program step as the action. Nothing here opens
a connection: whatever the model needs is the caller's.

>>> policy = LLMPolicy(FakeModel(["Sure. [Walk] <faucet> (42)"]))
>>> policy({"text": "You are in <bathroom> (1)."}, {})
'[Walk] <faucet> (42)'
>>> "[SwitchOn] <object> (id)" in policy.prompts[0]
True
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from homesim.program.actions import ACTIONS

Model = Callable[[str], str]
"""Prompt in, reply out."""

_STEP = re.compile(r"\[\s*[A-Za-z]+\s*\](?:\s*<[^<>]+>\s*\(\s*\d+(?:\.\d+)?\s*\)){0,2}")


def action_lines() -> list[str]:
    """One line per catalog action: ``[PutBack] <object> (id) <object> (id): put ...``."""
    return [f"[{a.name}]" + " <object> (id)" * a.arity + f": {a.description}"
            for a in ACTIONS.values()]


def build_prompt(observation_text: str, history: Sequence[tuple[str, str | None]] = ()) -> str:
    """The prompt: task, actions, the last steps and their outcomes, the observation."""
    lines = ["You control a person in a home. Reply with exactly one step, like "
             "[Walk] <sofa> (15), using objects as the observation names them.",
             "Actions:", *action_lines()]
    if history:
        lines.append("Your last steps:")
        lines += [f"{a} -> {'ok' if why is None else 'failed: ' + why}" for a, why in history]
    lines += ["Observation:", observation_text, "Next step:"]
    return "\n".join(lines)


def parse_reply(reply: str) -> str:
    """The first program step in `reply` (``[Walk] <sofa> (15)``), else the reply's first
    line (the environment then says why it is not a step)."""
    match = _STEP.search(reply)
    if match:
        return " ".join(match.group(0).split())
    return next((line.strip() for line in reply.splitlines() if line.strip()), "")


@dataclass
class LLMPolicy:
    """A policy ``(observation, info) -> action`` backed by a language model.

    Attributes:
        model: the model (``prompt -> reply``).
        memory: how many past steps the prompt lists.
        prompts: every prompt sent, in order (for logs and tests).
    """

    model: Model
    memory: int = 8
    prompts: list[str] = field(default_factory=list)
    _history: list[tuple[str, str | None]] = field(default_factory=list)
    _last: str | None = None

    def __call__(self, observation: dict[str, Any], info: dict[str, Any]) -> str:
        if self._last is not None:
            self._history.append((self._last, info.get("reason")))
        prompt = build_prompt(observation["text"], self._history[-self.memory:])
        self.prompts.append(prompt)
        self._last = parse_reply(self.model(prompt))
        return self._last

    def reset(self) -> None:
        """Forget the past steps (a new episode)."""
        self._history.clear()
        self._last = None


@dataclass
class FakeModel:
    """A model that replays `replies` in order (the last one again when they run out) and
    records the prompts: for tests and offline examples."""

    replies: Sequence[str]
    prompts: list[str] = field(default_factory=list)

    def __call__(self, prompt: str) -> str:
        self.prompts.append(prompt)
        i = min(len(self.prompts), len(self.replies)) - 1
        return self.replies[i] if self.replies else ""
