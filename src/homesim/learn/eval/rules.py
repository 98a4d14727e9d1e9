"""A hand-written rule parser for the synthetic descriptions: an upper bound, not a model.

It knows the phrasings of the template style (`homesim.synth.templates`, kept unchanged so
that earlier figures reproduce; the paraphrase grammar is new to it) and inverts them:
split the description at the connectives, match each part to a phrase, turn the phrase's
objects back into class names and write the task's steps. Where it scores near 1, the
synthetic text says the program outright and a learned model's score there measures
template inversion, not reading.
"""

from __future__ import annotations

import re
from functools import cache

from homesim.learn.vocabularies import key_step
from homesim.program.model import Program
from homesim.synth.templates import PHRASES as TEMPLATE_PHRASES

_WORD = r"(?!(?:and|the|it|to|from|on|onto|over|out|of|then)\b)[a-z]+"
_O = r"(?P<{}>" + _WORD + r"(?: " + _WORD + r"){{0,2}}?)"
"""A slot: one to three words, none of them a connective."""
def _numbered(phrasing: str) -> str:
    """A template with repeated slots numbered ({c} ... {c} -> {c} ... {c2}): a regex
    group name may appear only once."""
    seen: dict[str, int] = {}

    def rename(m: re.Match[str]) -> str:
        seen[m[1]] = seen.get(m[1], 0) + 1
        n = seen[m[1]]
        return f"{{{m[1]}}}" if n == 1 else f"{{{m[1]}{n}}}"

    return re.sub(r"\{(\w+)\}", rename, phrasing)


PHRASES: dict[str, tuple[str, ...]] = {
    kind: tuple(_numbered(p) for p in phrasings)
    for kind, phrasings in TEMPLATE_PHRASES.items() if kind != "stand_up"}
"""Phrase kind -> its phrasings ({slot}: a spoken object name), the templates' own
(`homesim.synth.templates.PHRASES`; standing up is parsed by `STAND_UP`)."""
STEPS: dict[str, tuple[tuple[str, tuple[str, ...]], ...]] = {
    "walk_room": (("WALK", ("room",)),), "run_room": (("RUN", ("room",)),),
    "switch_on": (("WALK", ("x",)), ("SWITCHON", ("x",))),
    "switch_off": (("WALK", ("x",)), ("SWITCHOFF", ("x",))),
    "fetch": (("WALK", ("x",)), ("GRAB", ("x",)), ("WALK", ("y",)), ("PUTBACK", ("x", "y"))),
    "fetch_open": (("WALK", ("x",)), ("OPEN", ("c",)), ("GRAB", ("x",)), ("WALK", ("y",)),
                   ("PUTBACK", ("x", "y"))),
    "fetch_open_close": (("WALK", ("x",)), ("OPEN", ("c",)), ("GRAB", ("x",)),
                         ("CLOSE", ("c",)), ("WALK", ("y",)), ("PUTBACK", ("x", "y"))),
    "grab": (("WALK", ("x",)), ("GRAB", ("x",))),
    "grab_open": (("WALK", ("x",)), ("OPEN", ("c",)), ("GRAB", ("x",))),
    "touch": (("WALK", ("x",)), ("TOUCH", ("x",))),
    "open": (("WALK", ("x",)), ("OPEN", ("x",))),
    "open_close": (("WALK", ("x",)), ("OPEN", ("x",)), ("CLOSE", ("x",))),
    "close": (("WALK", ("x",)), ("CLOSE", ("x",))),
    "sit": (("WALK", ("x",)), ("SIT", ("x",))),
    "sit_look": (("WALK", ("x",)), ("SIT", ("x",)), ("LOOKAT", ("y",))),
    "watch": (("WALK", ("x",)), ("SWITCHON", ("x",)), ("WALK", ("y",)), ("SIT", ("y",)),
              ("LOOKAT", ("x",))),
}
"""Phrase kind -> its steps (action, slots)."""
STAND_UP = r"(?: then stand up| and get up again| then get back up)?"
JOIN = r"(?:, and then |, then | and |\. after that, |\. next, )"
START = r"(?:first |please )?"


@cache
def _patterns() -> list[tuple[str, re.Pattern[str]]]:
    out = []
    for kind, phrasings in PHRASES.items():
        for text in phrasings:
            regex = re.escape(text).replace(r"\{", "{").replace(r"\}", "}")
            regex = re.sub(r"\{(\w+)\}", lambda m: _O.format(m.group(1)), regex)
            out.append((kind, re.compile(f"{regex}(?P<up>{STAND_UP})(?={JOIN}|$)")))
    # the most specific phrasing first: "take the {x} from the {c}" before "take the {x}"
    return sorted(out, key=lambda kp: -len(re.sub(r"\(\?P<\w+>[^)]*\)", "", kp[1].pattern)))


def _parse(text: str, at: int) -> list[tuple[str, dict[str, str]]] | None:
    """Tasks of text[at:], one phrase then a connective or the end (backtracking)."""
    for kind, pattern in _patterns():
        m = pattern.match(text, at)
        if m is None:
            continue
        end = m.end()
        if end == len(text):
            return [(kind, m.groupdict())]
        join = re.compile(JOIN).match(text, end)
        rest = _parse(text, join.end()) if join else None
        if rest is not None:
            return [(kind, m.groupdict()), *rest]
    return None


def _pieces(text: str) -> list[tuple[str, dict[str, str]]]:
    """Fallback for text that is not a chain of known phrases: each piece between
    connectives or sentence ends that is one known phrase, the rest skipped."""
    tasks = []
    for piece in re.split(rf"{JOIN}|\. |, ", text):
        piece = re.sub(rf"^{START}", "", piece.strip())
        for kind, pattern in _patterns():
            m = pattern.fullmatch(piece)
            if m is not None:
                tasks.append((kind, m.groupdict()))
                break
    return tasks


def parse(description: str) -> Program:
    """The program the description's phrases say: the whole text as a chain of known
    phrases, else the pieces of it that are known phrases (possibly none: empty)."""
    text = description.strip().lower().rstrip(".")
    start = re.compile(START).match(text)
    tasks = _parse(text, start.end() if start else 0) or _pieces(text)
    keys = []
    for kind, slots in tasks:
        names = {k.rstrip("2"): v.replace(" ", "_") for k, v in slots.items() if v and k != "up"}
        keys += [(a, tuple((names[s], 1) for s in args)) for a, args in STEPS[kind]]
        if slots.get("up"):
            keys.append(("STANDUP", ()))
    return Program(tuple(key_step(k) for k in keys))
