# FibrilFit: `make run` runs the default model, `make test` runs the unit tests once (no bpy) and
# the bpy tests on every supported bpy (4.2 LTS, 5.0, 5.2 LTS).
PYTHON ?= python3.11
BPY ?= 5.0.1
BPY_LTS ?= 4.2.0
VENV ?= .venv
VENV_LTS ?= .venv42
# bpy 5.2 LTS needs Python 3.13: a python3.13 on the PATH that runs (pyenv's shim may not),
# else pyenv's newest 3.13.
PYTHON_52 ?= $(or $(shell python3.13 -c "import sys; print(sys.executable)" 2>/dev/null),\
  $(addsuffix /bin/python3.13,$(shell pyenv prefix 3.13 2>/dev/null)),\
  $(lastword $(sort $(wildcard $(HOME)/.pyenv/versions/3.13*/bin/python3.13))),python3.13)
BPY_52 ?= 5.2.3
VENV_52 ?= .venv52
PYTEST_ARGS ?=
BENCH_ARGS ?=
VALIDATE_ARGS ?=
# Which tests a target runs: `make test-latest BLENDER_TESTS=tests/blender/test_run.py` runs one
# file. tests/unit is always run on its own, so its guard against bpy is effective (collected with
# tests/blender, whose conftest imports bpy first, it could never fire).
UNIT_TESTS ?= tests/unit
BLENDER_TESTS ?= tests/blender
# Every run prints its 25 slowest tests and keeps every test's duration in out/junit/<target>.xml;
# pyproject sets the per-test timeout (pytest-timeout: 300 s, a slow test 7200 s, tests/conftest.py).
PYTEST = -m pytest --durations=25 --junitxml=out/junit/$@.xml

# `make test` leaves out @pytest.mark.slow (long physics runs); `make test-slow` runs only those.
TEST_MARK ?= not slow

.PHONY: run test test-unit test-latest test-lts test-52 test-alone test-slow test-cluster \
	test-blender test-pip old-blender extension bench validate validate-walks validate-shapes docs pictures mutate clean

# Each venv: bpy, the test tools, and this checkout in editable mode (`import fibrilfit` from
# tests, tools/ and bench/, with no path set-up of their own).
$(VENV)/.installed: requirements-dev.txt pyproject.toml Makefile
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet "bpy==$(BPY)" -r requirements-dev.txt
	$(VENV)/bin/python -m pip install --quiet --no-deps -e .
	touch $@

$(VENV_LTS)/.installed: requirements-dev.txt pyproject.toml Makefile
	$(PYTHON) -m venv $(VENV_LTS)
	$(VENV_LTS)/bin/python -m pip install --quiet --upgrade pip
	$(VENV_LTS)/bin/python -m pip install --quiet "bpy==$(BPY_LTS)" -r requirements-dev.txt
	$(VENV_LTS)/bin/python -m pip install --quiet --no-deps -e .
	touch $@

# Blender 5.2 ships numpy 2: its own requirements (the others pin numpy<2).
$(VENV_52)/.installed: requirements-dev-52.txt pyproject.toml Makefile
	$(PYTHON_52) -m venv $(VENV_52)
	$(VENV_52)/bin/python -m pip install --quiet --upgrade pip
	$(VENV_52)/bin/python -m pip install --quiet "bpy==$(BPY_52)" -r requirements-dev-52.txt
	$(VENV_52)/bin/python -m pip install --quiet --no-deps -e .
	touch $@

run: $(VENV)/.installed
	mkdir -p out
	$(VENV)/bin/python headless.py run --json out/result.json --render out/final.png

