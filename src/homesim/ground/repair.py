"""Repair: insert the commonsense steps a program misses so that it runs.

People writing programs leave out minor steps (the paper: 28 % of collected programs miss
some, most often walking to an object). `homesim.run_program` repairs a program that
cannot run by default. `repair` runs the program through the pipeline's strict run
(`homesim.ground.strict.run_strict`); when a step fails it tries inserting steps before
it, derived from that step's row of the action catalog (`homesim.program.actions`):

- ``reach``: walk to the (last) object first (Grab, Open, SwitchOn, PutBack's destination).
- ``moves``: stand up first (Walk, Run, Find while sitting or lying).
- ``hands`` ``put`` / ``let_go``, or a ``use_held`` motion without ``reach`` (Read, Drink):
  grab the object first.
- ``connector`` ``into`` with ``hands`` ``put`` (PutIn): open the destination first.
- ``needs`` GRABBABLE (Grab): open a closed container holding the object first.
- ``presupposes_if_able`` (SwitchOn: PLUGGED_IN, Open: OFF): the catalog action that
  ``sets_states`` that state (PlugIn, SwitchOff).
- ``presupposes`` (SwitchOn: OFF, Open: CLOSED): likewise, but only with
  ``undo_states=True`` (switching off what is on before "switching it on" changes what the
  program means, so it is asked for).
- neither ``handles`` nor ``moves`` (LookAt, Watch): turn to, or walk to, the object.
- ``hands`` ``let_go`` with a ``reach`` motion but no ``reach`` (PutObjBack): walk back to
  where the object was taken from (a run of the steps before it says where).
- an object an earlier step already acted on without walking to it: walk to it before that
  first step (grounding then binds an object the character can reach, not the one it
  stands by: lying on the couch it sat on finds no room; another couch has it).

An insertion is kept when the program then runs further (a later original step fails, or
none); an insertion after which the program still fails, at its own step (a Walk needs a
StandUp) or at another, may be repaired in turn, up to `depth` levels. The search is
bounded (`max_runs` pipeline runs, `max_insertions`). The program's own steps are never
changed, dropped or reordered; every insertion is listed with its reason.

>>> from homesim.program import parse_program
>>> r = repair(parse_program("[Grab] <wine_glass> (1)"), "scene1_trimmed")
>>> r.executable, str(r.program).splitlines()
(True, ['[Walk] <wine_glass> (1)', '[Grab] <wine_glass> (1)'])
>>> r.insertions[0].reason
'walk to <wine_glass> (1) before [Grab]: it needs the character close to it'
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from homesim.ground.strict import Insertion, Run, run_strict
from homesim.knowledge.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.program.actions import ACTIONS, ActionSpec
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.failure import FailureKind
from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import CAN_OPEN, GRABBABLE, INSIDE

# One program line plus why it is there: None for the program's own steps.
_Item = tuple[Step, str | None]


@dataclass(frozen=True, eq=False)
class Repair:
    """What `repair` did.

    Attributes:
        original: the program as given.
        program: the repaired program (the original steps, in order, plus `insertions`).
        insertions: every inserted step with its reason, in program order.
        run: the pipeline's run of `program`.
        before: the pipeline's run of `original`.
        runs: how many pipeline runs the search made.
    """

    original: Program
    program: Program
    insertions: tuple[Insertion, ...]
    run: Run
    before: Run
    runs: int = 0

    @property
    def executable(self) -> bool:
        return self.run.executable

    def to_dict(self) -> dict[str, Any]:
        """JSON view: the repaired program, the insertions and both verdicts."""
        return {"program": str(self.program), "executable": self.run.executable,
                "message": self.run.message, "executable_before": self.before.executable,
                "message_before": self.before.message,
                "insertions": [i.to_dict() for i in self.insertions], "runs": self.runs}


@dataclass
class _Search:
    """The fixed inputs and the run budget of one repair."""

    home: EnvironmentGraph
    seed: int
    kb: ObjectKnowledge
    undo_states: bool
    runs_left: int
    runs: int = 0
    prepare: bool = True

    def run(self, items: list[_Item]) -> Run:
        self.runs_left -= 1
        self.runs += 1
        return run_strict(Program(tuple(s for s, _ in items)), self.home, seed=self.seed,
                          kb=self.kb, prepare=self.prepare)


def repair_steps(program: Program, home: EnvironmentGraph, before: Run, *, seed: int = 0,
                 kb: ObjectKnowledge | None = None, prepare: bool = True
                 ) -> tuple[Insertion, ...]:
    """The steps to insert so that `program` runs in `home` (`before`: its strict run,
    which failed); () when repair finds none. What `homesim.run_program` calls.

    When what stops it is a state the program's step would bring about already (it
    switches on a device that is on), a second search also undoes such states
    (``undo_states``: switch the device off first), each insertion saying so."""
    found = repair(program, home, seed=seed, kb=kb, prepare=prepare, before=before)
    if not found.executable and found.run.kind is FailureKind.ALREADY:
        found = repair(program, home, seed=seed, kb=kb, prepare=prepare, before=before,
                       undo_states=True)
    return found.insertions if found.executable else ()


def repair(program: Program | str, home: EnvironmentGraph | str, *, seed: int = 0,
           kb: ObjectKnowledge | None = None, undo_states: bool = False,
           max_insertions: int = 16, depth: int = 3, max_runs: int = 200,
           prepare: bool = True, before: Run | None = None) -> Repair:
    """Insert the missing steps `program` needs to run in `home` (see the module docstring).

    Args:
        program: a `Program` or program text, grounded or not.
        home: an environment graph or the name of a built-in home.
        seed: seed of preparation and grounding (as `run_program`).
        kb: the object knowledge base (default: `homesim.knowledge.load_kb()`).
        undo_states: also insert steps that undo a state an action presupposes the
            opposite of (SwitchOff before a SwitchOn of a device that is already on).
        max_insertions: at most this many inserted steps.
        depth: how many insertions may be chained to get past one failing step.
        max_runs: at most this many pipeline runs in all.
        prepare: prepare the home for each trial (as `run_program`'s `prepare`).
        before: the strict run of `program`, when the caller has it (not run again).

    Returns:
        A `Repair`; when no insertion helps, its run is the best one found (it may still
        not be executable).
    """
    if isinstance(program, str):
        program = Program.parse(program)
    if isinstance(home, str):
        from homesim.world.homes import load_home

        home = load_home(home)
    search = _Search(home, seed, kb or default_kb(), undo_states, max_runs, prepare=prepare)
    items: list[_Item] = [(s, None) for s in program.steps]
    before = run = before or search.run(items)
    while not run.executable and sum(r is not None for _, r in items) < max_insertions:
        found = _improve(items, run, depth, search)
        if found is None:
            break
        items, run = found
    repaired = program.with_steps([s for s, _ in items])
    return Repair(program, repaired, _insertions(items), run, before, search.runs)


def _insertions(items: list[_Item]) -> tuple[Insertion, ...]:
    out = []
    original = 0
    for index, (step, reason) in enumerate(items):
        if reason is None:
            original += 1
        else:
            out.append(Insertion(index, step, reason, original))
    return tuple(out)


def _progress(items: list[_Item], run: Run) -> int:
    """How many of the program's own steps ran (all of them plus one when executable)."""
    if run.executable:
        return len(items) + 1
    upto = len(items) if run.failed_step is None else run.failed_step - 1
    return sum(reason is None for _, reason in items[:upto])


def _improve(items: list[_Item], run: Run, depth: int, search: _Search,
             need: int | None = None) -> tuple[list[_Item], Run] | None:
    """The first insertion (or chain of up to `depth`) after which more than `need` (by
    default: as many as now) original steps run; None when there is none within the
    budget."""
    if run.failed_step is None or run.failed_step > len(items):
        return None
    need = _progress(items, run) if need is None else need
    stuck: list[tuple[list[_Item], Run]] = []
    for inserted in _candidates(items, run.failed_step - 1, run, search):
        if search.runs_left <= 0:
            return None
        trial = search.run(inserted)
        if _progress(inserted, trial) > need:
            return inserted, trial
        if trial.failed_step is not None:
            # Preparation places added objects where the program first acts on them, and
            # grounding may bind objects anew, so an insertion may move the failure
            # earlier: worth repairing in turn, after those that leave it where it was.
            stuck.append((inserted, trial))
    if depth <= 1:
        return None
    stuck.sort(key=lambda t: -_progress(*t))  # stable: candidate order among equals
    for inserted, trial in stuck:
        found = _improve(inserted, trial, depth - 1, search, need)
        if found is not None:
            return found
    return None


# The inserted actions that answer each kind of failure, tried first, in this order; the
# other candidates of the catalog row follow (a grounding failure's kind is that of the
# deepest step the search could not pass, which need not be the one repair looks at).
_FIRST: dict[FailureKind, tuple[str, ...]] = {
    FailureKind.UNREACHABLE: ("WALK",),
    FailureKind.NOT_FACING: ("TURNTO", "WALK"),
    FailureKind.NOT_HELD: ("GRAB", "WALK"),
    FailureKind.ENCLOSED: ("OPEN",),
    FailureKind.POSTURE: ("STANDUP",),
    FailureKind.STATE: ("PLUGIN", "OPEN", "SWITCHOFF"),
    FailureKind.ALREADY: ("SWITCHOFF", "CLOSE", "PLUGOUT"),
}


def _by_kind(fixes: Iterator[tuple[Step, str]], kind: FailureKind | None
             ) -> Iterator[tuple[Step, str]]:
    """`fixes` in the order the failure's kind suggests (see `_FIRST`). Every kind keeps
    every candidate: even where the object cannot take the action, a walk may let
    grounding bind (or preparation add) another instance that can."""
    first = _FIRST.get(kind, ()) if kind is not None else ()
    if not first:
        return fixes
    return iter(sorted(fixes, key=lambda f: first.index(f[0].action.key)
                       if f[0].action.key in first else len(first)))


def _candidates(items: list[_Item], k: int, run: Run, search: _Search
                ) -> Iterator[list[_Item]]:
    """Programs with one step inserted before step `k`, most likely fix first (by the
    failure's kind, `run.kind`)."""
    step = items[k][0]
    previous = items[k - 1][0] if k > 0 else None
    seen: set[Step] = set()
    for new, reason in _by_kind(_fixes(step, k, items, search), run.kind):
        if new == previous or new in seen:
            continue  # the same step twice in a row fixes nothing
        seen.add(new)
        yield [*items[:k], (new, reason), *items[k:]]
    for j, new, reason in _earlier_fixes(step, k, items):
        yield [*items[:j], (new, reason), *items[j:]]


def _earlier_fixes(step: Step, k: int, items: list[_Item]) -> Iterator[tuple[int, Step, str]]:
    """Walk to an object of step `k` before the first step that acts on it, when none
    walks there first: the object is then bound to one the character can reach, rather
    than to the one it happens to stand by (sitting on the couch it stands by, then
    lying on it, finds no room; a [Walk] first lets grounding pick another couch)."""
    for ref in dict.fromkeys(step.args):
        first = next((j for j in range(k) if ref in items[j][0].args), None)
        if first is None:
            continue
        walk = _step("WALK", ref)
        earlier = [s for s, _ in items[:first]]
        if walk in earlier or items[first][0].action.moves:
            continue
        first_name, name = items[first][0].action.name, step.action.name
        yield (first, walk, f"walk to {ref} before [{first_name}], which first acts on it, "
                            f"so that [{name}] finds one it can reach")


def _fixes(step: Step, k: int, items: list[_Item], search: _Search
           ) -> Iterator[tuple[Step, str]]:
    """Steps that may make `step` (step `k` of `items`) runnable, each with its reason,
    from its catalog row."""
    a = step.action
    name = f"[{a.name}]"
    if a.moves:
        yield _step("STANDUP"), f"stand up before {name}: the character cannot walk seated"
    if not step.args:
        return
    yield from _hand_fixes(step, name)
    yield from _place_fixes(step, k, items, search, name)
    obj = step.args[0]
    for state in a.presupposes_if_able + (a.presupposes if search.undo_states else ()):
        yield from _setting(state, obj, name)
    if not a.handles and not a.moves:
        yield _step("TURNTO", obj), f"turn to {obj} before {name}: it needs the character facing it"
        yield _step("WALK", obj), f"walk to {obj} before {name}: it may be in another room"


def _hand_fixes(step: Step, name: str) -> Iterator[tuple[Step, str]]:
    """Get within reach, take the object in hand, open where it goes."""
    a = step.action
    obj, last = step.args[0], step.args[-1]
    if a.reach:
        yield (_step("WALK", last),
               f"walk to {last} before {name}: it needs the character close to it")
    if a.hands in ("put", "let_go") or (a.motion == "use_held" and not a.reach):
        yield _step("GRAB", obj), f"grab {obj} before {name}: it needs {obj} in hand"
    if a.hands == "put" and a.connector == "into":
        yield _step("OPEN", last), f"open {last} before {name}: it must be open to put into"


def _place_fixes(step: Step, k: int, items: list[_Item], search: _Search, name: str
                 ) -> Iterator[tuple[Step, str]]:
    """Open the container the object is in; go back to where it was taken from."""
    a = step.action
    obj = step.args[0]
    if any(GRABBABLE in r for r in a.needs_of(0)):
        for box in _containers(obj, items, search):
            yield _step("OPEN", box), f"open {box} before {name}: {obj} may be inside it"
    if a.hands == "let_go" and a.motion == "reach" and not a.reach:
        # PutObjBack: it reaches back to where the object was taken from, a place the
        # program does not name; a run of the steps before it tells which.
        back = _origin(obj, k, items, search)
        if back is not None:
            yield (_step("WALK", back), f"walk back to {back}, where {obj} was taken from, "
                   f"before {name}")


def _step(key: str, *args: ObjectRef) -> Step:
    return Step(ACTIONS[key], args)


def _setting(state: str, obj: ObjectRef, name: str) -> Iterator[tuple[Step, str]]:
    """The one-object actions whose ``sets_states`` put `obj` in `state`."""
    for spec in _setters(state):
        yield (_step(spec.key, obj),
               f"{spec.name.lower()} {obj} before {name}: it must be {state}")


def _setters(state: str) -> list[ActionSpec]:
    return [a for a in ACTIONS.values() if a.arity == 1 and state in a.sets_states]


def _containers(obj: ObjectRef, items: list[_Item], search: _Search) -> list[ObjectRef]:
    """Refs for the openable containers of the home that hold an object of `obj`'s class:
    the program's own ref of that class if it has one, else a new instance (grounding
    binds it); for a grounded `obj`, the exact container node."""
    home = search.home
    if obj.node_id is not None:
        nodes = [obj.node_id] if obj.node_id in home else []
    else:
        nodes = [n.id for c in class_names_for(obj.name, search.kb)
                 for n in home.nodes_of_class(c)]
    boxes = sorted({b for n in nodes for b in home.targets(n, INSIDE)
                    if CAN_OPEN in home.node(b).properties})
    refs: dict[tuple[str, int | None], ObjectRef] = {}
    own: dict[str, ObjectRef] = {}
    for step, _ in items:
        for ref in step.args:
            own.setdefault(ref.name, ref)
    for b in boxes:
        cls = home.node(b).class_name
        if obj.node_id is not None:
            ref = ObjectRef(cls, _free_instance(cls, items), b)
        else:
            ref = own.get(cls) or ObjectRef(cls, _free_instance(cls, items))
        refs.setdefault((cls, ref.node_id), ref)
    return list(refs.values())[:6]  # bounded: a few containers at most


def _origin(obj: ObjectRef, k: int, items: list[_Item], search: _Search) -> ObjectRef | None:
    """A ref for the node `obj` was taken from, found by running the steps before step `k`:
    the program's own ref for that node, else a new ref of its class (grounding binds it;
    bound to the node when the program is grounded)."""
    if search.runs_left <= 0:
        return None
    prefix = search.run(items[:k])
    if prefix.result is None or prefix.bindings is None:
        return None
    node = prefix.bindings.get(obj.key)
    origin = None if node is None else prefix.result.state.memory.get(node)
    if origin is None or origin[0] < 0:
        return None
    for ref, bound in prefix.bindings.items():
        if bound == origin[0]:
            return next(r for step, _ in items for r in step.args if r.key == ref)
    cls = prefix.result.state.class_name(origin[0])
    grounded = obj.node_id is not None
    return ObjectRef(cls, _free_instance(cls, items), origin[0] if grounded else None)


def _free_instance(name: str, items: list[_Item]) -> int:
    used = [ref.instance for step, _ in items for ref in step.args if ref.name == name]
    return max(used, default=0) + 1
