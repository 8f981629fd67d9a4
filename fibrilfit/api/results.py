"""What the Python API's functions return: typed results, each the command's JSON document
underneath (`.data`, `.to_json()`), with its headline numbers as attributes."""
from __future__ import annotations

import dataclasses
import json


@dataclasses.dataclass
class Result:
    """A command's result: `data` is its JSON document (the file the command line writes)."""

    data: dict

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.data, indent=indent, default=str)

    def __getitem__(self, key):
        return self.data[key]


@dataclasses.dataclass
class RunResult(Result):
    """One run (`run`; with restarts, the best seed run again here): the result JSON, as
    `fibrilfit run --json` writes it (docs/reference/schemas.md#result)."""

    paths: dict = dataclasses.field(default_factory=dict)
    problems: list = dataclasses.field(default_factory=list)

    @property
    def answer(self) -> str | None:
        return self.data.get("answer")

    @property
    def verdict(self) -> str | None:
        return self.data.get("verdict")

    @property
    def accommodated(self) -> bool | None:
        return self.data.get("accommodated")

    @property
    def restarts(self) -> dict | None:
        """The restarts' tally (P(fit), its interval, the best seed), or None without restarts."""
        return self.data.get("restarts")

    @property
    def p_fit(self) -> float | None:
        return (self.restarts or {}).get("p_fit")

    @property
    def ensemble(self) -> dict | None:
        """The ensemble block (`run --ensemble`), or None when none was asked for."""
        return self.data.get("ensemble")


@dataclasses.dataclass
class MinimalLinkerResult(Result):
    """The minimal-linker map: minimal_linker.json's document (one row per diameter)."""

    table: str = ""
    paths: dict = dataclasses.field(default_factory=dict)

    @property
    def rows(self) -> list[dict]:
        return self.data["rows"]

    def minimal(self, diameter: float | None = None) -> int | None:
        """The minimal linker found for `diameter` (the only one when a single diameter was
        mapped), None where none fitted up to the longest linker."""
        rows = self.rows if diameter is None else [
            r for r in self.rows if float(r["globule_diameter"]) == float(diameter)]
        if len(rows) != 1:
            raise KeyError(f"no single row for diameter {diameter}")
        return rows[0]["minimal_linker"]


@dataclasses.dataclass
class LargestFractionResult(Result):
    """The largest-fraction map: largest_fraction.json's document (one row per diameter and
    linker)."""

    table: str = ""
    paths: dict = dataclasses.field(default_factory=dict)

    @property
    def rows(self) -> list[dict]:
        return self.data["rows"]

    def largest(self, diameter: float | None = None, linker: int | None = None) -> float | None:
        """The largest fraction found at `diameter` and `linker` (either may be left out when
        only one was mapped), None where no layout was found at any count."""
        rows = [r for r in self.rows
                if (diameter is None or float(r["globule_diameter"]) == float(diameter))
                and (linker is None or int(r["linker"]) == int(linker))]
        if len(rows) != 1:
            raise KeyError(f"no single row for diameter {diameter}, linker {linker}")
        return rows[0]["largest_fraction"]


@dataclasses.dataclass
class ReportResult(Result):
    """The report: report.json's document (docs/reference/schemas.md#report) and its folder."""

    folder: str = ""

    @property
    def answer(self) -> str:
        return self.data["answer"]

    @property
    def p_fit(self) -> dict:
        return self.data["p_fit"]

    @property
    def minimal_linker(self) -> int | None:
        return self.data["minimal_linker"]["linker"]

    @property
    def bracket(self) -> dict | None:
        return self.data.get("bracket")

    @property
    def html(self) -> str:
        return f"{self.folder}/{self.data['files']['html']}"


@dataclasses.dataclass
class SweepResult(Result):
    """A sweep: the grid's rows (summary.csv's, as dicts), the gates, the exit code the
    command line gives (0, or 1 when a requirement failed)."""

    exit_code: int = 0


@dataclasses.dataclass
class InspectResult(Result):
    """`inspect`: the measurements (as `inspect --json` writes them) and the printed text."""

    text: str = ""


@dataclasses.dataclass
class JobScript(Result):
    """With show_job_script: the SLURM batch script one job would run; nothing was run."""

    text: str = ""
