"""Progress of long commands: a tqdm bar on a terminal, plain lines otherwise.

On a TTY the bar redraws in place (with tqdm's rate and ETA); elsewhere (CI
logs, pipes) each step is one line, ``rt-drake run: object 2/4 notebook:
MOVE``, so logs stay readable. Both go to stderr, the table to stdout.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO


class Progress:
    """Steps done out of ``total``, each with a short text.

    Args:
        prefix: what is running, e.g. ``"rt-drake run"``.
        total: number of steps.
        unit: what a step is (``"phase"``, ``"trial"``).
        eta: plain lines also say the estimated time left (from the mean
            time per step so far).
        stream: where to write (default stderr).
    """

    def __init__(
        self,
        prefix: str,
        total: int,
        unit: str,
        eta: bool = False,
        stream: TextIO | None = None,
    ) -> None:
        self._prefix = prefix
        self._total = total
        self._eta = eta
        self._stream = stream or sys.stderr
        self._start = time.perf_counter()
        self._done = 0
        self._bar = None
        if self._stream.isatty():
            from tqdm import tqdm

            self._bar = tqdm(
                total=total, unit=unit, file=self._stream, desc=prefix, leave=False
            )

    def step(self, done: int, text: str) -> None:
        """``done`` steps of ``total`` are finished; ``text`` says what runs now."""
        if self._bar is not None:
            self._bar.update(done - self._done)
            self._bar.set_postfix_str(text)
        else:
            line = f"{self._prefix}: {done}/{self._total} {text}"
            if self._eta and done > 0:
                elapsed = time.perf_counter() - self._start
                left = elapsed / done * (self._total - done)
                line += f" (elapsed {elapsed:.0f} s, ETA {left:.0f} s)"
            print(line, file=self._stream, flush=True)
        self._done = done

    def close(self) -> None:
        """Remove the bar (plain lines need nothing)."""
        if self._bar is not None:
            self._bar.close()