# The three bpy passes run two at a time (-j2, a target's output printed whole when it ends): each
# is one process at a time of mostly single-threaded physics, and CI has 2 cores. Every part runs
# whatever an earlier one did (-k, and the unit tests' failure does not stop the bpy passes); each
# prints its own `make test: PASS|FAIL ..., N s` line, and `make test` fails if any part failed.
# The extension's wheels are fetched first: test_extension on two bpy at once would otherwise
# download them into fibrilfit/wheels/ side by side. CI's time: CONTRIBUTING.md#what-ci-costs.
test: $(VENV)/.installed $(VENV_LTS)/.installed $(VENV_52)/.installed
	@failed=; \
	$(call timed,test-unit,$(MAKE) --no-print-directory test-unit) || failed="$$failed test-unit"; \
	$(VENV)/bin/python tools/fetch_wheels.py || failed="$$failed fetch_wheels"; \
	$(MAKE) --no-print-directory -k -j2 --output-sync=target test-latest test-lts test-52 \
	  || failed="$$failed (bpy passes: see their lines)"; \
	[ -z "$$failed" ] || { echo "make test: failed:$$failed"; exit 1; }

# $(call timed,NAME,COMMAND): run COMMAND, then print `make test: PASS|FAIL (exit N), S s: NAME`;
# keeps COMMAND's exit code.
timed = ( t=$$(date +%s); $(2); rc=$$?; \
  if [ $$rc -eq 0 ]; then v=PASS; else v="FAIL (exit $$rc)"; fi; \
  echo "make test: $$v, $$(( $$(date +%s) - t )) s: $(1)"; exit $$rc )

# The pure logic (tests/unit: parameters, case files, structures, geometry, sweep statistics, the
# linker walk): no bpy is imported (a guard fails any test that does), so it runs in seconds, once.
test-unit: $(VENV)/.installed
	$(VENV)/bin/python $(PYTEST) $(UNIT_TESTS) -m "$(TEST_MARK)" $(PYTEST_ARGS)

# tests/blender on each bpy.
test-latest: $(VENV)/.installed
	@$(call timed,$@ (bpy $(BPY)),$(VENV)/bin/python $(PYTEST) $(BLENDER_TESTS) -m "$(TEST_MARK)" $(PYTEST_ARGS))

# On bpy 4.2 LTS each file runs alone (test-alone's loop over tests/blender): the check that
# every test passes without another having run first costs only the start of one Python per file
# (about 4 s each), not a second pass of the suite.
test-lts: $(VENV_LTS)/.installed
	@$(call timed,$@ (bpy $(BPY_LTS) each file alone),$(MAKE) --no-print-directory test-alone \
	  ALONE_VENV=$(VENV_LTS) ALONE_FILES="$(sort $(wildcard $(BLENDER_TESTS)/test_*.py))")

test-52: $(VENV_52)/.installed
	@$(call timed,$@ (bpy $(BPY_52)),$(VENV_52)/bin/python $(PYTEST) $(BLENDER_TESTS) -m "$(TEST_MARK)" $(PYTEST_ARGS))

# Every test file alone, its tests in reverse order (tests/conftest.py's --reverse), on bpy 4.2
# LTS (where the one_bpy tests, tests/blender/conftest.py, are deselected): a test that
# passes only because another ran first (imported a module, left state) fails here. One line per
# file; a failing file's output in out/alone/<file>.log. Exit 5 (none selected) passes.
ALONE_FILES ?= $(sort $(wildcard $(UNIT_TESTS)/test_*.py) $(wildcard $(BLENDER_TESTS)/test_*.py))
ALONE_VENV ?= $(VENV_LTS)
test-alone: $(ALONE_VENV)/.installed
	@mkdir -p out/alone; failed=; \
	for f in $(ALONE_FILES); do \
	  log=out/alone/$$(echo $$f | tr / _).log; start=$$(date +%s); \
	  $(ALONE_VENV)/bin/python -m pytest "$$f" --reverse -q -m "$(TEST_MARK)" $(PYTEST_ARGS) \
	    --junitxml=out/junit/alone/$$(basename $$f .py).xml \
	    >$$log 2>&1; \
	  rc=$$?; echo "alone: $$f exit $$rc, $$(( $$(date +%s) - start )) s: $$(tail -n 1 $$log)"; \
	  [ $$rc -eq 0 ] || [ $$rc -eq 5 ] || failed="$$failed $$f"; \
	done; \
	[ -z "$$failed" ] || { echo "fails alone (logs in out/alone/):$$failed"; exit 1; }

