"""English templates for the tasks of the program grammar.

Each task has several phrasings; `{x}` slots take spoken object names (``coffe_maker`` ->
"coffe maker"). A phrase names every object its steps touch, so the text determines the
program up to the choice of phrasing. Template text is far more regular than what people
write (see docs/learn.md): models score higher on it than on the real descriptions.
"""

from __future__ import annotations

import random

PHRASES: dict[str, tuple[str, ...]] = {
    "walk_room": ("go to the {room}", "walk to the {room}", "head into the {room}",
                  "make your way to the {room}", "enter the {room}"),
    "run_room": ("run to the {room}", "hurry to the {room}", "rush into the {room}",
                 "dash over to the {room}"),
    "switch_on": ("turn on the {x}", "switch the {x} on", "go to the {x} and turn it on",
                  "power up the {x}", "walk over to the {x} and switch it on"),
    "switch_off": ("turn off the {x}", "switch the {x} off", "go to the {x} and turn it off",
                   "shut off the {x}", "walk over to the {x} and switch it off"),
    "fetch": ("put the {x} on the {y}", "take the {x} to the {y}",
              "pick up the {x} and place it on the {y}", "move the {x} onto the {y}",
              "bring the {x} over to the {y}"),
    "fetch_open": ("open the {c}, take the {x} and put it on the {y}",
                   "get the {x} out of the {c} and set it on the {y}",
                   "take the {x} from the {c} and leave it on the {y}"),
    "fetch_open_close": ("open the {c}, take out the {x}, close the {c} and put the {x} on the {y}",
                         "get the {x} from the {c}, shut the {c} and put the {x} on the {y}"),
    "grab": ("pick up the {x}", "grab the {x}", "go get the {x}", "take the {x}",
             "walk to the {x} and pick it up"),
    "grab_open": ("open the {c} and take the {x}", "get the {x} out of the {c}",
                  "take the {x} from the {c}"),
    "touch": ("touch the {x}", "go and touch the {x}", "walk to the {x} and touch it",
              "feel the {x}"),
    "open": ("open the {x}", "go to the {x} and open it", "walk over and open the {x}"),
    "open_close": ("open the {x} and close it again", "open and then close the {x}",
                   "check inside the {x} and shut it"),
    "close": ("close the {x}", "shut the {x}", "go to the {x} and close it"),
    "sit": ("sit on the {x}", "sit down on the {x}", "take a seat on the {x}",
            "go rest on the {x}"),
    "sit_look": ("sit on the {x} and look at the {y}", "take a seat on the {x} and watch the {y}",
                 "sit down on the {x} facing the {y} and look at it"),
    "stand_up": ("then stand up", "and get up again", "then get back up"),
    "watch": ("turn on the {x}, sit on the {y} and watch it",
              "switch on the {x} and watch it from the {y}",
              "watch the {x}: turn it on and sit down on the {y}"),
}

TITLES: dict[str, str] = {
    "walk_room": "Go to a room", "run_room": "Hurry to a room", "switch_on": "Turn on device",
    "switch_off": "Turn off device", "fetch": "Tidy up", "grab": "Get something",
    "touch": "Touch object", "open": "Open container", "close": "Close container",
    "sit": "Relax", "watch": "Watch TV",
}

_JOINS = (", then {b}", " and {b}", ". After that, {b}", ", and then {b}", ". Next, {b}")
_FIRSTS = ("{a}", "{a}", "first {a}", "please {a}")


def spoken(class_name: str) -> str:
    """How a class name is said: ``coffe_maker`` -> "coffe maker"."""
    return class_name.replace("_", " ")


def phrase(kind: str, rng: random.Random, **slots: str) -> str:
    """One phrasing of a task, its slots filled with spoken names."""
    template = rng.choice(PHRASES[kind])
    return template.format(**{k: spoken(v) for k, v in slots.items()})


def join(phrases: list[str], rng: random.Random) -> str:
    """Join task phrases into one description sentence."""
    text = rng.choice(_FIRSTS).format(a=phrases[0])
    for p in phrases[1:]:
        text += rng.choice(_JOINS).format(b=p)
    return text[0].upper() + text[1:] + "."
