"""docs/python.md runs: its ``python`` blocks are executed and its ``pycon`` blocks run as
doctests (the printed values checked), in order, in one namespace, from the repository root.
``py`` blocks are fragments and are skipped. Blocks that plot need matplotlib (the [plot]
extra): without it they are skipped and the test says so."""
import doctest
import importlib.util
import re

import pytest

BLOCK = re.compile(r"^```(\w+)\n(.*?)^```", re.S | re.M)


def blocks(text):
    for m in BLOCK.finditer(text):
        yield m.group(1), m.group(2), text.count("\n", 0, m.start()) + 2


def test_every_snippet_of_the_tutorial_runs(root, monkeypatch):
    monkeypatch.chdir(root)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    have_matplotlib = importlib.util.find_spec("matplotlib") is not None
    path = root / "docs" / "python.md"
    ns, ran, skipped = {"__name__": "docs_python"}, 0, []
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for lang, code, line in blocks(path.read_text()):
        if lang not in ("python", "pycon"):
            continue
        if "matplotlib" in code and not have_matplotlib:
            skipped.append(line)
            continue
        if lang == "python":
            exec(compile(code, f"{path}:{line}", "exec"), ns)
        else:
            test = doctest.DocTestParser().get_doctest(code, ns, f"docs/python.md:{line}", str(path), line - 1)
            result = runner.run(test, clear_globs=False)
            ns.update(test.globs)  # a DocTest works on a copy of the namespace
            assert result.failed == 0, f"docs/python.md, the block at line {line}: {result.failed} failed"
        ran += 1
    assert ran >= 6
    if skipped:
        pytest.skip(f"matplotlib not installed: the plotting block(s) at line(s) {skipped} did not run")
