"""The macros of docs/benchmarks.md's tools sections (reading structures, protofilaments, the
movie, search costs, SLURM sweeps and lost jobs, `make validate` from a fresh clone; loaded by
docs/hooks/page_numbers.py): their tables as the page prints them, from the dated files under
docs/data/bench/ (inspect_*, protofilaments_*, movie_*, searchcost_*, slurm_*, freshvalidate_*),
each row with its date, commit, MODEL_VERSION, bpy and command. A file is named by its stem
(`"slurm_cluster"` for docs/data/bench/slurm_cluster.csv).

- `tools_said(name, key, field="value")`: one cell, of the one row whose `key` column is `key`,
  as the file writes it (the prose's single numbers);
- `tools_file(name)`: the file's path under docs/data/, for `rows_table` (macros_model_a.py);
- `tools_inspect(key)`: one inspect timing as "1.02 s [0.90, 1.06]" (median [min, max]);
- `tools_protofilaments_table()`: the 100 × 2 against 100 × 1 table;
- `tools_lost_jobs_table()`: the `make test-cluster` runs of "Losing every job".

Every cell is printed as the file writes it ("0.90" stays "0.90"); a missing key fails the page.
"""
from __future__ import annotations

import csv


def macros(numbers) -> dict:
    def tools_rows(path: str) -> list[dict]:
        """A CSV under docs/data/ as its text (numbers.data checks the path and that it exists)."""
        numbers.data(path)
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def tools_file(name: str) -> str:
        path = f"bench/{name}.csv"
        numbers.data(path)  # a file that exists
        return path

    def tools_row(path: str, column: str, key: str) -> dict:
        found = [r for r in tools_rows(path) if r[column] == key]
        if len(found) != 1:
            raise KeyError(f"{path}: {len(found)} rows with {column} {key!r}")
        return found[0]

    def tools_said(name: str, key: str, field: str = "value") -> str:
        row = tools_row(tools_file(name), "key", key)
        if field not in row:
            raise KeyError(f"{tools_file(name)}: no column {field!r}")
        return row[field]

    def tools_inspect(key: str) -> str:
        r = tools_row("bench/inspect_times.csv", "key", key)
        return f"{r['seconds']} s [{r['min_s']}, {r['max_s']}]"

    def tools_protofilaments_table() -> str:
        lines = ["| model | objects | build + bake, wall, median | CPU per round | vs 100 × 1, CPU (median) |",
                 "|---|---|---|---|---|"]
        for r in tools_rows("bench/protofilaments_bake.csv"):
            ratio = r["cpu_ratio"]
            if r["wall_ratio"]:
                ratio = f"{ratio}x (wall {r['wall_ratio']}x)"
            if r["key"] == "k2":  # the pair the target is about
                ratio = ratio.replace(f"{r['cpu_ratio']}x", f"**{r['cpu_ratio']}x**", 1)
            lines.append(f"| {r['model']} | {r['objects']} | {r['wall_median_s']} s "
                         f"| {r['cpu_per_round_s']} s | {ratio} |")
        return "\n".join(lines)

    def tools_lost_jobs_table() -> str:
        lines = ["| run | what | result | wall | CPU of make and pytest (user + sys; the jobs' "
                 "processes are SLURM's) |", "|---|---|---|---|---|"]
        for r in tools_rows("bench/slurm_lost_jobs.csv"):
            wall = f"{r['wall_s']} s" + (f" (tests {r['tests_s']} s)" if r["tests_s"] else "")
            lines.append(f"| {r['run']} | {r['what']} | {r['result']} | {wall} | {r['cpu_s']} s |")
        return "\n".join(lines)

    return {"tools_said": tools_said, "tools_file": tools_file, "tools_inspect": tools_inspect, "tools_protofilaments_table": tools_protofilaments_table,
            "tools_lost_jobs_table": tools_lost_jobs_table}
