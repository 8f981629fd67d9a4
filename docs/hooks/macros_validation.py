"""The validation page's macros (docs/validation.md; loaded by docs/hooks/page_numbers.py): its
numbers as the page writes them, each from the file that holds it.

- the gallery's rows (`numbers.gallery`, examples/measured.json, what `make validate` stored):
  `val_fit("sup35_9xbo")` "3/3", `val_fit_in(case)` "3 of 3 seeds", `val_walk(case)`
  "8 (1/3 fit; 7: 0/3)", `val_outer(case)` "74.3 nm (62.3–80.4)", ...;
- the runs behind the page's own tables, under docs/data/validation/ (each file names its date,
  commit, MODEL_VERSION, command and source): the negative control's seeds, its walks, the
  Aβ42-GFP prediction, the hull runs, Sup35's seeds; a table macro per table
  (`val_negative_control_table()`, ...);
- the widths' runs (docs/data/widths/*.json, docs/data/widths_sup35*.{csv,json}):
  `val_widths(case)` and `val_sup35_widths_table()`.

A table macro writes the same header its fast test reads (tests/unit/test_validation_page_numbers.py
reads the page as the site shows it: tests/docs_rows.py)."""
from __future__ import annotations

import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def macros(numbers) -> dict:
    from fibrilfit.model.fraction_bound import fraction_bracket
    from fibrilfit.search.table import bracket_line
    from fibrilfit.sweep.stats import wilson

    def row(case: str) -> dict:
        return numbers.gallery()[case]

    def runs_of(name: str) -> dict:
        return numbers.data(f"validation/{name}.json")

    def interval(k: int, n: int) -> str:
        lo, hi = wilson(k, n)
        return f"{lo:.2f}–{hi:.2f}"

    def listed(values, unit: str = "") -> str:
        """[579, 586, 1697], " s" -> "579, 586 and 1,697 s"."""
        words = [f"{v:,}" if isinstance(v, int) else f"{v:g}" for v in values]
        text = words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]
        return text + unit

    # ---- the gallery (examples/measured.json) ----------------------------------------------

    def val_fit(case: str) -> str:
        """P(fit) at the real linker as fitted/seeds: "3/3"."""
        f = row(case)["fit"]
        return f"{f['accommodated']}/{f['n']}"

    def val_fit_in(case: str) -> str:
        """"3 of 3 seeds"."""
        f = row(case)["fit"]
        return f"{f['accommodated']} of {f['n']} seeds"

    def val_ci(case: str) -> str:
        """The 95 % Wilson interval of P(fit) at the real linker: "0.44–1.00"."""
        lo, hi = row(case)["fit"]["wilson95"]
        return f"{lo:.2f}–{hi:.2f}"

    def walk(case: str) -> dict:
        m = row(case).get("minimal") or {}
        if "row" not in m or m["row"].get("minimal_linker") is None:
            raise KeyError(f"{case}: no minimal linker stored (examples/measured.json)")
        return m["row"]

    def val_minimal(case: str) -> int:
        return walk(case)["minimal_linker"]

    def val_at_minimal(case: str) -> str:
        """P(fit) at the minimal linker: "1/3"."""
        r = walk(case)
        return f"{r['fits']}/{r['restarts']}"

    def val_below(case: str) -> str:
        """The walk one residue below its minimum: "7: 0/3"."""
        r = walk(case)
        return f"{r['linker_below']}: {round(r['p_fit_below'] * r['restarts'])}/{r['restarts']}"

    def val_walk(case: str) -> str:
        """"8 (1/3 fit; 7: 0/3)", as the gallery's table writes it."""
        return f"{val_minimal(case)} ({val_at_minimal(case)} fit; {val_below(case)})"

    def val_outer(case: str) -> str:
        """The envelope's outer diameter over the seeds: "74.3 nm (62.3–80.4)"."""
        d = row(case)["outer_diameter"]
        return f"{d['median'] / 10:.1f} nm ({d['min'] / 10:.1f}–{d['max'] / 10:.1f})"

    def val_outer_parts(case: str) -> dict:
        """The outer diameter's median, min and max over the seeds, in nm: {"median": "74.3", ...}."""
        d = row(case)["outer_diameter"]
        return {k: f"{d[k] / 10:.1f}" for k in ("median", "min", "max")}

    def val_all_fit(*cases: str) -> str:
        """"3 of 3 seeds" when every case fitted in all its seeds, the same number of them; else
        a KeyError (the sentence that says "all ... fit" would be wrong)."""
        said = {val_fit_in(c) for c in cases}
        if len(said) != 1 or any(row(c)["fit"]["accommodated"] != row(c)["fit"]["n"]
                                 for c in cases):
            raise KeyError(f"not every case fitted in all its seeds: {cases}")
        return said.pop()

    # ---- the page's own runs (docs/data/validation/) ---------------------------------------

    def seeds_table(head: str, lines: list[str]) -> str:
        return "\n".join([head, "|" + "---|" * (head.count("|") - 1), *lines])

    def per_seed(runs: list[dict], key: str, unit: str = "") -> str:
        return ", ".join(f"{r[key]:.1f}{unit}" if isinstance(r[key], float) else f"{r[key]}{unit}"
                         for r in runs)

    def val_negative_control_table() -> str:
        runs = runs_of("negative_control")["runs"]
        order = ["abeta42_5oqv_gfp_linker12", "abeta42_5oqv_gfp_linker14",
                 "abeta42_5oqv_gfp_linker12_20layers", "abeta42_5oqv_gfp_linker14_20layers"]
        head = ("| case | fibril | linker | exit: residues spent, free linker | bound: impossible "
                "below | seeds | answer | P(fit) [95 % CI] | worst stretch per seed | clashing "
                "pairs per seed | frames per seed | bake per seed (wall) |")
        lines = []
        for case in order:
            rs = [r for r in runs if r["case"] == case]
            k, n, r0 = sum(r["fits"] for r in rs), len(rs), rs[0]
            lines.append(" | ".join([
                f"| `{case}`", r0["fibril"],
                f"{r0['linker'] - 1} + anchor = {r0['linker']}",
                f"{r0['exit_residues']}, {r0['free_linker']}", str(r0["bound"]),
                ", ".join(str(r["seed"]) for r in rs), "fits" if k else "no layout found",
                f"{k}/{n} [{interval(k, n)}]", per_seed(rs, "stretch_pct", " %"),
                per_seed(rs, "clashing_pairs"), per_seed(rs, "frames"),
                per_seed(rs, "bake_s", " s")]) + " |")
        return seeds_table(head, lines)

    def walk_runs(case: str) -> list[dict]:
        """The walk's runs of a case: below the real linker from walks.json, at it the seeds of
        negative_control.json (the walk reused them)."""
        return ([r for r in runs_of("walks")["runs"] if r["case"] == case]
                + [r for r in runs_of("negative_control")["runs"] if r["case"] == case])

    def val_walk_table(case: str, head: str) -> str:
        """One line per length walked: its free linker, restarts, fits, clashing pairs, worst
        stretch, frames and bake, a value per restart."""
        runs = walk_runs(case)
        lines = []
        for length in sorted({r["linker"] for r in runs}):
            rs = [r for r in runs if r["linker"] == length]
            lines.append(" | ".join([
                f"| {length}", str(rs[0]["free_linker"]),
                f"{len(rs)} ({', '.join(str(r['seed']) for r in rs)})",
                str(sum(r["fits"] for r in rs)), per_seed(rs, "clashing_pairs"),
                per_seed(rs, "stretch_pct", " %"), per_seed(rs, "frames"),
                per_seed(rs, "bake_s", " s")]) + " |")
        head = (f"| {head} | free after the exit | restarts (seeds) | fit | clashing pairs at the "
                "end | worst stretch | frames | bake |")
        return seeds_table(head, lines)

    def val_range(name: str, key: str, cases: list[str] | None = None, unit: str = "",
                  digits: int = 0) -> str:
        """The range of one per-run number in a run file, over the runs of `cases` (all if
        None): "34–47", or the one value when they agree."""
        vs = [r[key] for r in runs_of(name)["runs"] if cases is None or r["case"] in cases]
        lo, hi = f"{min(vs):.{digits}f}", f"{max(vs):.{digits}f}"
        return (lo if lo == hi else f"{lo}–{hi}") + unit

    def prediction() -> dict:
        return runs_of("abeta42_prediction")

    def val_largest_table() -> str:
        head = ("| linker (anchor counted) | subunits N | largest fraction found (k/N) | P(fit) "
                "there (runs) | one more decorated | bound f_B | bracket |")
        lines = []
        for r in prediction()["largest"]["rows"]:
            k, n = r["largest_count"], r["subunits"]
            lines.append(" | ".join([
                f"| {r['linker']}", str(n), f"{k / n:.3f} ({k}/{n})", f"{r['fits']}/{r['runs']}",
                f"{r['above_count']}/{n}: {r['above_fits']}/{r['above_runs']}",
                f"{r['fraction_bound']:.3f}", fraction_bracket(r["fraction_bound"], k / n)]) + " |")
        return seeds_table(head, lines)

    def val_largest(linker: int) -> dict:
        """The largest fraction found at a linker, as the prose quotes it."""
        r = next(r for r in prediction()["largest"]["rows"] if r["linker"] == linker)
        k, n = r["largest_count"], r["subunits"]
        return {"k": k, "n": n, "percent": f"{100 * k / n:g} %", "above": r["above_count"],
                "above_restarts": r["above_runs"], "wall_s": f"{r['wall_s']:,} s",
                "runs": r["runs_total"]}

    def val_stopped() -> dict:
        """The search at linker 15, stopped undecided: the largest count that fitted (answer
        `fits`), the counts above it answered `borderline` (accommodated, at the criterion), and
        those that missed, with their restarts."""
        st = prediction()["stopped"]
        fits = [r for r in st["runs"] if r["answer"] == "fits"]
        top = max(fits, key=lambda r: r["count"])
        edge = [r for r in st["runs"] if r["answer"] == "borderline" and r["count"] > top["count"]]
        missed = sorted({r["count"] for r in st["runs"] if not r["fits"]
                         and r["count"] > top["count"]})
        restarts = {c: sum(1 for r in st["runs"] if r["count"] == c) for c in missed}
        return {"linker": st["linker"], "n": st["subunits"], "count": top["count"],
                "percent": f"{100 * top['count'] / st['subunits']:g} %",
                "pairs": top["clashing_pairs"], "stretch": f"{top['stretch_pct']:g} %",
                "missed": listed(missed), "missed_restarts": sorted(set(restarts.values())),
                "borderline": [{"count": r["count"], "pairs": r["clashing_pairs"],
                                "stretch": f"{r['stretch_pct']:g} %"} for r in edge]}

    def val_fraction_minimal_table() -> str:
        head = ("| fraction (decorated of 40) | bound at the fraction: impossible below | "
                "minimal linker found | P(fit) there (runs) | one below | bracket |")
        lines = []
        for r in prediction()["minimal"]["rows"]:
            m = r["minimal_linker"]
            said = bracket_line({"globule_diameter": 0, "floor": r["bound"], "minimal_linker": m})
            lines.append(" | ".join([
                f"| {100 * r['fraction']:g} % ({r['count']})", str(r["bound"]), str(m),
                f"{r['fits']}/{r['runs']}", f"{m - 1}: {r['below_fits']}/{r['below_runs']}",
                said.split(" Å: ", 1)[1].split(" (docs/")[0]]) + " |")
        return seeds_table(head, lines)

    def val_fraction_minimal(fraction: float) -> dict:
        r = next(r for r in prediction()["minimal"]["rows"] if abs(r["fraction"] - fraction) < 1e-9)
        return {"linker": r["minimal_linker"], "below": r["minimal_linker"] - 1,
                "below_fits": f"{r['below_fits']}/{r['below_runs']}",
                "below_restarts": r["below_runs"]}

    def hull() -> dict:
        return runs_of("hull")

    def hull_walk(r: dict) -> str:
        return (f"{r['minimal_linker']} ({r['fits_at_minimal']}/{r['restarts']} fit; "
                f"{r['minimal_linker'] - 1}: {r['fits_below']}/{r['restarts']})")

    def val_hull_table() -> str:
        head = ("| case | source | observed | P(fit) at the real linker | real linker | minimal "
                "linker | margin (real / minimal) | predicted outer diameter | measured width | "
                "FibrilFit vs literature |")
        lines = []
        for r in hull()["rows"]:
            saw = row(r["case"])  # the case's own words, as the gallery's table gives them
            lines.append(" | ".join([
                f"| `{r['case']}.toml` {r['name']}", r["source"], observed(saw),
                f"{r['fits']}/{r['seeds']} ({interval(r['fits'], r['seeds']).replace('–', '-')})",
                str(r["real_linker"]), hull_walk(r), f"{r['real_linker'] / r['minimal_linker']:.1f}",
                f"{r['outer_median_nm']:.1f} nm ({r['outer_min_nm']:.1f}-{r['outer_max_nm']:.1f})",
                "-", "no verdict to compare"]) + " |")
        return seeds_table(head, lines)

    def observed(stored: dict) -> str:
        from fibrilfit.model import cases
        return cases.load(ROOT / "examples" / stored["case"]).meta.get("observed", "")

    def val_shapes_table() -> str:
        """The hull runs against the gallery's sphere rows of the same cases."""
        head = ("| case | minimal linker, sphere | minimal linker, hull | outer diameter, sphere "
                "| outer diameter, hull |")
        names = {"asyn_2n0a_gfp": "2N0A + GFP", "asyn_6cu7_ubiquitin": "6CU7 + ubiquitin"}
        lines = []
        for r in hull()["rows"]:
            c = r["case"]
            sphere = f"{val_minimal(c)} ({val_at_minimal(c)}; {val_below(c)})"
            hull_cell = (f"**{r['minimal_linker']}** ({r['fits_at_minimal']}/{r['restarts']}; "
                         f"{r['minimal_linker'] - 1}: {r['fits_below']}/{r['restarts']})")
            lines.append(" | ".join([
                f"| {names[c]} ({r['domain']})", sphere, hull_cell, val_outer(c),
                f"{r['outer_median_nm']:.1f} nm ({r['outer_min_nm']:.1f}–{r['outer_max_nm']:.1f})"])
                + " |")
        return seeds_table(head, lines)

    def val_hull(case: str) -> dict:
        r = next(r for r in hull()["rows"] if r["case"] == case)
        return {"minimal": r["minimal_linker"], "fits": f"{r['fits']}/{r['seeds']}"}

    def val_hull_stamp() -> str:
        p = hull()["provenance"]
        s = p["wall_s"]
        return (f"{p['date']} {p['time_utc']} UTC ({s // 60} min {s % 60} s), main at "
                f"{p['commit']}, MODEL_VERSION {p['model_version']}, bpy {p['bpy']}")

    def val_sup35_seeds() -> dict:
        s = runs_of("sup35_seeds")["seeds"]
        return {"stretch": listed([r["stretch_pct"] for r in s]),
                "frames": listed(sorted({r["frames"] for r in s})),
                "bakes": listed([r["bake_s"] for r in s], " s"),
                "pairs": listed(sorted({r["clashing_pairs"] for r in s})),
                "seeds": ", ".join(str(r["seed"]) for r in s)}

    # ---- widths (docs/data/widths*.json, docs/data/widths_sup35.csv) ------------------------

    widths = numbers.script("tools/widths.py")

    def val_widths(case: str) -> dict:
        """A widths run (docs/data/widths/CASE.json) as the prose quotes it, in nm."""
        d = numbers.data(f"widths/{case}.json")
        od = d["outer_diameter"]
        halves = d["halves"]
        return {
            "width": f"{d['width'] / 10:.2f}",
            "halves": [f"{w / 10:.1f}" for w in d["width_halves"]],
            "halves_apart": f"{100 * d['width_halves_relative_difference']:.1f} %",
            "interval": [f"{min(d['width_per_start']) / 10:.1f}",
                         f"{max(d['width_per_start']) / 10:.1f}"],
            "outer_mean": f"{od['mean'] / 10:.1f}", "outer_sem": f"{od['sem'] / 10:.1f}",
            "outer_95": [f"{v / 10:.1f}" for v in od["interval_95"]],
            "outer_halves": [f"{v / 10:.1f}" for v in od["halves"]["means"]],
            "outer_halves_apart": f"{100 * od['halves']['relative_difference']:.1f} %",
            "tau": f"{od['tau_samples']:.1f}", "ess": f"{od['ess']:.0f}",
            "bullet": [f"{b['outer_diameter'] / 10:.1f}" for h in halves for b in h["bullet"]],
            "repairs": [h["repair_sweeps"] for h in halves],
            "wall_min": f"{d['seconds'] / 60:.0f} min",
            "wall_s": d["seconds"], "tau_raw": od["tau_samples"], "ess_raw": od["ess"],
            "sweeps": d["sweeps"],
            "date": d["date"], "commit": d["commit"], "model_version": d["model_version"],
            "off": widths.off_by({"predicted_width_nm": f"{d['width'] / 10:.2f}",
                                  "measured_nm": d["measured"]["measured_nm"]}).replace("-", "−"),
        }

    def val_widths_span(cases: list[str], key: str) -> str:
        """The range of one number over several widths runs: "31–40 min", "70–108"."""
        ws = [val_widths(c) for c in cases]
        if key == "wall_min":
            vs = [w["wall_s"] / 60 for w in ws]
            return f"{min(vs):.0f}–{max(vs):.0f} min"
        if key == "repairs":
            vs = [v for w in ws for v in w["repairs"]]
            return f"{min(vs)}–{max(vs)}"
        if key == "tau":
            vs = [w["tau_raw"] for w in ws]
            return f"{min(vs):.1f}–{max(vs):.1f}"
        if key == "ess":
            vs = [w["ess_raw"] for w in ws]
            return f"{min(vs):.0f}–{max(vs):.0f}"
        raise KeyError(key)

    def val_sup35_widths_table() -> str:
        """docs/data/widths_sup35.csv as the widths table's columns (tools/widths.py's
        differences), a row whose width was not obtained saying so."""
        rows = widths.read_rows(ROOT / "docs" / "data" / "widths_sup35.csv")
        lines = ["| system | core | domain, kDa | linker | layers | technique | measured, nm | "
                 "predicted width, nm [interval] | predicted − measured | ESS | date | commit | "
                 "MODEL_VERSION |", "|" + "---|" * 13]
        for r in rows:
            got = r["predicted_width_nm"]
            lines.append("| " + " | ".join([
                r["system"], r["core_source"], r["domain_kDa"], r["linker"], r["layers"],
                r["technique"], r["measured_nm"],
                f"{got} [{r['interval_lo']}, {r['interval_hi']}]" if got else
                "not obtained: the ensemble's start was not repaired in this session (below)",
                widths.off_by(r).replace("-", "−") if got else "–", r["ess"] or "–",
                r["date"], r["commit"], r["model_version"]]) + " |")
        return "\n".join(lines)

    def val_sup35_width(system_start: str) -> dict:
        r = next(r for r in widths.read_rows(ROOT / "docs" / "data" / "widths_sup35.csv")
                 if r["system"].startswith(system_start))
        return {"width": r["predicted_width_nm"], "measured": r["measured_nm"],
                "lo": r["interval_lo"], "hi": r["interval_hi"],
                "off": widths.off_by(r).replace("-", "−")}

    return {name: fn for name, fn in locals().items() if name.startswith("val_")}
