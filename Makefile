# FibrilFit: `make run` runs the default model, `make test` runs the suite on both supported bpy.
PYTHON ?= python3.11
BPY ?= 5.0.1
BPY_LTS ?= 4.2.0
VENV ?= .venv
VENV_LTS ?= .venv42
PYTEST_ARGS ?=
BENCH_ARGS ?=

.PHONY: run test test-latest test-lts extension bench clean

$(VENV)/.installed: requirements-dev.txt Makefile
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet "bpy==$(BPY)" -r requirements-dev.txt
	touch $@

$(VENV_LTS)/.installed: requirements-dev.txt Makefile
	$(PYTHON) -m venv $(VENV_LTS)
	$(VENV_LTS)/bin/python -m pip install --quiet --upgrade pip
	$(VENV_LTS)/bin/python -m pip install --quiet "bpy==$(BPY_LTS)" -r requirements-dev.txt
	touch $@

run: $(VENV)/.installed
	mkdir -p out
	$(VENV)/bin/python headless.py run --json out/result.json

test: test-latest test-lts

test-latest: $(VENV)/.installed
	$(VENV)/bin/python -m pytest $(PYTEST_ARGS)

test-lts: $(VENV_LTS)/.installed
	$(VENV_LTS)/bin/python -m pytest $(PYTEST_ARGS)

$(VENV)/.bench-installed: $(VENV)/.installed bench/requirements.txt
	$(VENV)/bin/python -m pip install --quiet -r bench/requirements.txt
	touch $@

# Speed and memory side by side with ../shared/bench's baselines; see BENCHMARKS.md.
bench: $(VENV)/.bench-installed
	$(VENV)/bin/python bench/run.py $(BENCH_ARGS)

clean:
	rm -rf out dist .pytest_cache
