"""Hypothesis profiles of the fuzzing harness.

``ci`` (the default): few examples (20 per test: the suite's bound; the long search is the
``fuzz`` profile's), derandomized (the same examples on every run, so a busy
machine cannot make CI flaky), no deadline (load must not fail a test; hangs are caught by the
harness's own time bound), no example database written. ``fuzz``: a long random search, run
by hand::

    LAUNCHKIT_FUZZ_PROFILE=fuzz python -m pytest tests/fuzz -p no:cacheprovider

Whatever a long run finds becomes a file in tests/hostile/corpus and a case in tests/hostile.
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

_COMMON = {
    "deadline": None,
    "database": None,
    "suppress_health_check": [HealthCheck.too_slow, HealthCheck.data_too_large],
}
settings.register_profile("ci", max_examples=20, derandomize=True, **_COMMON)
settings.register_profile(
    "fuzz", max_examples=int(os.environ.get("LAUNCHKIT_FUZZ_EXAMPLES", "5000")), **_COMMON
)
settings.load_profile(os.environ.get("LAUNCHKIT_FUZZ_PROFILE", "ci"))