# Only the slow tests, on every bpy (pytest's exit 5, "none selected", counts as a pass).
test-slow: $(VENV)/.installed $(VENV_LTS)/.installed $(VENV_52)/.installed
	$(VENV)/bin/python $(PYTEST) --junitxml=out/junit/$@-unit.xml $(UNIT_TESTS) -m slow \
	  $(PYTEST_ARGS); rc=$$?; [ $$rc -eq 0 ] || [ $$rc -eq 5 ] || exit $$rc
	for venv in $(VENV) $(VENV_LTS) $(VENV_52); do \
	  $$venv/bin/python $(PYTEST) --junitxml=out/junit/$@-$$(basename $$venv).xml \
	    $(BLENDER_TESTS) -m slow $(PYTEST_ARGS); rc=$$?; \
	  [ $$rc -eq 0 ] || [ $$rc -eq 5 ] || exit $$rc; \
	done

# The pip route (docs/guide/install.md#pip) in a fresh venv out/pip/venv: the wheel and sdist
# built from this checkout (python -m build), the wheel installed with the dependencies it
# declares (bpy, numpy, gemmi, tqdm, matplotlib: from pip's cache, else PyPI), then
# tests/pip/check_installed.py, run from out/pip, checks the wheel's files (the package only)
# and the installed `fibrilfit` command: --version, `run --layers 4 --json -`, `inspect` on tests/data. No make-managed venv is used.
PIP_DIR ?= out/pip
test-pip:
	rm -rf $(PIP_DIR) && mkdir -p $(PIP_DIR)
	$(PYTHON) -m venv $(PIP_DIR)/venv
	$(PIP_DIR)/venv/bin/python -m pip install --quiet --upgrade pip build
	$(PIP_DIR)/venv/bin/python -m build --outdir $(PIP_DIR)/dist . >$(PIP_DIR)/build.log
	rm -rf build fibrilfit.egg-info  # setuptools' leftovers in the checkout
	$(PIP_DIR)/venv/bin/python -m pip install --quiet $(PIP_DIR)/dist/fibrilfit-*.whl
	cd $(PIP_DIR) && venv/bin/python $(CURDIR)/tests/pip/check_installed.py $(CURDIR) dist/fibrilfit-*.whl

# Debian's Blender 3.4.1 (older than the 4.2 minimum) and Xvfb, as root, for the old-Blender tests
# of tests/blender/test_entry_points.py (refused in one line, headless, as an add-on, windowed);
# without a `blender` on the PATH they skip, so .ci/run sets FIBRILFIT_REQUIRE_OLD_BLENDER=1.
# Measured on Debian bookworm: about 1 min, 174 packages, 650 MB.
old-blender:
	command -v blender >/dev/null && command -v xvfb-run >/dev/null || { \
	  export DEBIAN_FRONTEND=noninteractive; apt-get update -q && \
	  apt-get install -y -q --no-install-recommends blender xvfb xauth; }
	blender --version | head -n 1

# Sweeps through a real SLURM: as root, set up a single-node SLURM here (.ci/slurm/setup.sh:
# Debian's slurm-wlm and munge), run the cluster-marked tests, stop the daemons it started. With
# FIBRILFIT_REQUIRE_SLURM=1 a SLURM with no node up fails the tests instead of skipping them.
test-cluster: $(VENV)/.installed
	sh .ci/slurm/setup.sh start || { sh .ci/slurm/setup.sh stop; exit 1; }
	FIBRILFIT_REQUIRE_SLURM=1 $(VENV)/bin/python $(PYTEST) $(BLENDER_TESTS) -m cluster $(PYTEST_ARGS); \
	status=$$?; sh .ci/slurm/setup.sh stop; exit $$status

