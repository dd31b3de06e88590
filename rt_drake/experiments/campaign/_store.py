"""The results database of a campaign: one SQLite file, one row per rollout.

Tables (SQLite, WAL journal; only the driver process writes):

- ``meta(key, value)``: ``schema_version``, ``content_hash`` (the campaign's,
  see :mod:`._definition`), ``campaign_file``, ``campaign`` (its canonical
  JSON), ``total_rows``, ``created_at``.
- ``rollouts``: primary key ``(object, cup, seed, trial, variant)``; then
  ``status`` (``ok``, ``infeasible``, ``error``, ``crashed``),
  ``duration_s`` (the retimed MOVE at speed 1), ``speed``, ``success``
  (0/1), ``slip_translation_mm``, ``slip_rotation_deg``, ``critical_speed``,
  ``plan_s``, ``simulate_s``, ``wall_s`` (wall times in the worker),
  ``cpu_s`` (the task's CPU time in its worker),
  ``error`` (``TypeName: message``), ``detail`` (JSON), ``attempts``,
  ``worker`` (``host:pid``), ``code_version``, ``finished_at`` (UTC ISO).

Each row is committed in its own transaction as soon as it arrives, so an
interrupted campaign keeps every finished row and a rerun computes only the
missing ones. A database holds one campaign: opening it with another
content hash is a :class:`CampaignMismatchError`.
"""

from __future__ import annotations

import datetime
import json
import sqlite3
from pathlib import Path
from types import TracebackType

from rt_drake.experiments.campaign._campaign_errors import (
    CampaignError,
    CampaignMismatchError,
)
from rt_drake.experiments.campaign._definition import Campaign
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowKey,
    Status,
    Variant,
)

