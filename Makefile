# Two commands: `make book` and `make test`. Everything else is set up on demand.
# `make pdf` (after `make book`) prints the whole book to _build/pdf/sss-locus-book.pdf with
# headless Chromium (Debian package `chromium`, or Google Chrome).
#
# .venv is (re)built from environment.lock whenever the lock or pyproject.toml changes: the stamp
# file name carries their hash. uv (pinned and hash-checked in the lock itself) does the install;
# if uv is unavailable the fallback is pip with --require-hashes.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
PYTHON ?= python3
VENV := .venv
VPY := $(VENV)/bin/python
ENV_KEY := $(shell cat environment.lock pyproject.toml | $(PYTHON) -c "import hashlib, sys; print(hashlib.sha256(sys.stdin.buffer.read()).hexdigest()[:16])")
STAMP := $(VENV)/.installed-$(ENV_KEY)

.PHONY: book quick-book pdf test venv pyc lock clean

# Bytecode of the package's own modules, written before each command (only what changed is
# compiled again). Site-packages get theirs at install (uv --compile-bytecode; pip does it by
# default). Where PYTHONDONTWRITEBYTECODE is set (as on some CI machines) Python never writes it
# itself, and each of the ~60 Python processes of a book or test run (CLI, papermill, kernel)
# would compile every module it imports again: seaborn's import alone took 4.4 s of CPU instead
# of 1.5 s here.
pyc: $(STAMP)
	@$(VPY) -m compileall -q -j 0 sss_locus tests benchmarks tools >/dev/null

book: $(STAMP) pyc
	$(VENV)/bin/sss-locus book

# The same book from the fast `quick` parameter profile (seconds per notebook).
quick-book: $(STAMP) pyc
	$(VENV)/bin/sss-locus book --profile quick

pdf: $(STAMP)
	$(VPY) -m sss_locus.pipeline.book.bookpdf

# On every core (pytest-xdist). Tests sharing an expensive fixture form one group (conftest.py);
# --no-loadscope-reorder keeps the order conftest.py sets: the book tests last, while the shared
# quick book builds in the background.
test: $(STAMP) pyc
	$(VPY) -m pytest -n auto --dist loadgroup --no-loadscope-reorder

venv: $(STAMP)

$(STAMP): environment.lock pyproject.toml
	@$(PYTHON) -c "import sys; sys.exit(0 if sys.version_info >= (3, 11) else 'Python >= 3.11 is required (found ' + sys.version.split()[0] + '); set PYTHON=/path/to/python3.11')"
	@echo "== building $(VENV) from environment.lock ($(ENV_KEY))"
	@rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	@$(PYTHON) -c "import re, sys; t = open('environment.lock').read(); m = re.search(r'^uv==.*?(?=^\S)', t, re.M | re.S); sys.exit('no uv pin in environment.lock') if not m else open('$(VENV)/uv-requirement.txt', 'w').write(m.group(0))"
	@if $(VPY) -m pip install --quiet --require-hashes --no-deps -r $(VENV)/uv-requirement.txt \
	   && $(VENV)/bin/uv pip sync --quiet --python $(VPY) --require-hashes --compile-bytecode environment.lock; then \
	  $(VENV)/bin/uv pip install --quiet --python $(VPY) --no-deps --no-build-isolation -e . ; \
	else \
	  echo "== uv unavailable or failed: falling back to pip"; \
	  $(VPY) -m pip install --quiet --require-hashes --no-deps -r environment.lock; \
	  $(VPY) -m pip install --quiet --no-deps --no-build-isolation -e . ; \
	fi
	@touch $(STAMP)
	@echo "== $(VENV) ready"

# Regenerate environment.lock from pyproject.toml (needs internet). Keeps existing pins where
# possible; add --upgrade to move everything to the newest allowed versions.
lock:
	$(PYTHON) -m venv _build/lock-tools
	_build/lock-tools/bin/pip install --quiet uv
	_build/lock-tools/bin/uv pip compile --quiet --universal --generate-hashes --python-version 3.11 \
	  pyproject.toml --extra book --extra test --extra scale --extra survey --extra bootstrap -o environment.lock

clean:
	rm -rf _build
