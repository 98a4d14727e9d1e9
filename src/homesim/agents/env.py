"""`HomeEnv`: a Gymnasium environment that runs one program step per action in a home.

Observation: a dict of ``text`` (one paragraph an LLM can read), ``room``, ``holding``,
``objects`` (each visible object's id, class, states and whether it is within reach) and
``rooms`` (see `homesim.agents.observation`). Action: one program step as text,
``[Grab] <cup> (12)``, the instance read as the node id (as the observation writes
objects; ``<cup> (1.12)`` works too). The step runs through the simulator's one step
function (`homesim.sim.run_step`), with the same preconditions as `homesim.run_program`.

A step that cannot run (bad text, an unknown node, a failed precondition) changes
nothing; ``info["reason"]`` says why and ``info["kind"]`` what kind of precondition
failed (a `homesim.sim.FailureKind` value; None for bad text). Reward: 1 when the goal
holds after a step (the episode then terminates), else 0 (``failure_penalty`` for a step
that could not run). The episode is truncated after ``max_steps`` actions. ``info`` also
holds ``ok``, the ``step`` as parsed, what it ``changed`` and ``success``. `history` keeps
the `StepRecord` of every step that ran in this episode (what a `TraceGoal` is judged on).

>>> env = HomeEnv("scene1_trimmed", goal=StateGoal(states=((42, "ON"),)))
>>> obs, info = env.reset(seed=0)
>>> obs, reward, terminated, truncated, info = env.step("[SwitchOn] <faucet> (42)")
>>> info["reason"]
'the character is not close to faucet 42'
>>> _ = env.step("[Walk] <faucet> (42)")
>>> env.step("[SwitchOn] <faucet> (42)")[1:4]
(1.0, True, False)
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
from gymnasium import spaces

from homesim.agents.goal import Goal, StateGoal, TraceGoal
from homesim.agents.observation import CHARSET, MAX_TEXT, observe
from homesim.errors import HomesimError
from homesim.knowledge.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.program.model import Step
from homesim.sim.execute import StepRecord, run_step
from homesim.sim.state import SimState
from homesim.world.graph import EnvironmentGraph

__all__ = ["HomeEnv", "StateGoal"]

MAX_ACTION = 256
"""Longest action text accepted."""

_CHARS = "".join(sorted(CHARSET))
_NAME = spaces.Text(128, charset=_CHARS)
_REF = spaces.Text(160, charset=_CHARS)


class HomeEnv(gym.Env[dict[str, Any], str]):
    """A home, a goal and one program step per action (see the module docstring).

    Args:
        home: an environment graph or the name of a built-in home.
        goal: a `Goal` (``goal(state) -> bool``) or a `TraceGoal` (judged on the steps
            that ran: `TaskGoal` for the goals of `homesim.goals`); None: no goal, reward
            0, never terminates.
        max_steps: actions per episode before truncation.
        failure_penalty: reward of a step that could not run (0 by default).
        render_mode: None or ``"ansi"`` (`render` returns the observation text).
        kb: the knowledge base for equivalent class names (default: `load_kb()`).
    """

    # A class attribute: gymnasium.make reads the render modes from the class.
    metadata: dict[str, Any] = {"render_modes": ["ansi"], "render_fps": 1}  # noqa: RUF012

    def __init__(self, home: EnvironmentGraph | str = "scene1_trimmed", goal: Goal | None = None,
                 *, max_steps: int = 50, failure_penalty: float = 0.0,
                 render_mode: str | None = None, kb: ObjectKnowledge | None = None):
        if isinstance(home, str):
            from homesim.world.homes import load_home

            home = load_home(home)
        if render_mode not in (None, "ansi"):
            raise HomesimError(f"HomeEnv: render_mode {render_mode!r} is not None or 'ansi'")
        self.home = home
        self.goal = goal
        self.max_steps = max_steps
        self.failure_penalty = failure_penalty
        self.render_mode = render_mode
        self.kb = kb or default_kb()
        self.action_space = spaces.Text(MAX_ACTION, charset=_CHARS)
        self.observation_space = spaces.Dict({
            "text": spaces.Text(MAX_TEXT, min_length=0, charset=_CHARS),
            "room": _REF,
            "holding": spaces.Sequence(_REF),
            "objects": spaces.Sequence(spaces.Dict({
                "id": spaces.Discrete(2**31 - 1), "name": _NAME,
                "states": spaces.Text(256, min_length=0, charset=_CHARS),
                "close": spaces.Discrete(2)}), stack=False),
            "rooms": spaces.Sequence(_REF),
        })
        self.state = SimState(home)
        self.steps = 0
        self.history: list[StepRecord] = []

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[dict[str, Any], dict[str, Any]]:
        """Start again from the home as given; ``options={"goal": g}`` sets a new goal."""
        super().reset(seed=seed)
        if options and "goal" in options:
            self.goal = options["goal"]
        self.state = SimState(self.home)
        self.steps = 0
        self.history = []
        return self._observe(), {"ok": True, "reason": None, "kind": None,
                                 "success": self._success()}

    def step(self, action: str) -> tuple[dict[str, Any], float, bool, bool, dict[str, Any]]:
        """Run one program step; see the module docstring for reward and termination."""
        self.steps += 1
        step, reason = self._parse(action)
        mark = self.state.mark()
        kind = None
        if step is not None and reason is None:
            failure = run_step(self.state, step, step.nodes)
            if failure is not None:
                reason, kind = failure.reason, failure.kind.value
        ok = reason is None
        changes = self.state.changes_since(mark)
        if ok and step is not None:
            self.history.append(StepRecord(self.steps - 1, step, step.nodes, True, None,
                                           changes))
        success = self._success()
        reward = 1.0 if success else (0.0 if ok else self.failure_penalty)
        info = {"ok": ok, "reason": reason, "kind": kind,
                "step": None if step is None else str(step),
                "changed": changes.describe(self.state.label) if ok else "",
                "success": success}
        truncated = not success and self.steps >= self.max_steps
        return self._observe(), reward, success, truncated, info

    def render(self) -> str | None:
        """The observation text (render mode ``"ansi"``)."""
        return self._observe()["text"] if self.render_mode == "ansi" else None

    def goal_text(self) -> str | None:
        """The goal in words (its ``describe`` when it has one)."""
        if self.goal is None:
            return None
        describe = getattr(self.goal, "describe", None)
        return describe(self.state) if callable(describe) else repr(self.goal)

    def _observe(self) -> dict[str, Any]:
        return observe(self.state, self.goal_text())

    def _success(self) -> bool:
        if self.goal is None:
            return False
        if isinstance(self.goal, TraceGoal):
            return bool(self.goal.on_trace(self.home, self.history))
        return bool(self.goal(self.state))

    def _parse(self, action: str) -> tuple[Step | None, str | None]:
        """The step `action` names, or why it names none (one line)."""
        text = str(action).strip()
        if len(text) > MAX_ACTION:
            return None, f"the action is longer than {MAX_ACTION} characters"
        try:
            step = Step.parse(text)
        except HomesimError as e:
            return None, " ".join(str(e).split())
        for ref, node in zip(step.args, step.nodes, strict=True):
            if node not in self.state:
                return step, f"the home has no node {node} for <{ref.name}>"
            cls = self.state.class_name(node)
            if cls != ref.name and cls not in class_names_for(ref.name, self.kb):
                return step, f"node {node} is a {cls}, not a {ref.name}"
        return step, None
