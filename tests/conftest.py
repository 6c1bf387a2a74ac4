"""Shared pytest setup for the sss_locus tests.

* Puts this directory on ``sys.path`` so the test-support module ``reference_locus`` imports
  the same way under every pytest import mode.
* Registers hypothesis profiles: ``default`` (no per-example deadline: the first call of a
  numpy kernel can be slow on a loaded machine, and speed is measured in ``benchmarks/``, not
  in tests) and ``thorough`` (more examples; select with ``--hypothesis-profile=thorough``).
"""

from __future__ import annotations

import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

try:
    from hypothesis import HealthCheck, settings
except ImportError:  # hypothesis is a test extra; tests that need it importorskip it
    pass
else:
    settings.register_profile(
        "default",
        deadline=None,
        max_examples=100,
        suppress_health_check=[HealthCheck.too_slow],
    )
    settings.register_profile(
        "thorough",
        deadline=None,
        max_examples=2000,
        suppress_health_check=[HealthCheck.too_slow],
    )
    settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
