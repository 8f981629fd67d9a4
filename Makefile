# FibrilFit: `make run` runs the default model, `make test` runs the suite on both supported bpy.
PYTHON ?= python3.11
BPY ?= 5.0.1
BPY_LTS ?= 4.2.0
VENV ?= .venv
VENV_LTS ?= .venv42
PYTEST_ARGS ?=
BENCH_ARGS ?=
# rootdir=tests: the repository root is itself a package (the extension); without it pytest 8
# imports that __init__.py under the clone folder's name, which fails for names like fibrilfit-main.
PYTEST := -m pytest --rootdir=tests tests

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
	$(VENV)/bin/python headless.py run --json out/result.json --render out/final.png

test: test-latest test-lts

test-latest: $(VENV)/.installed
	$(VENV)/bin/python $(PYTEST) $(PYTEST_ARGS)

test-lts: $(VENV_LTS)/.installed
	$(VENV_LTS)/bin/python $(PYTEST) $(PYTEST_ARGS)

# Blender's own extension CLI ships inside the bpy wheel: no Blender binary needed.
BLENDER_EXT = $(VENV)/lib/python*/site-packages/bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py

# The gemmi wheels that blender_manifest.toml lists (every platform, Python 3.11 and 3.13) come
# from PyPI with pip download (tools/fetch_wheels.py); wheels/ is not in git.
extension: $(VENV)/.installed
	$(VENV)/bin/python tools/fetch_wheels.py
	$(VENV)/bin/python $$(ls $(BLENDER_EXT)) validate .
	mkdir -p dist
	$(VENV)/bin/python $$(ls $(BLENDER_EXT)) build --source-dir . --output-dir dist

$(VENV)/.bench-installed: $(VENV)/.installed bench/requirements.txt
	$(VENV)/bin/python -m pip install --quiet -r bench/requirements.txt
	touch $@

# Speed and memory side by side with ../shared/bench's baselines; see BENCHMARKS.md.
bench: $(VENV)/.bench-installed
	$(VENV)/bin/python bench/run.py $(BENCH_ARGS)

clean:
	rm -rf out dist .pytest_cache
