"""python/README.md's `>>>` examples run as doctests: their printed numbers cannot go
stale. They run from the repository root, where their scene paths are."""

from __future__ import annotations

import doctest
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_examples(monkeypatch):
    monkeypatch.chdir(README.parents[1])
    failures, tried = doctest.testfile(str(README), module_relative=False, verbose=False)
    assert tried >= 20 and failures == 0, f"{failures} of {tried} README examples failed"
