"""Progress: one plain line per step off a terminal, a redrawn bar on one."""

from __future__ import annotations

import io

from rt_drake.cli._progress import Progress


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_plain_lines_when_not_a_terminal():
    out = io.StringIO()
    progress = Progress(
        "rt-drake experiment transport", 4, "trial", eta=True, stream=out
    )
    for done in range(5):
        progress.step(done, "trials done")
    progress.close()
    lines = out.getvalue().splitlines()
    assert len(lines) == 5
    assert lines[0] == "rt-drake experiment transport: 0/4 trials done"
    assert lines[2].startswith("rt-drake experiment transport: 2/4 trials done (")
    assert "ETA" in lines[2] and "\r" not in out.getvalue()


def test_a_bar_on_a_terminal():
    out = _Terminal()
    progress = Progress("rt-drake run", 20, "phase", stream=out)
    progress.step(3, "object 1/4 whetstone_box: MOVE")
    progress.close()
    text = out.getvalue()
    assert "\r" in text and "whetstone_box: MOVE" in text
    assert "rt-drake run: 3/20" not in text  # no plain lines on a terminal
