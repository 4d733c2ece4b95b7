"""The Python examples of the docs run: every ```python block of README.md and of the user
guide's pages (docs/guide/*.md, found when the tests are collected, so a new page is tested
without naming it here). The conventions are the docs' own (the guide's code blocks; the
TOML and shell blocks are run by crates/cli/tests/docs.rs):

- per page a scratch directory, the working directory of its blocks, holding the page's
  TOML blocks whose first line is ``# file: NAME`` (written as NAME, in page order) and a
  symlink ``docs`` to the repository's docs/ (files a page reads are named from the root);
- the page's ```python blocks run in order in one namespace, as one script would run them;
- ```python,no_run blocks (long runs, clusters) are only compiled.

A failure names the page and the line of the block (the blocks are compiled with the
page's path and line numbers, so a traceback points into the Markdown file).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import List

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: The first line of a TOML block that is also a file of the scratch directory.
FILE_LINE = re.compile(r"^#\s*file:\s*(\S+)\s*$")


@dataclass
class Block:
    info: str   # the info string, e.g. "python", "python,no_run", "toml,fragment"
    line: int   # the line of the block's first line of code (1-based)
    code: str

    @property
    def language(self) -> str:
        return self.info.split(",")[0].strip().lower()

    @property
    def options(self) -> List[str]:
        return [o.strip().lower() for o in self.info.split(",")[1:]]


def blocks(text: str) -> List[Block]:
    """The fenced code blocks of a Markdown text, in order, found as the TOML and shell
    test finds them (crates/cli/tests/docs.rs): a line starting with three backticks
    (after any indentation) opens a block and the next such line closes it; the body loses
    the opening fence's indentation (a block inside a list item)."""
    out: List[Block] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        stripped = lines[i].lstrip()
        if not stripped.startswith("```"):
            i += 1
            continue
        indent = lines[i][:len(lines[i]) - len(stripped)]
        info = stripped[3:].strip()
        body = []
        j = i + 1
        while j < len(lines) and not lines[j].lstrip().startswith("```"):
            line = lines[j]
            body.append(line[len(indent):] if line.startswith(indent) else line)
            j += 1
        out.append(Block(info, i + 2, "\n".join(body) + "\n"))
        i = j + 1
    return out


def pages() -> List[Path]:
    """README.md and the guide's pages."""
    return [ROOT / "README.md", *sorted((ROOT / "docs" / "guide").glob("*.md"))]


def with_python(page: Path) -> bool:
    return any(b.language == "python" for b in blocks(page.read_text(encoding="utf-8")))


def page_id(page: Path) -> str:
    return str(page.relative_to(ROOT))


def scratch(page: Path, directory: Path) -> None:
    """The page's scratch directory: its `# file:` TOML blocks and the docs symlink."""
    (directory / "docs").symlink_to(ROOT / "docs", target_is_directory=True)
    for block in blocks(page.read_text(encoding="utf-8")):
        first = block.code.split("\n", 1)[0]
        named = FILE_LINE.match(first)
        if block.language == "toml" and named:
            target = directory / named.group(1)
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(block.code, encoding="utf-8")


def compiled(page: Path, block: Block):
    """The block as code of the page's file at the block's lines (for tracebacks)."""
    return compile("\n" * (block.line - 1) + block.code, str(page), "exec")


def test_the_blocks_are_found():
    """The extraction itself: README's Python block and its line."""
    readme = blocks((ROOT / "README.md").read_text(encoding="utf-8"))
    python = [b for b in readme if b.language == "python"]
    assert python, "README.md has a python block"
    first = python[0]
    line = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()[first.line - 1]
    assert line == first.code.splitlines()[0]
    text = "x\n```toml,fragment\n# file: a.toml\n[run]\n```\n- item\n\n  ```python\n  x = 1\n  ```\n"
    found = blocks(text)
    assert [(b.info, b.line, b.code) for b in found] == [
        ("toml,fragment", 3, "# file: a.toml\n[run]\n"), ("python", 9, "x = 1\n")]


@pytest.mark.parametrize("page", [p for p in pages() if with_python(p)], ids=page_id)
def test_the_python_blocks_of_the_page_run(page: Path, tmp_path: Path, monkeypatch):
    pytest.importorskip("haff")
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")  # figures drawn, never shown
    scratch(page, tmp_path)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    where = page_id(page)
    for block in blocks(page.read_text(encoding="utf-8")):
        if block.language != "python":
            continue
        try:
            code = compiled(page, block)
        except SyntaxError as error:
            pytest.fail(f"{where}:{block.line}: the block does not compile: {error}")
        if "no_run" in block.options:
            continue
        try:
            exec(code, namespace)
        except Exception as error:
            raise AssertionError(
                f"{where}:{block.line}: the block raised {type(error).__name__}: {error}"
            ) from error
    import matplotlib.pyplot as plt
    plt.close("all")