# A real Blender: Debian trixie's 4.3.2 in a chroot (root; .ci/blender/chroot.sh builds it once,
# cached outside the clone and keyed on its package list), the zip installed with Blender's own
# extension command, then tests/realblender/: the command line and headless.py against the bpy
# module's verdicts, and the sidebar under Xvfb (real clicks). A screen that differs from its
# docs/images/*.png fails, its shot and difference in out/realblender/gui/screens/, unless accepted:
# `make test-blender ACCEPT_SCREENS=1` rewrites docs/images/ with the new shots.
# A chroot that cannot be built fails here with one line, never a silent pass.
ACCEPT_SCREENS ?=
test-blender: extension
	chroot=$$(sh .ci/blender/chroot.sh path) && \
	FIBRILFIT_CHROOT=$$chroot FIBRILFIT_ACCEPT_SCREENS=$(ACCEPT_SCREENS) \
	  $(VENV)/bin/python $(PYTEST) tests/realblender -p no:randomly $(PYTEST_ARGS)

# Blender's own extension CLI ships inside the bpy wheel: no Blender binary needed.
BLENDER_EXT = $(VENV)/lib/python*/site-packages/bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py

# One zip per platform (dist/fibrilfit-<version>-<platform>.zip, Blender's own
# `build --split-platforms`), each with only its own platform's wheels, from the package folder
# fibrilfit/, whose blender_manifest.toml lists the wheels (gemmi, matplotlib and its
# dependencies; every platform, Python 3.11 and 3.13); they come from PyPI with pip download
# (tools/fetch_wheels.py) into fibrilfit/wheels/, which is not in git. The folder and every zip
# are validated by Blender's extension CLI; docs/guide/install.md#which-zip gives their sizes.
extension: $(VENV)/.installed
	$(VENV)/bin/python tools/fetch_wheels.py
	$(VENV)/bin/python $$(ls $(BLENDER_EXT)) validate fibrilfit
	mkdir -p dist
	rm -f dist/fibrilfit-*.zip
	$(VENV)/bin/python $$(ls $(BLENDER_EXT)) build --source-dir fibrilfit \
	  --output-dir $(CURDIR)/dist --split-platforms
	for zip in dist/fibrilfit-*.zip; do \
	  $(VENV)/bin/python $$(ls $(BLENDER_EXT)) validate $$zip || exit 1; done
	ls -l dist/fibrilfit-*.zip

$(VENV)/.bench-installed: $(VENV)/.installed bench/requirements.txt
	$(VENV)/bin/python -m pip install --quiet -r bench/requirements.txt
	touch $@

# The three targets of issue #35 (the report, the infinite fibril's map, make validate: wall time,
# peak memory, load), then speed and memory side by side with bench/baselines/ (the seed
# tutorial's port, pybullet); see docs/benchmarks.md. QUICK=1: only checks that the three still
# run and answer, on small cases (their times mean nothing; what CI can afford).
bench: $(if $(filter 1,$(QUICK)),$(VENV)/.installed,$(VENV)/.bench-installed)  # QUICK needs no pybullet
ifeq ($(QUICK),1)
	$(VENV)/bin/python bench/targets.py --quick $(TARGETS_ARGS)
else
	$(VENV)/bin/python bench/targets.py --json out/bench_targets.json $(TARGETS_ARGS)
	$(VENV)/bin/python bench/run.py $(BENCH_ARGS)
endif

# The gallery (examples/*.toml): each case's seeds at its real linker (the answer, P(fit), the
# envelope) and its bound (the bracket's lower side); rewrites docs/validation.md's short table
# and wide table. Results stay in out/validate, so running it again resumes. Its time:
# docs/benchmarks.md#validate-47.
validate: $(VENV)/.installed
	$(VENV)/bin/python tools/validate.py --no-walk $(VALIDATE_ARGS)

