# Two commands: `make demo` (set up and run the main job) and `make test` (set up and test).
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
EXTRAS ?= dev,stats,render

.PHONY: setup demo test lint bench clean

setup: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml
	sh tools/install_system_deps.sh
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[$(EXTRAS)]"
	touch $@

demo: setup
	$(BIN)/homesim run
	rm -rf out/demo
	$(BIN)/homesim render --home scene1 --out out/demo --width 320 --height 240 --fps 12 --preview

test: setup
	$(BIN)/homesim data fetch
	$(BIN)/ruff check src tests benchmarks tools
	HOMESIM_REQUIRE_DATA=1 $(BIN)/python -m pytest

bench: setup
	$(BIN)/homesim data fetch
	$(BIN)/python benchmarks/executor.py
	$(BIN)/python benchmarks/grounding.py
	$(BIN)/python benchmarks/render.py

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
