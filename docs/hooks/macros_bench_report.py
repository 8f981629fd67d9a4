"""The macros of docs/benchmarks.md from "The report side by side" to the page's end (the report,
the stopping rule's traces, the infinite fibril's map at MODEL_VERSION 2, 5 and 6, domain shapes,
the ensemble's two targets): their tables and the numbers their prose quotes, read from
docs/data/bench/{report,traces,mapcost,shapes,ensemble}_*.csv, each row with the date, commit,
MODEL_VERSION, bpy and command that made it. Files are named by their stem
(`report_said("report_measured", KEY)`: macros_model_a's `said` on docs/data/bench/STEM.csv; a
path "bench/..." in the page would read as the repository's bench/ folder). Beside it: a value
every row must share, the span of a column, minutes and seconds, the map's P(fit) one below the
minimum (the notebook's, through macros_model_b's `infinite_map`), and the section's tables, some
with a median or a total as their last row. page_numbers.py loads this file and calls
`macros(numbers)`; every name here starts with `report_`."""
from __future__ import annotations

import csv


def macros(numbers) -> dict:
    def raw(path: str) -> list[dict]:
        """A CSV under docs/data/ as its text ("0.40" stays "0.40"); a missing file fails."""
        numbers.data(path)  # the same checks: under docs/data/, a file that exists
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def bench(name: str) -> str:
        """A file of this section by its stem: "report_measured" is
        docs/data/bench/report_measured.csv."""
        return f"bench/{name}.csv"

    def column(path: str, name: str, where: dict | None = None) -> list[str]:
        rows = raw(path)
        if rows and name not in rows[0]:
            raise KeyError(f"{path}: no column {name!r}")
        rows = [r for r in rows if all(str(r[k]) == str(v) for k, v in (where or {}).items())]
        if not rows:
            raise ValueError(f"{path}: no row with {where}")
        return [r[name] for r in rows]

    def report_said(stem: str, key: str, field: str = "value"):
        """One cell of a file of this section, by its `key` column (macros_model_a's `said`)."""
        return numbers.MACROS["said"](bench(stem), key, field)

    def report_same(stem: str, name: str, where: dict | None = None) -> str:
        """The value of `name` that every row (matching `where`) holds; rows that differ fail
        ("both sides give the same answer" is then checked, not typed)."""
        return same(bench(stem), name, where)

    def same(path: str, name: str, where: dict | None = None) -> str:
        values = set(column(path, name, where))
        if len(values) != 1:
            raise ValueError(f"{path}: {name!r} differs between rows: {sorted(values)}")
        return values.pop()

    def median(path: str, name: str, where: dict | None = None) -> str:
        """The median of a column of an odd number of rows, as the file writes it."""
        values = sorted(column(path, name, where), key=lambda v: float(v.replace(",", "")))
        if len(values) % 2 == 0:
            raise ValueError(f"{path}: the median of {len(values)} values is not one of them")
        return values[len(values) // 2]

    def report_span(stem: str, name: str, where: dict | None = None, sep: str = "–") -> str:
        """The least and the largest of a column, as the file writes them: "1,790–2,189"."""
        path = bench(stem)
        values = sorted(column(path, name, where), key=lambda v: float(v.replace(",", "")))
        return values[0] if values[0] == values[-1] else f"{values[0]}{sep}{values[-1]}"

    def report_minutes_span(stem: str, name: str, sep: str = "–") -> str:
        """A column of seconds as whole minutes, least and largest: "8–11"."""
        values = sorted(float(v) for v in column(bench(stem), name))
        return f"{values[0] / 60:.0f}{sep}{values[-1] / 60:.0f}"

    def report_min_s(seconds) -> str:
        """Seconds as minutes and whole seconds: 1322.1 -> "22 min 2 s"."""
        whole = round(float(seconds))
        return f"{whole // 60} min {whole % 60} s"

    def report_map_below(anchor: str) -> str:
        """P(fit) one residue below the minimum, "0/5", that every diameter of the notebook's map
        under `anchor` shows (macros_model_b's `infinite_map`, which reads the notebook's table);
        diameters that differ fail."""
        rows = numbers.MACROS["infinite_map"](anchor)
        found = {f"{r['fits_below']}/{r['runs_below']}" for r in rows.values()}
        if len(found) != 1:
            raise ValueError(f"the map under {anchor}: P(fit) one below differs by diameter: {found}")
        return found.pop()

    def markdown(columns: dict, rows: list[dict]) -> str:
        """Rows as a Markdown table: `columns` maps each header to a template over the row."""
        lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
        lines += ["| " + " | ".join(spec.format(**r) for spec in columns.values()) + " |" for r in rows]
        return "\n".join(lines)

    def batch_rows(stem: str, batch: str) -> list[dict]:
        rows = [r for r in raw(bench(stem)) if r["batch"] == batch]
        if not rows:
            raise ValueError(f"{stem}: no batch {batch!r}")
        return rows

    def report_rules_table(batch: str) -> str:
        """The stopping rules replayed on a batch of traces (docs/data/bench/traces_rules.csv,
        `bench/stop_traces.py table`'s first table): the runs each rule stops early, how many
        of those fit in the end, and the frames it saves."""
        return markdown({"rule: stop after a judgement that is ...": "{rule}",
                         "runs stopped early": "{stopped}", "of them fit in the end": "**{stopped_fit}**",
                         "frames saved": "{frames_saved}"}, batch_rows("traces_rules", batch))

    def report_systems_table(batch: str) -> str:
        """The same batch by system and linker (docs/data/bench/traces_systems.csv)."""
        return markdown({"system": "{system}", "linker": "{linker}", "runs": "{runs}", "fit": "{fit}",
                         "fit at cycle (count)": "{fit_at_cycle}", "misses' frames": "{misses_frames}",
                         "first judgement of the runs that fit late: pairs, stretch/tol, overlap Å":
                         "{late_first_judgement}"}, batch_rows("traces_systems", batch))

    def report_traces_summary(batch: str) -> str:
        """A batch's first line as `table` prints it, counted from its rows by system:
        "50 runs (40 fit, 3 of them after a regrow; 10 misses) in 4 systems: base_report_1 24, ..."
        (a fit after a regrow: at a cycle after 0)."""
        rows = batch_rows("traces_systems", batch)
        runs = sum(int(r["runs"]) for r in rows)
        fits = sum(int(r["fit"]) for r in rows)
        late = sum(int(n) for r in rows if r["fit_at_cycle"] != "-"
                   for cycle, n in (part.split(": ") for part in r["fit_at_cycle"].split(", "))
                   if int(cycle) > 0)
        by: dict[str, int] = {}
        for r in rows:
            by[r["system"]] = by.get(r["system"], 0) + int(r["runs"])
        return (f"{runs} runs ({fits} fit, {late} of them after a regrow; {runs - fits} misses) in "
                f"{len(by)} systems: " + ", ".join(f"{s} {n}" for s, n in sorted(by.items())))

    def report_cells(stem: str, name: str, where: dict | None = None, sep: str = ", ") -> str:
        """A column's cells (of the rows matching `where`) in the file's order, joined by `sep`."""
        return sep.join(column(bench(stem), name, where))

    def report_diameter_table(which: str) -> str:
        """What a run of the infinite fibril's map cost, a diameter a row (median, range; s), for
        the map `which` ("v2", "v5", "v6": docs/data/bench/mapcost_diameters.csv)."""
        rows = [r for r in raw(bench("mapcost_diameters")) if r["map"] == which]
        if not rows:
            raise ValueError(f"mapcost_diameters.csv: no map {which!r}")
        columns = {"diameter (Å)": "{diameter}"}
        if rows[0]["cell_layers"]:
            columns["cell layers"] = "{cell_layers}"
        columns["misses (clear)" if rows[0]["clear_misses"] else "misses"] = (
            "{misses} ({clear_misses})" if rows[0]["clear_misses"] else "{misses}")
        columns.update({"a miss": "{miss_median_s} ({miss_range_s})", "fits": "{fits}",
                        "a fit": "{fit_median_s} ({fit_range_s})"})
        return markdown(columns, rows)

    def report_side_table() -> str:
        """The report side by side (docs/data/bench/report_side_by_side.csv), a side a row."""
        return numbers.MACROS["rows_table"](bench("report_side_by_side"), {
            "side": "side", "wall": "{wall_s} s", "restarts": "{restarts_s} s", "walk": "{walk_s} s",
            "best layout": "{best_layout_s} s", "pictures": "{pictures_s} s", "runs": "runs",
            "frames": "frames", "peak memory (tree)": "{peak_mib} MiB",
            "load before → after": "{load_before} → {load_after}"})

    def report_stage_table(run: str) -> str:
        """The report's stage times (docs/data/bench/report_stages.csv, run "quiet" or "load"),
        the whole command's row in bold; "what ran" where the run recorded it."""
        rows = [r for r in raw(bench("report_stages")) if r["run"] == run]
        if not rows:
            raise ValueError(f"report_stages.csv: no run {run!r}")
        what = any(r["what_ran"] for r in rows)
        lines = ["| stage | seconds |" + (" what ran |" if what else ""),
                 "|---|---|" + ("---|" if what else "")]
        for r in rows:
            stage, seconds = r["stage"], r["seconds"]
            if r["key"].endswith("_wall"):
                stage, seconds = f"**{stage}**", f"**{seconds}**"
            cells = [stage, seconds] + ([r["what_ran"]] if what else [])
            lines.append(("| " + " | ".join(cells) + " |").replace("|  |", "| |"))
        return "\n".join(lines)

    def report_rounds_table() -> str:
        """The map at MODEL_VERSION 6, its three rounds (docs/data/bench/mapcost_walls.csv) and
        their median wall time and peak memory."""
        path = bench("mapcost_walls")
        rows = [r for r in raw(path) if r["model_version"] == "6"]
        v6 = {"model_version": "6"}
        lines = ["| round | when (UTC) | commit | wall | peak memory (tree) | load (1 min) before → "
                 "after | runs | frames | worker-seconds |",
                 "|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            load = f"{r['load_before']} → {r['load_after']}"
            load += f" ({r['load_note']})" if r["load_note"] else ""
            lines.append(f"| {r['round']} | {r['when']} | {r['commit']} | {r['wall_s']} s | "
                         f"{r['peak_mib']} MiB | {load} | {r['runs']} | {r['frames']} | {r['worker_s']} |")
        wall = median(path, "wall_s", v6)
        loads = sorted(float(r[k]) for r in rows for k in ("load_before", "load_after"))
        lines.append(f"| **median** | | | **{wall} s ({report_min_s(wall)})** | "
                     f"{median(path, 'peak_mib', v6)} MiB | {loads[0]:.1f}–{loads[-1]:.1f} | | | |")
        return "\n".join(lines)

    def report_shapes_table() -> str:
        """Domain shapes, `sphere` against `hull` (docs/data/bench/shapes_rounds.csv), with the
        medians of the rounds."""
        path = bench("shapes_rounds")
        lines = ["| round | `sphere`, s | `hull`, s | hull / sphere |", "|---|---|---|---|"]
        lines += [f"| {r['round']} | {r['sphere_s']} | {r['hull_s']} | {r['ratio']}x |" for r in raw(path)]
        lines.append(f"| **median** | {median(path, 'sphere_s')} | {median(path, 'hull_s')} | "
                     f"**{median(path, 'ratio')}x** (target <= 3x: **met**, whole run) |")
        return "\n".join(lines)

    def report_ensemble_table() -> str:
        """The default model's ensemble, three runs and their medians
        (docs/data/bench/ensemble_default_runs.csv), a run a column."""
        path = bench("ensemble_default_runs")
        rows = raw(path)

        def pair(a: str, b: str, sep: str = ", "):
            return [f"{r[a]}{sep}{r[b]}" for r in rows], f"{median(path, a)}{sep}{median(path, b)}"

        def same_as_first(cells: list[str]) -> list[str]:
            return [c if i == 0 or c != cells[0] else "same" for i, c in enumerate(cells)]

        outer = [f"{r['outer_half_0']}, {r['outer_half_1']} ({r['outer_rel_diff_pct']} %)" for r in rows]
        table = [
            ("wall time, both halves (bpy import, 4 Bullet runs, sampling, map each), s",
             [r["wall_s"] for r in rows], f"**{median(path, 'wall_s')}**"),
            ("CPU time per half (Bullet, sampling, the half's map), s",
             pair("cpu_half_0", "cpu_half_1")[0], f"**{pair('cpu_half_0', 'cpu_half_1')[1]}**"),
            ("of it sampling, CPU s", *pair("sampling_half_0", "sampling_half_1")),
            ("halves' mean outer diameters, Å (relative difference)", same_as_first(outer),
             f"{same(path, 'outer_rel_diff_pct')} %"),
            ("width from the pooled map, Å (halves' widths 0.25 % apart)", [r["width"] for r in rows],
             same(path, "width")),
            ("ESS of the outer diameter (both halves)", [r["ess"] for r in rows], same(path, "ess")),
            ("peak memory: a half's process, MB; the whole command (`time -v`), MB",
             *pair("peak_half_mb", "peak_command_mb", "; ")),
        ]
        lines = ["| | " + " | ".join(f"run {r['run']}" for r in rows) + " | median |",
                 "|---|" + "---|" * (len(rows) + 1)]
        lines += [f"| {label} | " + " | ".join(cells) + f" | {mid} |" for label, cells, mid in table]
        return "\n".join(lines)

    return {name: fn for name, fn in locals().items() if name.startswith("report_")}
