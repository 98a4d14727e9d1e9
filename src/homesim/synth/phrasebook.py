"""The words of `homesim.synth.describe`: phrasings per step pattern, joins, openers (what
people call each object class is the class table's ``names``, `homesim.world.class_table`).

Phrasings are verb phrases in the base form, so they serve both voices (``grab the cup``,
``I grab the cup``). Slots name the objects: ``{x}`` may become a pronoun (``it``) when
the object was the last one mentioned; ``{X}`` is always a noun phrase, for places where
English wants one (``turn on the TV``, never ``turn on it``). ``{my}``, ``{me}`` and ``{I}``
follow the voice (``your``, ``you``, ``you`` in the imperative).
"""

from __future__ import annotations

PHRASINGS: dict[str, tuple[str, ...]] = {
    # one step
    "walk_room": ("go to {room}", "walk to {room}", "walk into {room}", "head to {room}",
                  "go into {room}", "enter {room}", "make {my} way to {room}",
                  "go over to {room}", "step into {room}", "walk over to {room}",
                  "go back to {room}", "move to {room}"),
    "run_room": ("run to {room}", "hurry to {room}", "rush into {room}", "dash to {room}",
                 "run over to {room}", "hurry over to {room}", "quickly go to {room}"),
    "walk_obj": ("walk over to {x}", "go to {x}", "find {x}", "walk to {x}", "approach {x}",
                 "go over to {x}", "walk up to {x}", "look for {x}",
                 "step over to {x}"),
    "run_obj": ("run to {x}", "hurry over to {x}", "rush to {x}", "dash over to {x}"),
    "switch_on": ("turn on {X}", "switch on {X}", "turn {x} on", "switch {x} on",
                  "power on {X}", "start {X}"),
    "switch_off": ("turn off {X}", "switch off {X}", "turn {x} off", "switch {x} off",
                   "shut off {X}", "power off {X}", "shut {x} off"),
    "grab": ("grab {x}", "pick up {X}", "pick {x} up", "take {x}", "get {x}",
             "take hold of {x}", "reach for {x}",
             "grab hold of {x}", "lift {x}"),
    "put": ("put {x} on {y}", "place {x} on {y}", "set {x} down on {y}", "leave {x} on {y}",
            "put {x} down on {y}", "rest {x} on {y}", "drop {x} on {y}",
            "lay {x} on {y}"),
    "open": ("open {x}", "open up {X}", "pull {x} open", "swing {x} open",
             "open {x} wide"),
    "close": ("close {x}", "shut {x}", "pull {x} shut", "push {x} closed",
              "close {x} firmly"),
    "touch": ("touch {x}", "feel {x}", "put a hand on {x}", "tap {x}", "reach out and touch {x}",
              "run {my} fingers over {x}", "lay a hand on {x}"),
    "sit": ("sit on {x}", "sit down on {x}", "take a seat on {x}", "have a seat on {x}",
            "sit down on {x} for a while",
            "settle down on {x}", "relax on {x}", "plop down on {x}"),
    "look": ("look at {x}", "watch {x}", "take a look at {x}", "stare at {x}",
             "gaze at {x}", "keep {my} eyes on {x}", "have a look at {x}"),
    "stand_up": ("stand up", "get up", "get back up", "stand up again",
                 "get back on {my} feet", "get up again"),
    # patterns of steps
    "move": ("put {x} on {y}", "move {x} to {y}", "take {x} to {y}",
             "bring {x} over to {y}", "pick up {X} and put {x} on {y}",
             "grab {x} and place {x} on {y}", "carry {x} to {y}",
             "pick {x} up and set {x} down on {y}",
             "relocate {x} to {y}", "take {x} and leave {x} on {y}",
             "grab {x} and drop {x} on {y}"),
    "take_out": ("take {x} out of {c}", "open {c} and take out {X}", "open {c} and grab {x}",
                 "get {x} from {c}", "reach into {c} for {x}",
                 "pull {x} out of {c}"),
    "take_out_put": ("take {x} out of {c} and put {x} on {y}",
                     "open {c}, grab {x} and put {x} on {y}",
                     "get {x} from {c} and set {x} on {y}",
                     "open {c}, take out {X} and leave {x} on {y}"),
    "take_out_close": ("take {x} out of {c} and close {c}",
                       "open {c}, grab {x} and shut {c} again",
                       "get {x} from {c} and close {c} behind {me}",
                       "reach into {c} for {x} and shut {c}"),
    "take_out_close_put": ("open {c}, take out {X}, close {c} and put {x} on {y}",
                           "get {x} from {c}, shut {c} and leave {x} on {y}",
                           "take {x} out of {c}, close {c} again and put {x} on {y}",
                           "reach into {c} for {x}, shut {c} and set {x} down on {y}"),
    "open_close": ("open {x} and close {x} again", "open {x}, then shut {x}",
                   "check inside {x} and close {x}", "take a look inside {x} and shut {x}",
                   "peek into {x} and close {x} again"),
    "sit_look": ("sit on {x} and look at {y}", "sit down on {x} and watch {y}",
                 "take a seat on {x} and look at {y}", "sit on {x} facing {y} and watch {y}",
                 "relax on {x} and look at {y}", "settle down on {x} and gaze at {y}"),
    "watch": ("turn on {X}, sit on {y} and watch {x}", "switch {x} on and watch {x} from {y}",
              "turn on {X} and sit down on {y} to watch {x}",
              "switch on {X}, take a seat on {y} and look at {x}",
              "turn {x} on, sit down on {y} and watch {x} for a while",
              "put {X} on and watch {x} from {y}",
              "turn on {X}, then relax on {y} and watch {x}"),
}
"""Pattern or step kind -> phrasings (see `homesim.synth.describe.PATTERNS`)."""