#: Bump when the tables change meaning.
SCHEMA_VERSION = 1

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS rollouts (
    object TEXT NOT NULL,
    cup TEXT NOT NULL,
    seed INTEGER NOT NULL,
    trial INTEGER NOT NULL,
    variant TEXT NOT NULL,
    status TEXT NOT NULL
        CHECK (status IN ('ok', 'infeasible', 'error', 'crashed')),
    duration_s REAL,
    speed REAL,
    success INTEGER,
    slip_translation_mm REAL,
    slip_rotation_deg REAL,
    critical_speed REAL,
    plan_s REAL,
    simulate_s REAL,
    wall_s REAL,
    cpu_s REAL,
    error TEXT,
    detail TEXT NOT NULL,
    attempts INTEGER NOT NULL,
    worker TEXT NOT NULL,
    code_version TEXT NOT NULL,
    finished_at TEXT NOT NULL,
    PRIMARY KEY (object, cup, seed, trial, variant)
);
"""

#: The columns of ``rollouts``, in order.
COLUMNS = (
    "object",
    "cup",
    "seed",
    "trial",
    "variant",
    "status",
    "duration_s",
    "speed",
    "success",
    "slip_translation_mm",
    "slip_rotation_deg",
    "critical_speed",
    "plan_s",
    "simulate_s",
    "wall_s",
    "cpu_s",
    "error",
    "detail",
    "attempts",
    "worker",
    "code_version",
    "finished_at",
)


def connect(path: Path, readonly: bool = False) -> sqlite3.Connection:
    """A connection to the database at ``path`` (rows as ``sqlite3.Row``).

    Raises:
        CampaignError: the file is not an SQLite database (or, read-only,
            does not exist).
    """
    if readonly and not path.is_file():
        raise CampaignError(f"{path}: results database does not exist")
    uri = f"file:{path.resolve()}?mode=ro" if readonly else str(path)
    try:
        connection = sqlite3.connect(uri, uri=readonly, timeout=30.0)
        connection.row_factory = sqlite3.Row
        if not readonly:
            connection.execute("PRAGMA journal_mode=WAL")
        connection.execute("SELECT name FROM sqlite_master LIMIT 1").fetchall()
    except sqlite3.DatabaseError as error:
        raise CampaignError(f"{path}: not a campaign database ({error})") from None
    return connection


def read_meta(connection: sqlite3.Connection, path: Path) -> dict[str, str]:
    """The ``meta`` table; CampaignError if the file has none."""
    try:
        rows = connection.execute("SELECT key, value FROM meta").fetchall()
    except sqlite3.DatabaseError:
        raise CampaignError(
            f"{path}: not a campaign database (no meta table)"
        ) from None
    return {row["key"]: row["value"] for row in rows}


class ResultStore:
    """The results database of one campaign, open for writing.

    Use as a context manager; see the module docstring for the tables.
    """

    def __init__(self, path: str | Path, campaign: Campaign) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._connection = connect(self.path)
        with self._connection:
            self._connection.executescript(_SCHEMA)
        self._claim(campaign)

    def _claim(self, campaign: Campaign) -> None:
        """Record the campaign in a new database, or check it is the one held."""
        meta = read_meta(self._connection, self.path)
        held = meta.get("content_hash")
        if held is None:
            values = {
                "schema_version": str(SCHEMA_VERSION),
                "content_hash": campaign.content_hash,
                "campaign_file": str(campaign.path),
                "campaign": campaign.canonical,
                "total_rows": str(len(campaign.row_keys())),
                "created_at": _now(),
            }
            with self._connection:
                self._connection.executemany(
                    "INSERT INTO meta VALUES (?, ?)", values.items()
                )
        elif held != campaign.content_hash:
            raise CampaignMismatchError(
                f"{self.path}: holds the results of another campaign "
                f"({meta.get('campaign_file')}, content hash {held[:12]}), not "
                f"{campaign.path} (content hash {campaign.content_hash[:12]}); "
                "write this campaign to another database"
            )
        elif meta.get("schema_version") != str(SCHEMA_VERSION):
            raise CampaignError(
                f"{self.path}: database schema version "
                f"{meta.get('schema_version')}, this rt-drake writes {SCHEMA_VERSION}"
            )

    def finished(self) -> set[RowKey]:
        """The rows already in the database."""
        rows = self._connection.execute(
            "SELECT object, cup, seed, trial, variant FROM rollouts"
        ).fetchall()
        return {
            RowKey(r["object"], r["cup"], r["seed"], r["trial"], Variant(r["variant"]))
            for r in rows
        }

    def count(self, *statuses: Status) -> int:
        """How many rows have one of ``statuses``."""
        marks = ", ".join("?" * len(statuses))
        (count,) = self._connection.execute(
            f"SELECT COUNT(*) FROM rollouts WHERE status IN ({marks})",
            [s.value for s in statuses],
        ).fetchone()
        return int(count)

    def forget(self, *statuses: Status) -> int:
        """Delete the rows with one of ``statuses`` (to compute them again)."""
        marks = ", ".join("?" * len(statuses))
        with self._connection:
            cursor = self._connection.execute(
                f"DELETE FROM rollouts WHERE status IN ({marks})",
                [s.value for s in statuses],
            )
        return cursor.rowcount

    def add(self, outcome: Outcome) -> None:
        """Commit one row (a row already there is kept, not duplicated)."""
        key, result = outcome.key, outcome.result
        values = (
            key.object,
            key.cup,
            key.seed,
            key.trial,
            key.variant.value,
            result.status.value,
            result.duration_s,
            result.speed,
            None if result.success is None else int(result.success),
            result.slip_translation_mm,
            result.slip_rotation_deg,
            result.critical_speed,
            result.plan_s,
            result.simulate_s,
            outcome.wall_s,
            outcome.cpu_s,
            result.error,
            json.dumps(result.detail, sort_keys=True),
            outcome.attempts,
            outcome.worker,
            outcome.code_version,
            _now(),
        )
        marks = ", ".join("?" * len(COLUMNS))
        with self._connection:
            self._connection.execute(
                f"INSERT OR IGNORE INTO rollouts ({', '.join(COLUMNS)}) "
                f"VALUES ({marks})",
                values,
            )

    def close(self) -> None:
        """Close the connection (every row is already committed)."""
        self._connection.close()

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()


def _now() -> str:
    return datetime.datetime.now(datetime.UTC).isoformat(timespec="milliseconds")


__all__ = ["COLUMNS", "SCHEMA_VERSION", "ResultStore", "connect", "read_meta"]
