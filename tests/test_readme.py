"""The Python examples of README.md and the docs run as a user would paste them.

Each page's ```python blocks run in order, in one namespace, in a fresh
directory; a block preceded by the line `<!-- test: skip -->` is not run.
Each page must print what its text promises.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SKIP = "<!-- test: skip -->"
BLOCK = re.compile(r"^(<!-- test: skip -->\n)?```python\n(.*?)^```", re.S | re.M)

#: Page -> what its examples print (a line or part of one).
PRINTS = {
    "README.md": ["0.705 s holding the notebook, 0.548 s without"],
    "docs/quickstart.md": ["with the grasp", "object mass must be > 0 kg"],
    "docs/guides/own-robot.md": ["min margin"],
    "docs/guides/multi-cup-tools.md": ["one cup:", "W_T: 436 rows", "two cups:"],
    "docs/guides/bellows-load-sharing.md": [
        "cup 0 carries [0.    0.    0.033 0.    1.957 0.   ]",
        "1662 rows, holds: False",
        "564 rows, holds: True",
    ],
    "docs/guides/robust-retiming.md": ["holds every object", "worst excess over"],
    "docs/guides/protective-stops.md": [
        "grasp-aware stop within every limit: True",
        "joint brake grasp margin: -",
        "MOVE and stop within every limit, jerk included: True",
        "table: 9 stops; trip at 0.234 s -> stop at 0.300 s",
    ],
    "docs/guides/cycle-floor.md": ["whetstone_box 1.332 s of motion at least"],
    "docs/reference/cli.md": ["True", ", 6) scene"],
    "docs/guides/jerk-limits.md": [
        "s with jerk limits",
        "jerk:",
        "holds: True",
        "s refined",
    ],
    "docs/guides/export.md": ["points to", "joints shoulder_pan_joint", "end: True"],
}


def python_blocks(text: str) -> list[str]:
    """The page's ```python blocks not marked to skip, in order."""
    return [code for skip, code in BLOCK.findall(text) if not skip]


def pages_with_examples() -> list[str]:
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    return [
        str(page.relative_to(ROOT)) for page in pages if python_blocks(page.read_text())
    ]


def test_every_page_with_examples_says_what_they_print():
    # A page whose examples run unchecked, or a check of a page that lost
    # its examples (a broken pattern would find none), fails here.
    assert set(pages_with_examples()) == set(PRINTS)


def test_a_marked_block_is_skipped():
    text = f"```python\nrun()\n```\n\n{SKIP}\n```python\nskip()\n```\n"
    assert python_blocks(text) == ["run()\n"]


@pytest.mark.slow
@pytest.mark.parametrize("page", sorted(PRINTS))
def test_every_python_block_runs(page, tmp_path, monkeypatch, capsys):
    blocks = python_blocks((ROOT / page).read_text())
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__docs__"}
    for index, block in enumerate(blocks):
        try:
            exec(compile(block, f"{page} python block {index}", "exec"), namespace)
        except Exception as error:  # name the block that failed
            raise AssertionError(f"{page} python block {index} failed") from error
    printed = capsys.readouterr().out
    for text in PRINTS[page]:
        assert text in printed, f"{page} should print {text!r}; printed:\n{printed}"
    if page == "docs/quickstart.md":  # its trajectory file, read back by a block
        assert (tmp_path / "move.npz").is_file()
