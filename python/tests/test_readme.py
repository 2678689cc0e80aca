"""python/README.md's `>>>` examples run as doctests: their printed numbers cannot go
stale."""

from __future__ import annotations

import doctest
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_examples():
    failures, tried = doctest.testfile(str(README), module_relative=False, verbose=False)
    assert tried >= 8 and failures == 0, f"{failures} of {tried} README examples failed"
