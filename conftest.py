"""Root pytest configuration: doctests of optional packages need their extras."""

import importlib.util

collect_ignore_glob = []
if importlib.util.find_spec("mujoco") is None:
    collect_ignore_glob.append("src/homesim/render/*")
if importlib.util.find_spec("gymnasium") is None:
    collect_ignore_glob += ["src/homesim/agents/*", "tests/agents/*"]