# The walks to each case's minimal linker (issue #13's walk, up to the real linker or 40), after
# the real linker's runs (resumed from out/validate, so after make validate it runs the walks only).
validate-walks: $(VENV)/.installed
	$(VENV)/bin/python tools/validate.py $(VALIDATE_ARGS)

# The gallery's cases that read a domain structure file again, with the domain's real shape
# (its convex hull); a second table in docs/validation.md#real-shapes. Results in out/validate-hull.
validate-shapes: $(VENV)/.installed
	$(VENV)/bin/python tools/validate.py --domain-shape hull $(VALIDATE_ARGS)

$(VENV)/.docs-installed: $(VENV)/.installed requirements-docs.txt
	$(VENV)/bin/python -m pip install --quiet -r requirements-docs.txt
	touch $@

# The documentation site (MkDocs, Material theme) into out/site. --strict: a broken link or
# anchor fails the build; the command-line reference is generated from the parser at build time.
docs: $(VENV)/.docs-installed
	NO_MKDOCS_2_WARNING=1 $(VENV)/bin/python -m mkdocs build --strict --site-dir out/site

# Every picture the docs show that the model makes, made again from this checkout and stamped
# with its MODEL_VERSION (tools/pictures.py; tests/unit/test_pictures.py fails an older stamp).
# The report screenshot uses the trixie chroot's Chromium (root, as make test-blender); about
# 20 min on two cores. PICTURES_ARGS="--only report_6cu7.png" makes one (--list: each stamp).
PICTURES_ARGS ?=
pictures: $(VENV)/.installed
	$(VENV)/bin/python tools/pictures.py $(PICTURES_ARGS)

# Mutation testing (docs/contributing/mutation.md): cosmic-ray, in its own venv, mutates each module
# whose wrong number is a wrong science answer (tools/mutate/<module>.toml: the module and the
# tests/unit files that must kill its mutants) in a copy of the tracked files (out/mutate/tree:
# the checkout is never touched); each module's kill rate and survivors in out/mutate/<module>.txt.
# Not part of make test: all of bound.py's 2321 mutants take hours. MUTATE_SAMPLE=N runs a
# seeded sample of N mutants per module (MUTATE_SEED), MUTATE_MODULES a subset.
MUTATE_VENV ?= .venv-mutate
MUTATE_MODULES ?= bound answer judgement stretch minimal
MUTATE_SAMPLE ?=
MUTATE_SEED ?= 0
$(MUTATE_VENV)/.installed: requirements-mutate.txt
	$(PYTHON) -m venv $(MUTATE_VENV)
	$(MUTATE_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(MUTATE_VENV)/bin/python -m pip install --quiet -r requirements-mutate.txt
	touch $@

mutate: $(VENV)/.installed $(MUTATE_VENV)/.installed
	rm -rf out/mutate && mkdir -p out/mutate/tree
	git ls-files -z | xargs -0 tar -cf - | tar -C out/mutate/tree -xf -
	cd out/mutate/tree && for m in $(MUTATE_MODULES); do \
	  $(abspath $(MUTATE_VENV))/bin/cosmic-ray init tools/mutate/$$m.toml ../$$m.sqlite || exit 1; \
	  if [ -n "$(MUTATE_SAMPLE)" ]; then $(abspath $(MUTATE_VENV))/bin/python \
	    tools/mutate/sample.py ../$$m.sqlite $(MUTATE_SAMPLE) $(MUTATE_SEED) || exit 1; fi; \
	  PATH=$(abspath $(VENV))/bin:$$PATH $(abspath $(MUTATE_VENV))/bin/cosmic-ray exec \
	    tools/mutate/$$m.toml ../$$m.sqlite || exit 1; \
	  $(abspath $(MUTATE_VENV))/bin/python tools/mutate/report.py ../$$m.sqlite \
	    | tee ../$$m.txt || exit 1; \
	done

clean:
	rm -rf out dist .pytest_cache
