"""The Python snippets of the README and the user's guide run as written, so that they stay
true (the command-line lines of the same pages are run by `tests/doc_commands.rs`).

Every ```python block of README.md and docs/*.md is executed, the blocks of one page one after
another in one namespace, in a directory of its own where the repository's `scenes/` and
`tests/` are linked and `roadmaps/` copied, so that files the snippets write stay there. A
block that needs what the repository does not ship (another planner's path) says so in a
`# needs ...` comment and is only compiled."""

import re
import shutil
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))


def python_blocks(page):
    """(first line number, code) of each ```python block of `page`."""
    blocks, code, start = [], None, 0
    for n, line in enumerate(page.read_text().splitlines(), 1):
        fence = re.match(r"\s*```(\S*)", line)
        if fence and code is None:
            # a list collects a python block; False skips any other block
            code = [] if fence.group(1) == "python" else False
            start = n + 1
        elif fence:
            if code is not False:
                blocks.append((start, textwrap.dedent("\n".join(code))))
            code = None
        elif isinstance(code, list):
            code.append(line)
    return blocks


@pytest.mark.parametrize("page", [p for p in PAGES if python_blocks(p)], ids=lambda p: p.name)
def test_the_snippets_of_a_page_run(page, tmp_path, monkeypatch):
    for linked in ["scenes", "tests"]:
        (tmp_path / linked).symlink_to(ROOT / linked)
    shutil.copytree(ROOT / "roadmaps", tmp_path / "roadmaps")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for start, code in python_blocks(page):
        where = f"{page.relative_to(ROOT)}:{start}"
        compiled = compile(code, where, "exec")
        if re.search(r"#\s*needs\b", code):
            continue
        exec(compiled, namespace)


def test_the_reader_finds_the_readme_snippet():
    blocks = python_blocks(ROOT / "README.md")
    assert blocks and "import viaroad" in blocks[0][1]
