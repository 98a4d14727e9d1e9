"""Generation plans: a data set made of parts, each with its own homes, agents and share
of the episodes, so that the split the video models learn on is decided when the data is
made (docs/dataset.md, "Plans").

Glossary:
    part: one data set folder ``DIR/<part>`` (`generate_dataset`), made with the part's
        homes, agents, episode count and seed; its role says what learning does with it:
        ``train``, ``val`` (chooses epochs and settings; never tested) or ``test``.
    row: a test row of a table: a label and the test parts it pools.

``DIR/plan.json`` records the plan, the counts and seeds of its parts and the options
they share; running the same command again resumes every part, other options are refused.
The built-in `PAPER` plan follows the paper's Table 2 protocol: it trains on seen homes
with two agents, validates on homes of its own, and tests seen homes with the same
agents, seen homes with the other two agents, and homes used by no other part.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from homesim.dataset.layout import read_json
from homesim.dataset.spec import AGENT_NAMES, DatasetConfig
from homesim.errors import DataError, HomesimError

PLAN_FILE = "plan.json"
PLAN_FORMAT = "homesim-plan/1"
ROLES = ("train", "val", "test")
PLAN_OPTIONS = ("programs", "width", "height", "fps", "modalities", "gt_stride",
                "shard_size")
"""The `DatasetConfig` options every part shares (the rest come from the part)."""


@dataclass(frozen=True)
class Part:
    """One part of a plan: a data set folder of its own."""

    name: str
    role: str  # one of ROLES
    homes: tuple[str, ...]
    agents: tuple[str, ...]
    share: float  # of the plan's episodes


@dataclass(frozen=True)
class Plan:
    """Parts and the test rows that pool them."""

    name: str
    parts: tuple[Part, ...]
    rows: tuple[tuple[str, str, tuple[str, ...]], ...]  # (row, label, test parts pooled)

    def __post_init__(self) -> None:
        check_plan(self)

    def part(self, name: str) -> Part:
        return next(p for p in self.parts if p.name == name)

    def counts(self, n: int) -> dict[str, int]:
        """Episodes per part for `n` in all: each its share, rounded; the train parts
        take what rounding leaves."""
        counts = {p.name: round(p.share * n) for p in self.parts}
        first_train = next(p.name for p in self.parts if p.role == "train")
        counts[first_train] += n - sum(counts.values())
        return counts

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name,
                "parts": [{"name": p.name, "role": p.role, "homes": list(p.homes),
                           "agents": list(p.agents), "share": p.share} for p in self.parts],
                "rows": [{"row": r, "label": label, "parts": list(parts)}
                         for r, label, parts in self.rows]}

    @classmethod
    def from_dict(cls, data: dict[str, Any], where: str = "plan") -> Plan:
        """A plan from its dict (`to_dict`, or a user's plan file)."""
        try:
            parts = tuple(Part(str(p["name"]), str(p["role"]), tuple(p["homes"]),
                               tuple(p.get("agents", AGENT_NAMES)), float(p["share"]))
                          for p in data["parts"])
            rows = tuple((str(r["row"]), str(r.get("label", r["row"])), tuple(r["parts"]))
                         for r in data["rows"])
            return cls(str(data.get("name", where)), parts, rows)
        except (KeyError, TypeError, ValueError) as e:
            raise HomesimError(f"{where}: not a plan ({type(e).__name__}: {e}); see "
                               "docs/dataset.md, 'Plans'") from None


def check_plan(plan: Plan) -> None:
    """Refuse a plan whose parts or rows are inconsistent, in one line naming the part."""
    names = [p.name for p in plan.parts]
    if len(set(names)) != len(names) or not names:
        raise HomesimError(f"plan {plan.name}: part names must be distinct and given")
    for p in plan.parts:
        _check_part(plan.name, p)
    if not any(p.role == "train" for p in plan.parts):
        raise HomesimError(f"plan {plan.name}: no train part")
    if abs(sum(p.share for p in plan.parts) - 1) > 1e-6:
        raise HomesimError(f"plan {plan.name}: the shares add up to "
                           f"{sum(p.share for p in plan.parts):.3f}, not 1")
    roles = {p.name: p.role for p in plan.parts}
    for row, _, pooled in plan.rows:
        wrong = [q for q in pooled if roles.get(q) != "test"]
        if wrong or not pooled:
            raise HomesimError(f"plan {plan.name}, row {row}: pools "
                               f"{wrong[0] if wrong else 'nothing'!r}, not a test part "
                               "(validation and training episodes are never tested)")


def _check_part(plan: str, p: Part) -> None:
    if p.role not in ROLES:
        raise HomesimError(f"plan {plan}, part {p.name}: role {p.role!r}; choose from "
                           f"{', '.join(ROLES)}")
    if not p.homes or not 0 < p.share <= 1 or "/" in p.name or p.name.startswith("."):
        raise HomesimError(f"plan {plan}, part {p.name}: needs homes, a share in (0, 1] "
                           "and a plain folder name")
    DatasetConfig(homes=p.homes, agents=p.agents)  # agents known (one-line errors)


SEEN_HOMES = ("scene1", "scene2", "scene3", "scene4", "gen-0", "gen-1", "gen-2", "gen-3",
              "gen-4", "gen-5")
VAL_HOMES = ("gen-6", "gen-7")
UNSEEN_HOMES = ("scene5", "gen-8", "gen-9", "gen-10", "gen-11")
TRAIN_AGENTS = ("male1", "female1")
OTHER_AGENTS = ("male2", "female2")

PAPER = Plan("paper", (
    Part("train", "train", SEEN_HOMES, TRAIN_AGENTS, 0.72),
    Part("val", "val", VAL_HOMES, AGENT_NAMES, 0.05),
    Part("test-seen", "test", SEEN_HOMES, TRAIN_AGENTS, 0.08),
    Part("test-unseen-agents", "test", SEEN_HOMES, OTHER_AGENTS, 0.06),
    Part("test-unseen-homes", "test", UNSEEN_HOMES, AGENT_NAMES, 0.09),
), (
    ("seen", "seen homes and agents", ("test-seen",)),
    ("unseen-agents", "seen homes, unseen agents", ("test-unseen-agents",)),
    ("unseen-homes", "unseen homes", ("test-unseen-homes",)),
    ("all", "all test episodes", ("test-seen", "test-unseen-agents", "test-unseen-homes")),
))
"""The paper's protocol (Table 2): 72 % of the episodes train on ten seen homes (the
apartments scene1-4 and generated homes gen-0..5) acted by two agents; validation has two
generated homes of its own; the unseen-homes test has scene5 and gen-8..11, used by no
other part."""

PLANS = {"paper": PAPER}


def load_plan(name: str) -> Plan:
    """A built-in plan by name, or a plan file (JSON, `Plan.to_dict`'s shape)."""
    if name in PLANS:
        return PLANS[name]
    path = Path(name)
    if not path.is_file():
        raise HomesimError(f"--plan {name}: no such plan file; built-in plans: "
                           f"{', '.join(PLANS)}")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise HomesimError(f"--plan {name}: cannot read ({e})") from None
    return Plan.from_dict(data, str(path))


def part_seed(seed: int, part: str) -> int:
    """The seed of a part's episodes and programs: its own stream, so parts that share
    homes (train, test-seen) never draw the same programs or choices."""
    digest = hashlib.sha256(f"homesim-plan-{seed}-{part}".encode()).digest()
    return int.from_bytes(digest[:4], "big") % 2**31


def part_configs(plan: Plan, n: int, seed: int, base: DatasetConfig
                 ) -> dict[str, DatasetConfig]:
    """Each part's `DatasetConfig`: the `PLAN_OPTIONS` of `base`, the part's homes, agents,
    count and seed."""
    return {p.name: replace(base, n=count, seed=part_seed(seed, p.name), homes=p.homes,
                            agents=p.agents)
            for p, count in zip(plan.parts, plan.counts(n).values(), strict=True)}


def plan_record(plan: Plan, n: int, seed: int, base: DatasetConfig) -> dict[str, Any]:
    """What ``DIR/plan.json`` holds."""
    configs = part_configs(plan, n, seed, base)
    shared = {k: v for k, v in base.to_dict().items() if k in PLAN_OPTIONS}
    return {"format": PLAN_FORMAT, "n": n, "seed": seed, "options": shared,
            "plan": plan.to_dict(),
            "parts": {name: {"n": c.n, "seed": c.seed} for name, c in configs.items()}}


@dataclass(frozen=True)
class PlanFolder:
    """A plan folder as learning reads it: the plan and each part's folder."""

    root: Path
    plan: Plan

    def folder(self, part: str) -> Path:
        return self.root / part

    def role(self, part: str) -> str:
        return self.plan.part(part).role


def read_plan(root: str | Path) -> PlanFolder | None:
    """The plan of a plan folder, or None for a folder without ``plan.json``."""
    path = Path(root) / PLAN_FILE
    if not path.exists() and not path.is_symlink():
        return None
    data = read_json(path)  # a regular file, bounded; DataError in one line
    if not isinstance(data, dict):
        raise DataError(f"{path}: expected a JSON object")
    if data.get("format") != PLAN_FORMAT:
        raise HomesimError(f"{path}: format {data.get('format')!r}, not {PLAN_FORMAT}")
    return PlanFolder(Path(root), Plan.from_dict(data["plan"], str(path)))
