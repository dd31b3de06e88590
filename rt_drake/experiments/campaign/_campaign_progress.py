"""Progress of a whole campaign: done / total, failures, rate and ETA.

On a terminal, a tqdm bar; otherwise (a log file, CI, a batch system) plain
lines, at most one per ``interval`` seconds and one at the end:
``campaign: 12/48 rows (25%), 1 failed, 3.1 rows/min, ETA 11m36s``. The
rate and ETA count only rows computed in this run, not those resumed.
"""

from __future__ import annotations

import time
from typing import IO, Any


def _duration(seconds: float) -> str:
    seconds = int(round(seconds))
    hours, rest = divmod(seconds, 3600)
    minutes, seconds = divmod(rest, 60)
    if hours:
        return f"{hours}h{minutes:02d}m"
    return f"{minutes}m{seconds:02d}s" if minutes else f"{seconds}s"


class Progress:
    """Report a campaign's progress to ``stream``.

    Args:
        total: Rows of the campaign.
        done: Rows already in the database.
        failed: How many of those failed (infeasible, error, crashed).
        stream: Where to write (a TTY gets a tqdm bar).
        interval: Seconds between plain lines.
    """

    def __init__(
        self,
        total: int,
        done: int,
        failed: int,
        stream: IO[str],
        interval: float = 30.0,
    ) -> None:
        self.total, self.done, self.failed = total, done, failed
        self._resumed = done
        self._stream = stream
        self._interval = interval
        self._start = time.monotonic()
        self._last_line = -float("inf")
        self._bar: Any = None
        if stream.isatty():
            from tqdm import tqdm

            self._bar = tqdm(
                total=total, initial=done, file=stream, unit="row", desc="campaign"
            )
            self._bar.set_postfix(failed=failed)

    def line(self) -> str:
        """``campaign: done/total rows (pct), failed, rate, ETA``."""
        percent = 100.0 * self.done / self.total if self.total else 100.0
        text = f"campaign: {self.done}/{self.total} rows ({percent:.0f}%), "
        text += f"{self.failed} failed"
        computed = self.done - self._resumed
        elapsed = time.monotonic() - self._start
        if computed and elapsed > 0:
            rate = computed / elapsed
            text += f", {60.0 * rate:.1f} rows/min"
            if self.done < self.total:
                text += f", ETA {_duration((self.total - self.done) / rate)}"
        return text

    def advance(self, failed: bool) -> None:
        """Count one more finished row."""
        self.done += 1
        self.failed += int(failed)
        if self._bar is not None:
            self._bar.update(1)
            self._bar.set_postfix(failed=self.failed)
            return
        now = time.monotonic()
        if now - self._last_line >= self._interval or self.done == self.total:
            self._last_line = now
            print(self.line(), file=self._stream, flush=True)

    def close(self) -> None:
        """End the bar (plain output needs no closing)."""
        if self._bar is not None:
            self._bar.close()


__all__ = ["Progress"]
