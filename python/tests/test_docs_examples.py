"""Every Python block of the README and docs/*.md runs as written (a newcomer pastes
them): each in a fresh folder holding a copy of examples/ (the files they read), so
that what they write stays there."""

import os
import pathlib
import re
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def blocks():
    for page in PAGES:
        text = page.read_text()
        for k, m in enumerate(re.finditer(r"```python\n(.*?)```", text, re.S)):
            yield pytest.param(m.group(1), id=f"{page.name}-{k}")


@pytest.mark.parametrize("code", list(blocks()))
@pytest.mark.filterwarnings("ignore:units")
def test_a_documented_block_runs_as_written(code, tmp_path, monkeypatch):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "<documented block>", "exec"), {"__name__": "__doc_block__"})


def test_the_readme_has_python_blocks():
    assert len(list(blocks())) >= 2
