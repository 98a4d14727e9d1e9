"""Every limit of homesim in one place.

The CLI (``homesim run``, reading program and graph files) and the web API apply the same
limits; input over a limit is refused with one line (a 4xx answer) naming the limit.
Real data is far below each of them: the 518 VirtualHome programs have under 100 steps
and under 2 KB of text, and the five apartments are under 4 MB of JSON with coordinates
within 30 m. docs/limits.md lists them in a table.
"""

from __future__ import annotations

# ------------------------------------------------------------------ programs
MAX_PROGRAM_BYTES = 256 * 1024
"""Largest program text (UTF-8 bytes), from a file, stdin or a request."""

MAX_STEPS = 1000
"""Most steps a program may have."""

MAX_ID_DIGITS = 9
"""Most digits of an instance number or node id in a step (``(1.417)``); keeps ids
within 32-bit integers, which MuJoCo and numpy indexes use."""

MAX_NAME_CHARS = 100
"""Longest action or object name between brackets (``[Walk]``, ``<sofa>``)."""

MAX_DESCRIPTION_CHARS = 2000
"""Longest title or description a program is written for (``homesim learn write``,
``POST /api/write``)."""

EXCERPT_CHARS = 80
"""Most characters of user text an error message quotes (then an ellipsis)."""

# ------------------------------------------------------------------ goals and plans
MAX_FORMULA_CHARS = 16 * 1024
"""Longest goal formula (characters); EAI's longest is 667."""

MAX_FORMULA_DEPTH = 32
"""Deepest nesting of a goal formula: parentheses, 'not' and quantifiers, each a level
(EAI's deepest is 4); the parser and the checker recurse once per level."""

MAX_FORMULA_ATOMS = 256
"""Most atoms in a goal formula (EAI's largest has 18); checking ``A then B then ...``
costs about atoms x (steps + 1)² / 2 atom checks."""

MAX_FORMULA_QUANTIFIERS = 2
"""Most quantifiers nested in one another (EAI nests 2); each multiplies the checking
cost by the number of nodes of the home."""

MAX_PLAN_DEPTH = 8
"""Deepest nesting of JSON arrays and objects in a plan file or in one plan's text (EAI's
format needs 3: the list of records, a record, and in a plan its object and lists)."""

MAX_PLAN_STEPS = MAX_STEPS
"""Most steps one plan may have; a longer plan gets a ``format`` error, the others are
scored."""

# ------------------------------------------------------------------ graphs
MAX_GRAPH_BYTES = 256 * 1024 * 1024
"""Largest environment graph file (bytes of JSON, after gunzip)."""

MAX_DATA_FILE_BYTES = 256 * 1024 * 1024
"""Largest other input file: a JSONL data set of programs, a file of plans to score, a
data set's json (``dataset.json``, a shard's json), in bytes."""

MAX_JSON_DEPTH = 32
"""Deepest nesting of JSON arrays and objects in a graph or request (a graph needs 4)."""

MAX_NODE_ID = 2**31 - 1
"""Largest node id of a graph (ids index 32-bit arrays in render: segmentation, MuJoCo
names); ids are at least 0."""

MAX_RENDER_NODES = 4000
"""Most nodes of a home that is rendered (an apartment has ~450): MuJoCo compiles the scene
in one call that cannot be interrupted, minutes for tens of thousands of boxes."""

MAX_COORD = 1.0e4
"""Largest absolute bounding-box coordinate, in metres."""

MAX_SIZE = 1.0e3
"""Largest bounding-box extent along one axis, in metres."""

# ------------------------------------------------------------------ API
MAX_REQUEST_BYTES = MAX_PROGRAM_BYTES
"""Largest request body the API accepts (its JSON holds at most one program)."""

# ------------------------------------------------------------------ rendering
MIN_RENDER_SIDE = 16
"""Smallest frame width or height, in pixels."""

MAX_RENDER_WIDTH = 1280
"""Widest frame, in pixels."""

MAX_RENDER_HEIGHT = 960
"""Tallest frame, in pixels."""

MAX_RENDER_PIXEL_FRAMES = 64 * 320 * 240
"""Most frames x pixels one render request may ask for (64 frames at 320x240; an
RGB frame costs 3 bytes a pixel, so at most ~15 MB of images per request)."""

MAX_RENDER_VIDEO_FPS = 30
"""Highest frame rate of a program's video rendered for the editor (``/api/render/video``)."""

