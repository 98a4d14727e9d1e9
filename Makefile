# Two commands: `make demo` (set up and run the main job) and `make test` (set up and test).
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
EXTRAS ?= dev,stats,render,serve,learn,agents,dataset

.PHONY: setup demo test lint bench clean
WEB_BUILD := src/homesim/serve/static/index.html

setup: $(VENV)/.installed $(WEB_BUILD)

$(VENV)/.installed: pyproject.toml
	sh tools/install_system_deps.sh
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[$(EXTRAS)]"
	touch $@

# The block editor (web/) is built here, not committed; homesim serve serves the build.
# npm install --no-save, not npm ci: the lock file lacks the other platforms' optional
# rollup binaries (our registry mirror lacks them), which npm ci rejects.
$(WEB_BUILD): web/package.json web/package-lock.json web/index.html web/vite.config.ts $(wildcard web/src/*)
	cd web && npm install --no-save --no-audit --no-fund --loglevel=error && npm run build

demo: setup
	$(BIN)/homesim run
	rm -rf out/demo
	$(BIN)/homesim render --home scene1 --out out/demo --width 320 --height 240 --fps 12 --preview

# The writer's model is fitted once here (90 s on an idle 2-core machine; nothing to do
# when it is there), so that no test and no request of the editor's e2e test pays for a fit.
test: lint
	$(BIN)/homesim data fetch
	$(BIN)/homesim learn fit-writer
	HOMESIM_REQUIRE_DATA=1 HOMESIM_REQUIRE_E2E=1 $(BIN)/python -m pytest

# Static checks, also the first part of `make test`: ruff, mypy, radon's complexity gate,
# the layer order of DESIGN.md (import-linter's contracts in pyproject.toml) and no import
# circle between files (tools/import_graph.py).
lint: setup
	$(BIN)/ruff check src tests benchmarks tools
	$(BIN)/mypy
	@out="$$($(BIN)/radon cc -n D src)"; if [ -n "$$out" ]; then echo "$$out"; \
		echo "radon: units of complexity D or worse; split them into named steps"; exit 1; fi
	PYTHONPATH=src $(BIN)/lint-imports --no-cache
	PYTHONPATH=src $(BIN)/python tools/import_graph.py

bench: setup
	$(BIN)/homesim data fetch
	$(BIN)/python benchmarks/executor.py
	$(BIN)/python benchmarks/grounding.py
	$(BIN)/python benchmarks/render.py
	$(BIN)/python benchmarks/interactions.py
	$(BIN)/python benchmarks/serve.py
	$(BIN)/python benchmarks/learn.py
	$(BIN)/python benchmarks/median.py
	$(BIN)/python benchmarks/repair.py
	$(BIN)/python benchmarks/examples.py
	$(BIN)/python benchmarks/home_load.py
	$(BIN)/python benchmarks/descriptions.py
	$(BIN)/python benchmarks/parse.py
	$(BIN)/python benchmarks/entry_points.py
	$(BIN)/python benchmarks/serve_load.py
	$(BIN)/python benchmarks/serve_render_rss.py
	$(BIN)/python benchmarks/homes.py --seeds 0-19

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
