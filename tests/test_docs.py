"""The examples in the package's docstrings run and print what they claim (doctest).

Every module of the package is collected, so a new module's examples are covered without
editing this file; ``python -m restitution`` (``__main__``) is skipped since importing it runs the CLI.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import restitution

MODULES = ["restitution"] + sorted(
    m.name for m in pkgutil.walk_packages(restitution.__path__, "restitution.") if not m.name.endswith("__main__")
)
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=FLAGS, verbose=False, report=True)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples in {name} failed (see the output)"


def test_the_public_api_has_examples() -> None:
    # The public entry points (docs/model.md, section 2; docs/api/) must show how they are called.
    for name in ("restitution", "restitution.scene", "restitution.simulate", "restitution.runs.sweep",
                 "restitution.study.ensemble", "restitution.runs.distributions", "restitution.collision.operator"):
        tests = doctest.DocTestFinder().find(importlib.import_module(name))
        assert sum(len(t.examples) for t in tests) > 0, name
