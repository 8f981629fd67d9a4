"""docs/benchmarks.md's three targets (from `#answer-in-a-minute` to `#validate-walks-47`): the
record's own measurements, each from the file that holds it (loaded by docs/hooks/page_numbers.py).

The files, under docs/data/ (each row with its date, commit, MODEL_VERSION, bpy and command):
- bench/targets_said.csv: the numbers the section's prose quotes that no other file holds, one
  row a number by `key`, each with what it is (`targets_said(KEY)`); a number another section
  measured is quoted from that section's file (`targets_from`);
- bench/targets_report_rounds.csv: the report side by side, three rounds a side;
- bench/targets_validate_v6_rounds.csv and bench/targets_validate_v6_cases.csv: `make validate`
  at MODEL_VERSION 6 end to end, its rounds and where round 1's time went;
- bench/targets_validate_morning.csv: the morning's attempts at MODEL_VERSION 7;
- validate_timings.csv (written before this file): `make validate` and `make validate-walks` at
  MODEL_VERSION 8, a row an attempt.

The macros:
- `targets_said(key)`: a number of bench/targets_said.csv as the file writes it ("1,199");
- `targets_from(path, key, field)`: a number another section's file holds (the report's stages
  and side by side, the map's walls and floors, `make validate`'s first fresh run), quoted from
  there; `targets_whole(value)` rounds it as the page does, `targets_extremes(path, column,
  where)` gives the least and largest of some rows, `targets_seconds(text)` reads "24 min 6 s"
  as seconds;
- `targets_min_s(seconds)`: "38 min 18 s", as the page writes a wall time in minutes;
- `targets_rounds_table(prefix, columns)`: the report's rounds (rows whose key starts so), the
  median checked against the rounds;
- `targets_validate_v6_table()`, `targets_validate_v6_cases_table()`, `targets_case(case)`,
  `targets_validate_v6_median()`: `make validate` at MODEL_VERSION 6;
- `targets_morning_table()`, `targets_morning(attempt)`: the attempts of 2026-11-27's morning;
- `targets_timing(attempt)`: a row of validate_timings.csv with its CPU time added up, in the
  ways the page writes it.
Every lookup fails loudly on a key the file does not hold. Standard library only."""
from __future__ import annotations

import csv
import statistics