MAX_RENDER_VIDEO_PIXEL_FRAMES = 1800 * 320 * 240
"""Most frames x pixels of one video rendered for the editor (2.5 minutes at 12 fps and
320x240), checked once the program is animated, before the first frame is drawn; the
frames go straight into the MP4 file, one at a time."""

MIN_VIDEO_SIDE = 8
"""Smallest frame width or height of a recorded video (``homesim render``), in pixels."""

MAX_VIDEO_SIDE = 4096
"""Largest frame width or height of a recorded video, in pixels."""

MAX_VIDEO_FPS = 240
"""Highest frame rate of a recorded video."""

MAX_VIDEO_PIXEL_FRAMES = 30 * 60 * 20 * 640 * 480
"""Most frames x pixels one recorded video may hold (20 minutes at 30 fps and 640x480;
the whole recording is checked before its first frame is drawn). A video is written to
disk frame by frame, so it may be far longer than what one API request renders
(`MAX_RENDER_PIXEL_FRAMES`), but not unbounded: a 1000-step program at 4096x4096 and 240
fps would run for days and fill the disk."""

MAX_WALK_CELLS = 16_000_000
"""Most cells of the walk grid the renderer plans paths on (10 cm cells: a floor of
400 m x 400 m; an apartment has ~30 000). A home spread wider is refused before the grid
is allocated (a 1 byte per cell array)."""

MAX_EPISODES = 1_000_000
"""Most episodes of one activity video data set (``homesim dataset generate --n``)."""

RENDER_WORKERS = 1
"""Render requests that run at the same time (each holds an OpenGL context)."""

RENDER_QUEUE = 4
"""Render requests that may wait for a worker; more are refused with 503."""

# ------------------------------------------------------------------ server
RENDER_TIMEOUT_S = 120.0
"""Longest a render job may run before its worker process is killed."""

RENDER_KEEP_JOBS = 16
"""Finished render jobs whose frames the server keeps (the oldest go first)."""

RENDER_KEEP_S = 600.0
"""Seconds a finished render job's frames stay available."""

INLINE_PROGRAM_CHARS = 4 * 1024
"""Programs up to this many characters are checked and run in the server process; larger
ones go to a program worker process, so their parsing never holds up other requests."""

PROGRAM_WORKERS = 1
"""Worker processes for large programs."""

PROGRAM_QUEUE = 8
"""Large-program requests that may wait for a program worker; more are refused with 503."""

PROGRAM_TIMEOUT_S = 30.0
"""Longest a program worker may take for one request (a large program, or any request on
a generated home) before it is killed and the client told so."""

WORKER_MEMORY_BYTES = 3 * 1024**3
"""Memory (``RLIMIT_DATA``) of each of the server's worker processes: program workers,
writer workers and render jobs. A job needing more fails with one line."""

WRITE_WORKERS = 1
"""Worker processes that write programs for descriptions (``POST /api/write``); each keeps
the writer's model loaded."""

WRITE_QUEUE = 4
"""Write requests that may wait for a writer worker; more are refused with 503."""

WRITE_TIMEOUT_S = 60.0
"""Longest one write may take (the model loaded: about a second; loading it: seconds)."""

LARGE_BODIES_AT_ONCE = 1
"""Requests with bodies over `INLINE_PROGRAM_CHARS` bytes that the server reads and answers
at the same time (1: small requests wait behind at most one); up to `PROGRAM_QUEUE` more
wait unread, further ones get 503."""

HEADER_TIMEOUT_S = 10.0
"""Seconds a client has to send a request's headers; slower connections are closed."""

BODY_TIMEOUT_S = 10.0
"""Seconds a client has to send a request body; slower ones get 408."""

KEEP_ALIVE_S = 5
"""Seconds an idle keep-alive connection stays open."""

SHUTDOWN_GRACE_S = 2
"""Seconds a stopping server waits for requests in flight before cancelling them."""

MAX_MESSAGE_CHARS = 500
"""Longest error message (and quoted text) in an API answer (then an ellipsis)."""


def deeper_than(value: object, depth: int) -> bool:
    """Whether JSON data (dicts, lists, scalars) nests more than `depth` levels.

    Iterative, so it is safe on data of any depth. Loaders call it on the parts of a
    document they keep without reading (a node's unknown keys).

    >>> deeper_than([[1]], 1), deeper_than([[1]], 2)
    (True, False)
    """
    stack = [(value, 0)]
    while stack:
        item, level = stack.pop()
        if isinstance(item, dict):
            item = list(item.values())
        elif not isinstance(item, list):
            continue
        if level + 1 > depth:
            return True
        stack.extend((child, level + 1) for child in item)
    return False