LEADS: tuple[str, ...] = ("go to {x} and", "walk over to {x} and", "find {x} and",
                          "head to {x} and", "locate {x} and", "walk to {x} and",
                          "walk up to {x} and", "go over to {x} and", "look for {x} and",
                          "make {my} way to {x} and", "get to {x} and")
"""Said before a clause in place of the walk to its object, when the walk is not left out."""

EXTRAS: dict[str, tuple[str, ...]] = {
    "walk_room": ("to look around", "quickly", "slowly"),
    "run_room": ("as fast as {I} can", "in a hurry"),
    "walk_obj": ("slowly",),
    "switch_on": ("right away", "again"),
    "switch_off": ("to save energy", "before leaving the room"),
    "grab": ("carefully", "with one hand"),
    "put": ("carefully", "neatly"),
    "move": ("to tidy up", "to clear some space", "carefully"),
    "open": ("to see what is inside", "slowly"),
    "close": ("gently", "behind {me}"),
    "touch": ("to check on something", "for a moment", "lightly"),
    "sit": ("to rest", "to relax for a bit", "to take a break"),
    "sit_look": ("for a while", "for a few minutes"),
    "look": ("for a while", "for a moment"),
    "watch": ("to relax", "for a while"),
}
"""Clause kind -> words sometimes said after the clause (purposes, manners)."""

CONNECTORS: tuple[str, ...] = (" and ", ", then ", " and then ", ", and ", " and ")
"""Between two clauses of one sentence."""

STARTERS: tuple[str, ...] = ("Then ", "Next, ", "After that, ", "Now ", "", "", "Then ",
                             "Afterwards, ", "Once that is done, ", "Later, ", "After this, ",
                             "Next ")
"""Before a sentence that is not the first."""

FIRST_STARTERS: tuple[str, ...] = ("", "", "", "First, ", "First ")
LAST_STARTERS: tuple[str, ...] = ("Finally, ", "Then ", "", "Lastly, ", "In the end, ",
                                  "To finish, ")

OPENERS: dict[str, tuple[str, ...]] = {
    "Watch TV": ("I want to watch some TV.", "Time for some TV.", "Let's watch TV.",
                 "TV time."),
    "Relax": ("I want to relax.", "Time to take a break.", "I am tired.",
              "Let's rest for a bit."),
    "Tidy up": ("Time to tidy up.", "The house is a mess.", "Let's clean up a little.",
                "I want to put things where they belong."),
    "Get something": ("I need something.", "I want to get something.",),
    "Turn on device": ("Time to turn things on.", "It is too quiet in here."),
    "Turn off device": ("Time to save some energy.", "Let's turn things off."),
    "Open container": ("I want to look inside.", "Let's see what is inside."),
    "Close container": ("Something was left open.", "Let's close things up."),
    "Touch object": ("I want to check something.",),
    "Go to a room": ("I need to go somewhere.", "Let's move around the house."),
    "Hurry to a room": ("I am in a hurry.", "No time to lose."),
}
"""Activity title -> opening sentences (said first, sometimes)."""