def macros(numbers) -> dict:
    def rows(path: str) -> list[dict]:
        """A CSV under docs/data/ with its cells as the file writes them."""
        numbers.data(path)  # the same checks: under docs/data/, a file that exists
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def one(path: str, column: str, value: str) -> dict:
        found = [r for r in rows(path) if r[column] == str(value)]
        if len(found) != 1:
            raise KeyError(f"{path}: {len(found)} rows with {column} = {value!r}, not one")
        return found[0]

    def seconds(text: str) -> float:
        return float(text.replace(",", ""))

    def targets_said(key: str) -> str:
        """The `value` of bench/targets_said.csv's row `key`, as the file writes it."""
        return one("bench/targets_said.csv", "key", key)["value"]

    def targets_from(name: str, key: str, field: str = "value", by: str = "key") -> str:
        """The `field` of the one row whose `by` column is `key` in another file under
        docs/data/, as the file writes it: a measurement another section holds is quoted from
        there, not copied. `name` is a path under docs/data/ ("notebook/x.csv") or the stem of
        a file of docs/data/bench/ ("mapcost_walls": a path "bench/..." in a page would read
        as the repository's bench/ folder)."""
        return one(name if name.endswith(".csv") else f"bench/{name}.csv", by, key)[field]

    def targets_whole(value, thousands: bool = False) -> str:
        """A number rounded to a whole one, as the page writes it ("174" for 174.1; "1,199")."""
        return f"{seconds(str(value)):,.0f}" if thousands else f"{seconds(str(value)):.0f}"

    def targets_extremes(path: str, column: str, where: dict, unnoted: str = "") -> list[str]:
        """The least and the largest of `column` over the rows of a file whose cells match
        `where` ({column: [values]}), rows with a note in column `unnoted` left out."""
        found = [r for r in rows(path)
                 if all(r[k] in [str(v) for v in vs] for k, vs in where.items())
                 and not (unnoted and r[unnoted])]
        if not found:
            raise KeyError(f"{path}: no row with {where}")
        values = sorted((r[column] for r in found), key=seconds)
        return [values[0], values[-1]]

    def targets_seconds(text: str) -> float:
        """A time as seconds, from "1,446", "1446.0" or "24 min 6 s"."""
        text = str(text).strip()
        if " min" in text:
            minutes, _, rest = text.partition(" min")
            rest = rest.strip().removesuffix("s").strip()
            return int(minutes) * 60 + (float(rest) if rest else 0)
        return seconds(text)

    def targets_min_s(value) -> str:
        """A wall time in seconds as minutes and seconds, "38 min 18 s" (2297.8 s)."""
        s = round(seconds(str(value)))
        return f"{s // 60} min {s % 60} s"

    def targets_minutes(value, cores: int = 1, floor: bool = False) -> str:
        """Seconds as whole minutes, rounded ("38") or, `floor`, the whole minutes it lasted at
        least ("25" for 1539 s); on `cores` cores kept busy, the CPU time's."""
        minutes = seconds(str(value)) / 60 / cores
        return str(int(minutes)) if floor else f"{minutes:.0f}"

    def checked_median(r: dict) -> str:
        """The row's median, which must be the median of its three rounds."""
        rounds = [seconds(r[f"round_{i}_s"]) for i in (1, 2, 3)]
        if statistics.median(rounds) != seconds(r["median_s"]):
            raise ValueError(f"{r['key']}: median {r['median_s']} is not that of {rounds}")
        return r["median_s"]

    def targets_rounds_table(prefix: str, columns: dict) -> str:
        """bench/targets_report_rounds.csv's rows whose key starts with `prefix` as a Markdown
        table: `columns` maps each header to a template over the row (str.format)."""
        found = [r for r in rows("bench/targets_report_rounds.csv") if r["key"].startswith(prefix)]
        if not found:
            raise KeyError(f"bench/targets_report_rounds.csv: no key starting {prefix!r}")
        lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
        for r in found:
            r = {**r, "median_s": checked_median(r)}
            lines.append("| " + " | ".join(spec.format(**r) for spec in columns.values()) + " |")
        return "\n".join(lines)

    def targets_median_of(*values):
        """The median of an odd number of values, as given ("1221.7" of three rounds)."""
        if len(values) % 2 != 1:
            raise ValueError(f"targets_median_of: an odd number of values, not {len(values)}")
        return sorted(values, key=lambda v: seconds(str(v)))[len(values) // 2]

    def targets_report(key: str) -> dict:
        """One side of the report's rounds (its median checked)."""
        r = one("bench/targets_report_rounds.csv", "key", key)
        return {**r, "median_s": checked_median(r)}

    def v6_rounds() -> list[dict]:
        return rows("bench/targets_validate_v6_rounds.csv")

    def targets_validate_v6_median() -> str:
        """The median of `make validate`'s rounds at MODEL_VERSION 6, as the file writes it."""
        walls = sorted((r["wall_s"] for r in v6_rounds()), key=seconds)
        return walls[len(walls) // 2]

    def targets_validate_v6_round(number: int) -> dict:
        return one("bench/targets_validate_v6_rounds.csv", "round", str(number))

    def targets_validate_v6_table(note: str = "") -> str:
        """The rounds of `make validate` at MODEL_VERSION 6 and their median."""
        found = v6_rounds()
        lines = ["| round | when (UTC) | wall | peak memory (tree) | load (1 min) before → after "
                 "| beside it |", "|---|---|---|---|---|---|"]
        for r in found:
            lines.append(f"| {r['round']} | {r['when_utc']} | {r['wall_s']} s "
                         f"({targets_min_s(r['wall_s'])}) | {r['peak_mib']} MiB | "
                         f"{r['load_before']} → {r['load_after']} | {r['beside']} |")
        median = targets_validate_v6_median()
        before = sorted((r["load_before"] for r in found), key=float)[0]
        after = sorted((r["load_after"] for r in found), key=float)[-1]
        # the median row's memory is the largest of the rounds, as the page first wrote it
        peak = max(int(r["peak_mib"]) for r in found)
        lines.append(f"| **median of {len(found)}** | | **{median} s ({targets_min_s(median)})** "
                     f"| {peak} MiB | {before}–{after} | |")
        return "\n".join(lines)

    def targets_validate_v6_cases_table() -> str:
        """Where round 1's worker-seconds went, a row a case."""
        lines = ["| case | runs at the real linker | worker-s | walk runs | worker-s | frames | share |",
                 "|---|---|---|---|---|---|---|"]
        for r in rows("bench/targets_validate_v6_cases.csv"):
            lines.append(f"| `{r['case']}` | {r['real_runs']} | {r['real_worker_s']} | "
                         f"{r['walk_runs']} | {r['walk_worker_s']} | {r['frames']} | "
                         f"{r['share_pct']} % |")
        return "\n".join(lines)

    def targets_case(case: str) -> dict:
        return one("bench/targets_validate_v6_cases.csv", "case", case)

    def targets_morning(attempt: int) -> dict:
        """An attempt of 2026-11-27's morning, with its wall time ("32 min 13 s"), its CPU time
        rounded ("1,600") and in minutes on two cores kept busy ("13.3")."""
        r = dict(one("bench/targets_validate_morning.csv", "attempt", str(attempt)))
        r["wall_min_s"] = targets_min_s(r["wall_s"])
        r["wall_whole_s"] = f"{seconds(r['wall_s']):,.0f}"
        if r["cpu_total_s"]:
            cpu = seconds(r["cpu_total_s"])
            r["cpu_rounded"] = f"{cpu:,.0f}"
            r["cpu_two_cores_min"] = f"{cpu / 120:.1f}"
        return r

    def targets_morning_table() -> str:
        lines = ["| attempt | when (UTC) | what ran | wall | CPU, user + system | load (1 min) "
                 "| runs done |", "|---|---|---|---|---|---|---|"]
        for r in rows("bench/targets_validate_morning.csv"):
            m = targets_morning(int(r["attempt"]))
            wall = f"{r['wall_s']} s"
            if seconds(r["wall_s"]) >= 120 and not r["wall_note"]:
                wall += f" ({m['wall_min_s']})"
            if r["wall_note"]:
                wall += f", {r['wall_note']}"
            cpu = (f"{r['cpu_user_s']} + {r['cpu_system_s']} = {r['cpu_total_s']} s"
                   if r["cpu_total_s"] else r["cpu_note"])
            if abs(seconds(r["cpu_user_s"] or "0") + seconds(r["cpu_system_s"] or "0")
                   - seconds(r["cpu_total_s"] or "0")) > 0.51:
                raise ValueError(f"attempt {r['attempt']}: user + system is not {r['cpu_total_s']}")
            if r["bold"]:
                wall, cpu = f"**{wall}**", f"**{cpu}**"
            lines.append(f"| {r['attempt']} | {r['when_utc']} | {r['what']} | {wall} | {cpu} | "
                         f"{r['load']} | {r['runs_done']} |")
        return "\n".join(lines)

    def targets_timing(attempt: str) -> dict:
        """A row of docs/data/validate_timings.csv (`attempt` A, B or walks) with: `wall` as the
        file writes it ("16 min 51 s"), `minutes` its wall in whole minutes, `cpu` user + system
        ("1,755"), `user` and `system` rounded, `cpu_min` the CPU time in minutes ("29") and
        `two_cores_min` on two cores kept busy ("14.6")."""
        r = dict(one("validate_timings.csv", "attempt", attempt))
        cpu = seconds(r["cpu_user_s"]) + seconds(r["cpu_system_s"])
        r.update(minutes=targets_minutes(r["wall_s"]), cpu=f"{cpu:,.0f}",
                 user=f"{seconds(r['cpu_user_s']):,.0f}", system=f"{seconds(r['cpu_system_s']):,.0f}",
                 cpu_s=cpu, cpu_min=f"{cpu / 60:.0f}", two_cores_min=f"{cpu / 120:.1f}")
        return r

    def targets_room(attempt: str, target_min: int) -> str:
        """The whole minutes between a target and an attempt's wall time ("3")."""
        return f"{target_min - seconds(targets_timing(attempt)['wall_s']) / 60:.0f}"

    def targets_together(*attempts: str) -> dict:
        """Several attempts' CPU time together: in CPU-minutes and on two cores kept busy."""
        cpu = sum(targets_timing(a)["cpu_s"] for a in attempts)
        return {"cpu_min": f"{cpu / 60:.0f}", "two_cores_min": f"{cpu / 120:.0f}"}

    return {name: fn for name, fn in locals().items() if name.startswith("targets_")}
