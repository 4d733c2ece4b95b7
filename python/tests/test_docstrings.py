"""The API documents itself: every public function, class, method and property of `haff`
has a numpy-style docstring (a summary line; Parameters naming every argument, Returns
for functions, Examples), and the examples run and print what they say (doctest).

The public names are those of ``haff.__all__`` and the ``__all__`` of its public modules
(``haff.rods``, ``haff.theory``), with the public methods and properties of its classes.
"""

from __future__ import annotations

import doctest
import inspect
import pickle
import re
import time
from types import ModuleType
from typing import Any, Iterator, List, Set, Tuple

import pytest

import haff

#: The modules whose docstrings hold the examples (the package's own, with __init__'s).
MODULES = ["haff", "haff._cor", "haff._simulation", "haff._study", "haff._particles",
           "haff.rods", "haff.theory"]


def public() -> Iterator[Tuple[str, Any]]:
    """(qualified name, object) of every public function, class, method and property."""
    for name in haff.__all__:
        obj = getattr(haff, name)
        if name == "__version__":
            continue
        if isinstance(obj, ModuleType):
            yield f"haff.{name}", obj
            for inner in obj.__all__:
                yield f"haff.{name}.{inner}", getattr(obj, inner)
        elif inspect.isclass(obj):
            yield f"haff.{name}", obj
            for member, value in vars(obj).items():
                if member.startswith("_"):
                    continue
                if isinstance(value, (classmethod, staticmethod)):
                    value = value.__func__
                if inspect.isfunction(value) or isinstance(value, property):
                    yield f"haff.{name}.{member}", value
        else:
            yield f"haff.{name}", obj


def sections(doc: str) -> List[str]:
    """The numpy-style section titles of a docstring (a line underlined by dashes)."""
    lines = inspect.cleandoc(doc).splitlines()
    return [lines[i].strip() for i in range(len(lines) - 1)
            if lines[i].strip() and re.fullmatch(r"-{3,}", lines[i + 1].strip())
            and len(lines[i + 1].strip()) == len(lines[i].strip())]


def documented_parameters(doc: str, title: str = "Parameters") -> Set[str]:
    """The names a section (``Parameters``) documents: its unindented ``name : type``
    lines (``a, b : float`` documents both)."""
    lines = inspect.cleandoc(doc).splitlines()
    try:
        start = next(i for i in range(len(lines) - 1)
                     if lines[i].strip() == title and set(lines[i + 1].strip()) == {"-"})
    except StopIteration:
        return set()
    names: Set[str] = set()
    for line in lines[start + 2:]:
        if line.strip() and set(line.strip()) == {"-"}:
            break  # the next section's underline: its title was the previous line
        if line and not line[0].isspace():
            head = line.split(" : ")[0]
            names.update(n.strip().lstrip("*") for n in head.split(","))
    return names


def arguments(obj: Any) -> List[str]:
    """The arguments of a function or of a class's constructor, without self and cls."""
    target = obj.__init__ if inspect.isclass(obj) else obj
    try:
        signature = inspect.signature(target)
    except (TypeError, ValueError):
        return []
    return [p for p in signature.parameters if p not in ("self", "cls")]


PUBLIC = list(public())


def test_the_public_api_is_walked():
    names = {name for name, _ in PUBLIC}
    for expected in ("haff.Simulation", "haff.Simulation.run", "haff.Simulation.timeseries",
                     "haff.Simulation.load", "haff.study", "haff.StudyResult",
                     "haff.rods.collide", "haff.theory.sonine", "haff.read_configuration",
                     "haff.ConfigError", "haff.eps"):
        assert expected in names
    assert len(names) > 50


@pytest.mark.parametrize("name, obj", PUBLIC, ids=[name for name, _ in PUBLIC])
def test_every_public_name_has_a_numpy_docstring(name: str, obj: Any):
    doc = obj.__doc__ if not isinstance(obj, property) else obj.fget.__doc__
    assert doc and doc.strip(), f"{name}: no docstring"
    summary = inspect.cleandoc(doc).splitlines()[0]
    assert summary.strip() and not summary.startswith(" "), f"{name}: no summary line"
    if isinstance(obj, ModuleType):
        return
    found = sections(doc)
    assert "Examples" in found, f"{name}: no Examples section (has {found})"
    if isinstance(obj, property):
        return
    args = arguments(obj)
    if inspect.isclass(obj) and issubclass(obj, BaseException):
        args = []  # an exception takes its message
    if args:
        assert "Parameters" in found, f"{name}: arguments {args} and no Parameters section"
        missing = set(args) - documented_parameters(doc)
        assert not missing, f"{name}: Parameters does not document {sorted(missing)}"
    if not inspect.isclass(obj):
        assert "Returns" in found, f"{name}: no Returns section (has {found})"


def test_help_of_simulation_reads_as_documentation():
    """help(haff.Simulation): what a Simulation is, the config dict and where its keys are
    listed, its attributes and methods."""
    text = pydoc_text(haff.Simulation)
    for phrase in ("the run of ``haff run``", "bit", "docs/guide/reference.md",
                   "Attributes", "timeseries", "Methods", "run(self, progress",
                   "Examples"):
        assert phrase in text, phrase


def pydoc_text(obj: Any) -> str:
    import pydoc
    return pydoc.render_doc(obj, renderer=pydoc.plaintext)


def test_config_error_is_haff_config_error():
    """Declared in `haff`: tracebacks and help name haff.ConfigError, and it pickles (a
    worker of a process pool or of dask raising it sends it back)."""
    assert haff.ConfigError.__module__ == "haff"
    error = pickle.loads(pickle.dumps(haff.ConfigError("system.particles: 0")))
    assert isinstance(error, haff.ConfigError) and str(error) == "system.particles: 0"


@pytest.mark.parametrize("module", MODULES)
def test_the_examples_run(module: str, tmp_path, monkeypatch):
    """The doctests of the module, in a scratch directory (examples write files); each
    docstring's examples well under a second (the first import of pandas or xarray, a
    one-time cost, aside)."""
    pytest.importorskip("pandas")
    monkeypatch.chdir(tmp_path)
    imported = __import__(module, fromlist=["_"])
    finder = doctest.DocTestFinder()
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    failures = []
    timings = []
    for test in finder.find(imported, module):
        if not test.examples:
            continue
        out: List[str] = []
        runner = doctest.DocTestRunner(optionflags=flags)
        clock = time.perf_counter()
        result = runner.run(test, out=out.append)
        timings.append((time.perf_counter() - clock, test.name))
        if result.failed:
            failures.append("".join(out))
    assert not failures, "\n".join(failures)
    print(sorted(timings, reverse=True)[:3])
