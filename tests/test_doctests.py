"""The examples in the package's docstrings run as doctests (in a scratch folder, since
some write files)."""

import doctest
import importlib
from pathlib import Path

import pytest

import gearcoupling

ROOT = Path(gearcoupling.__file__).parent
MODULES = sorted(
    ".".join(("gearcoupling", *path.relative_to(ROOT).with_suffix("").parts))
    .removesuffix(".__init__")
    for path in ROOT.rglob("*.py") if ">>>" in path.read_text(encoding="utf-8"))


def test_the_package_has_docstring_examples():
    assert "gearcoupling.loading.api" in MODULES and len(MODULES) >= 5


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    module = importlib.import_module(name)
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    tests = [t for t in finder.find(module, name) if t.examples]
    assert tests, f"{name} mentions >>> but has no docstring example"
    for test in tests:
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed in {name}"
