"""Every `--help` reads as plain text for a user.

No Sphinx markup, no private module paths, no issue numbers: the help a user
reads is not the code's docstring conventions nor the project's tracker.
"""

from __future__ import annotations

import argparse
import re
import shlex
from pathlib import Path

import pytest

from rt_drake.cli import build_parser, main

#: What a user should never read in --help, and why.
FORBIDDEN = {
    "``": "Sphinx double backticks",
    ":mod:": "a Sphinx role",
    ":func:": "a Sphinx role",
    ":class:": "a Sphinx role",
    "rt_drake.": "a module path",
}
ISSUE_NUMBER = re.compile(r"\bissue \d", re.IGNORECASE)


def command_paths(
    parser: argparse.ArgumentParser, path: tuple[str, ...] = ()
) -> list[tuple[str, ...]]:
    """Every (sub)command's words, the top-level command first."""
    paths = [path]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, subparser in action.choices.items():
                paths += command_paths(subparser, (*path, name))
    return paths


def problems(text: str) -> list[str]:
    """The forbidden pieces in `text`, whatever the line wrapping."""
    flat = " ".join(text.split())  # argparse may wrap "issue 13" across lines
    found = [f"{why}: {piece!r}" for piece, why in FORBIDDEN.items() if piece in flat]
    found += [f"an issue number: {m.group()!r}" for m in ISSUE_NUMBER.finditer(flat)]
    return found


COMMANDS = command_paths(build_parser())


def test_the_walk_reaches_every_subcommand():
    # Guards the test below against passing on an empty walk.
    assert {("run",), ("constraint",), ("plan",), ("retime",), ("show",)} <= set(
        COMMANDS
    )
    assert ("export",) in COMMANDS
    assert {("experiment", name) for name in ("transport", "cycle", "campaign")} <= (
        set(COMMANDS)
    )
    assert ("experiment", "report") in COMMANDS


@pytest.mark.parametrize(
    "text",
    [
        "``rt-drake run [SCENARIO]``: simulate",
        "see :mod:`rt_drake.cli._campaign_command`",
        "checked (``rt_drake.cli._output``: a directory)",
        "shape each MOVE for speed (issue\n   13)",
        "a :func:`retime` and a :class:`HeldObject`",
    ],
)
def test_the_check_catches_what_the_old_help_said(text):
    # Phrases the help text held before it was rewritten.
    assert problems(text)


def test_plain_text_passes_the_check():
    assert not problems("retime MOVE with joint limits only (objects may slip)")


@pytest.mark.parametrize("words", COMMANDS, ids=lambda w: " ".join(w) or "rt-drake")
def test_help_is_plain_text(words, capsys):
    assert main([*words, "--help"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("usage: rt-drake")
    assert not problems(text), f"rt-drake {' '.join(words)} --help: {problems(text)}"


# The command-line reference (docs/reference/cli.md): every flag of every
# command's parser has a row there, and each row's example parses and uses it.

CLI_REFERENCE = Path(__file__).resolve().parents[2] / "docs" / "reference" / "cli.md"
LEAVES = [words for words in COMMANDS if words and words != ("experiment",)]


def reference_section(words: tuple[str, ...]) -> str:
    """The text under `## rt-drake <words>`, up to the next section."""
    text = CLI_REFERENCE.read_text()
    start = text.index(f"\n## rt-drake {' '.join(words)}\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end >= 0 else len(text)]


def flag_rows(section: str) -> list[tuple[list[str], str]]:
    """(the flags or argument of the row, its example command) per table row."""
    rows = []
    for line in section.splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split(" | ")]
        if len(cells) == 3 and cells[0].startswith("`") and cells[2].startswith("`"):
            names = [name.strip("`").split()[0] for name in cells[0].split(", ")]
            rows.append((names, cells[2].strip("`")))
    return rows


def subparser(words: tuple[str, ...]) -> argparse.ArgumentParser:
    parser = build_parser()
    for word in words:
        action = next(
            a for a in parser._actions if isinstance(a, argparse._SubParsersAction)
        )
        parser = action.choices[word]
    return parser


@pytest.mark.parametrize("words", LEAVES, ids=" ".join)
def test_the_reference_has_a_row_per_flag(words):
    rows = flag_rows(reference_section(words))
    documented = {name for names, _ in rows for name in names}
    for action in subparser(words)._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        names = action.option_strings or [action.dest]
        assert set(names) <= documented, f"rt-drake {' '.join(words)}: {names}"


@pytest.mark.parametrize("words", LEAVES, ids=" ".join)
def test_each_example_parses_and_uses_its_flag(words):
    parser = build_parser()
    for names, example in flag_rows(reference_section(words)):
        argv = shlex.split(example)
        assert argv[: 1 + len(words)] == ["rt-drake", *words], example
        args = parser.parse_args(argv[1:])  # a usage error exits: the test fails
        assert args.run is not None
        flags = [name for name in names if name.startswith("-")]
        if flags:
            assert any(flag in argv for flag in flags), example
