"""The macros of the notebook's negative control, periodic cell and protofilaments pages
(docs/notebook/negative-control.md, periodic-cell.md, protofilaments.md), of the changelog and of
the contributing page: their dated tables and the times, P(fit)s and thresholds their prose
quotes, read from docs/data/notebook/*.csv (each row names its date, commit, MODEL_VERSION, bpy
and command), so the prose and the tables print what one file holds. page_numbers.py loads this
file and calls `macros(numbers)`; every name starts with `nb_`.

The negative control before the exit rule (`nb_nc_*`, negative-control_*.csv):
- `nb_nc_seeds_table()`, `nb_nc_v4(case)`: the MODEL_VERSION 4 runs at the published linkers, one
  row a seed (negative-control_v4_seeds.csv), and one case's P(fit), bound and seeds;
- `nb_nc_probes_table()`, `nb_nc_probe_miss()`: MODEL_VERSION 5's single-seed probes;
- `nb_nc_walk_table()`, `nb_nc_walk()`: MODEL_VERSION 5's walk with restarts, one row a restart,
  and what it found (the minimum, P(fit) there, the length below, the bound, the open range);
- `nb_nc_largest_table()`, `nb_nc_minimal_table()`, `nb_nc_largest(linker)`,
  `nb_nc_minimal(fraction)`, `nb_nc_cost(key)`: MODEL_VERSION 6's prediction and its costs.

The periodic cell (`nb_pc_*`): the cells against long fibrils, the tables rendered with
macros_model_b.py's `measured_table` (periodic-cell_agreement_axial.csv, _whole.csv) and their
shares quoted with `nb_pc_share`, `nb_pc_pooled`, `nb_pc_span`, `nb_pc_cell_runs`; inflate in a
cell (`nb_pc_inflate_table`, `nb_pc_inflate`: periodic-cell_inflate_cell.csv; `nb_pc_52`: its
52-layer re-run; `nb_pc_issue25`: the model page's row of the same runs). Protofilaments
(`nb_pf_table`, `nb_pf`: protofilaments_two.csv). A page's single numbers in prose are rows of
docs/data/notebook/PAGE_said.csv (key, value), quoted with macros_model_a.py's `said(path, key)`.
"""
from __future__ import annotations

import csv

NB = "notebook/"


def macros(numbers) -> dict:
    from fibrilfit.model.fraction_bound import fraction_bracket
    from fibrilfit.search.table import bracket_line

    def rows(name: str) -> list[dict]:
        return numbers.data(NB + name)

    def raw(name: str) -> list[dict]:
        """A CSV's cells as the file writes them ("3.0" stays "3.0")."""
        numbers.data(NB + name)  # the same checks: under docs/data/, a file that exists
        with open(numbers.DATA / NB / name, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def one(found: list[dict], what: str) -> dict:
        if len(found) != 1:
            raise KeyError(f"{what}: {len(found)} rows, not one")
        return found[0]

    def seconds(s, comma: bool = True) -> str:
        return (f"{s:,}" if comma else str(s)) + " s"

    def ratio(k: int, n: int) -> str:
        return f"{k}/{n}"

    def in_words(values) -> str:
        """"23, 24 and 28": a list as prose writes it."""
        values = [str(v) for v in values]
        return ", ".join(values[:-1]) + " and " + values[-1] if len(values) > 1 else "".join(values)

    def table(head: list[str], lines: list[list]) -> str:
        out = ["| " + " | ".join(str(h) for h in head) + " |", "|" + "---|" * len(head)]
        out += ["| " + " | ".join(str(c) for c in line) + " |" for line in lines]
        return "\n".join(out)

    # ---- the negative control, MODEL_VERSION 4 ---------------------------------------------

    def v4(case: str) -> list[dict]:
        found = [r for r in rows("negative-control_v4_seeds.csv") if r["case"] == case]
        if not found:
            raise KeyError(f"negative-control_v4_seeds.csv: no case {case!r}")
        return found

    def nb_nc_v4(case: str) -> dict:
        """One case's runs: P(fit) "0/3", its 95 % interval, the bound, the seeds."""
        rs = v4(case)
        k, n = sum(r["fits"] for r in rs), len(rs)
        return {"p_fit": ratio(k, n), "ci": numbers.wilson(k, n), "bound": rs[0]["bound"],
                "seeds": n, "linker": rs[0]["linker"]}

    def nb_nc_seeds_table() -> str:
        head = ["case", "fibril", "linker", "exit: residues spent, free linker",
                "bound: impossible below", "seeds", "answer", "P(fit) [95 % CI]",
                "worst stretch per seed", "clashing pairs per seed", "frames per seed",
                "bake per seed (wall)"]
        order = list(dict.fromkeys(r["case"] for r in rows("negative-control_v4_seeds.csv")))
        lines = []
        for case in order:
            rs = v4(case)
            k, n, r0 = sum(r["fits"] for r in rs), len(rs), rs[0]
            lines.append([f"`{case}`", r0["fibril"], r0["linker_said"], r0["exit"], r0["bound"],
                          ", ".join(str(r["seed"]) for r in rs),
                          "fits" if k else "no layout found",
                          f"{ratio(k, n)} [{numbers.wilson(k, n)}]",
                          ", ".join(f"{r['stretch_pct']} %" for r in rs),
                          ", ".join(str(r["clashing_pairs"]) for r in rs),
                          ", ".join(str(r["frames"]) for r in rs),
                          ", ".join(seconds(r["bake_s"], comma=False) for r in rs)])
        return table(head, lines)

    # ---- the negative control, MODEL_VERSION 5: probes and the walk -------------------------

    def nb_nc_probes_table() -> str:
        head = ["linker (anchor counted)", "free after the exit", "seed", "answer",
                "clashing pairs", "worst stretch", "frames; cycles (pairs, worst stretch)",
                "bake", "wall", "load at start"]
        return table(head, [[r["linker"], r["free_linker"], r["seed"], r["answer"],
                             r["clashing_pairs"], r["worst_stretch"], r["frames_cycles"],
                             seconds(int(r["bake_s"])), seconds(int(r["wall_s"])), r["load"]]
                            for r in raw("negative-control_v5_probes.csv")])

    def nb_nc_probe_miss() -> str:
        """What a miss cost in the probes, in whole minutes of wall time (the shorter miss)."""
        missed = [r["wall_s"] for r in rows("negative-control_v5_probes.csv")
                  if "fits" not in r["answer"]]
        return f"{round(min(missed) / 60)} minutes"

    def walk_lengths() -> dict[int, list[dict]]:
        by: dict[int, list[dict]] = {}
        for r in raw("negative-control_v5_walk.csv"):
            by.setdefault(int(r["linker"]), []).append(r)
        return dict(sorted(by.items()))

    def nb_nc_walk() -> dict:
        """The walk's answer: `minimal` (the shortest length with a fit), `fits`/`runs` there
        ("1/2" as `p_fit`), `ci`, the length below (`below`, `below_p_fit`, `below_ci`), the
        `bound` it started at, the `open` range, the seed that fitted (`fit_seed`) and every length
        where a seed fitted (`fitted_at`, "23, 24 and 28")."""
        by = walk_lengths()
        minimal = min(lk for lk, rs in by.items() if any(r["fits"] == "1" for r in rs))
        at, below = by[minimal], by[minimal - 1]
        k, n = sum(int(r["fits"]) for r in at), len(at)
        kb, nb = sum(int(r["fits"]) for r in below), len(below)
        bound = int(one(list({r["bound"]: r for rs in by.values() for r in rs}.values()),
                        "the walk's bound")["bound"])
        return {"minimal": minimal, "fits": k, "runs": n, "p_fit": ratio(k, n),
                "ci": numbers.wilson(k, n), "below": minimal - 1, "below_p_fit": ratio(kb, nb),
                "below_runs": nb, "below_ci": numbers.wilson(kb, nb), "bound": bound,
                "open": f"{bound}–{minimal - 1}",
                "fit_seed": ", ".join(r["seed"] for r in at if r["fits"] == "1"),
                "at_runs": {lk: len(rs) for lk, rs in by.items()},
                "fitted_at": in_words([lk for lk, rs in by.items() if any(r["fits"] == "1" for r in rs)])}

    def nb_nc_walk_table() -> str:
        head = ["linker (anchor counted)", "free after the exit", "restarts (seeds)", "fit",
                "clashing pairs at the end", "worst stretch", "frames", "bake"]
        minimal = nb_nc_walk()["minimal"]
        lines = []
        for lk, rs in walk_lengths().items():
            bold = (lambda r, text: f"**{text}**" if lk == minimal and r["fits"] == "1" else text)
            k = sum(int(r["fits"]) for r in rs)
            fitted = ", ".join(f"seed {r['seed']}" for r in rs if r["fits"] == "1")
            fit = f"**{k}** ({fitted})" if lk == minimal else str(k)
            frames = {r["frames"] for r in rs}
            frames = (f"{int(frames.pop()):,} each" if len(frames) == 1
                      else ", ".join(f"{int(r['frames']):,}" for r in rs))
            plain = [r for r in rs if not r["bake_note"]]
            noted = [r for r in rs if r["bake_note"]]
            bake = ", ".join(seconds(int(r["bake_s"])) for r in plain)
            if noted:
                bake += (f" (seed {', '.join(r['seed'] for r in plain)}; "
                         + "; ".join(f"seed {r['seed']} {r['bake_note']}: "
                                     f"{seconds(int(r['bake_s']))}" for r in noted) + ")")
            lines.append([f"**{lk}**" if lk == minimal else lk, rs[0]["free_linker"],
                          f"{len(rs)} ({', '.join(r['seed'] for r in rs)})", fit,
                          ", ".join(bold(r, r["clashing_pairs"]) for r in rs),
                          ", ".join(bold(r, f"{r['stretch_pct']} %") for r in rs),
                          frames, bake])
        return table(head, lines)

    # ---- the negative control, MODEL_VERSION 6: the prediction and its costs ----------------

    def nb_nc_largest(linker: int) -> dict:
        r = one([r for r in rows("negative-control_v6_largest.csv") if r["linker"] == linker],
                f"negative-control_v6_largest.csv linker {linker}")
        k, n = r["largest_count"], r["subunits"]
        fitted = str(r["counts_that_fitted"]).split()
        return {"k": k, "n": n, "percent": f"{100 * k / n:g} %", "fits": ratio(r["fits"], r["runs"]),
                "above": r["above_count"], "above_fits": ratio(r["above_fits"], r["above_runs"]),
                "fitted": in_words(fitted)}

    def nb_nc_largest_table() -> str:
        head = ["linker (anchor counted)", "subunits N", "largest fraction found (k/N)",
                "P(fit) there (runs)", "one more decorated", "bound f_B", "bracket"]
        lines = []
        for r in rows("negative-control_v6_largest.csv"):
            k, n = r["largest_count"], r["subunits"]
            lines.append([r["linker"], n, f"{k / n:.3f} ({k}/{n})", ratio(r["fits"], r["runs"]),
                          f"{r['above_count']}/{n}: {ratio(r['above_fits'], r['above_runs'])}",
                          f"{r['fraction_bound']:.3f}", fraction_bracket(r["fraction_bound"], k / n)])
        return table(head, lines)

    def nb_nc_minimal(fraction: float) -> dict:
        r = one([r for r in rows("negative-control_v6_minimal.csv")
                 if abs(r["fraction"] - fraction) < 1e-9],
                f"negative-control_v6_minimal.csv fraction {fraction}")
        m = r["minimal_linker"]
        return {"linker": m, "below": m - 1, "below_fits": ratio(r["below_fits"], r["below_runs"]),
                "bound": r["bound"]}

    def nb_nc_minimal_table() -> str:
        """The MODEL_VERSION 6 walks at a fraction, and the MODEL_VERSION 5 walk with every
        subunit decorated (negative-control_v5_walk.csv) as the last row."""
        head = ["fraction (decorated of 40)", "bound at the fraction: impossible below",
                "minimal linker found", "P(fit) there (runs)", "one below", "bracket"]

        def said(bound: int, minimal: int) -> str:
            line = bracket_line({"globule_diameter": 0, "floor": bound, "minimal_linker": minimal})
            return line.split(" Å: ", 1)[1].split(" (docs/")[0]

        lines = []
        for r in rows("negative-control_v6_minimal.csv"):
            m = r["minimal_linker"]
            lines.append([f"{100 * r['fraction']:g} % ({r['count']})", r["bound"], m,
                          ratio(r["fits"], r["runs"]),
                          f"{m - 1}: {ratio(r['below_fits'], r['below_runs'])}", said(r["bound"], m)])
        w = nb_nc_walk()
        lines.append(["100 % (40): the negative control, MODEL_VERSION 5 ([the walk](#infinite-walk))",
                      w["bound"], w["minimal"], w["p_fit"], f"{w['below']}: {w['below_p_fit']}",
                      said(w["bound"], w["minimal"])])
        return table(head, lines)

    def nb_nc_cost(key: str) -> dict:
        r = one([r for r in rows("negative-control_v6_costs.csv") if r["key"] == key],
                f"negative-control_v6_costs.csv key {key!r}")
        return {"wall": seconds(r["wall_s"]), "runs": r["runs"], "misses": r["misses"]}

    # ---- the periodic cell: inflate in a cell ----------------------------------------------

    def nb_pc_share(gravity: str, run: str, linker: int) -> dict:
        """One row of the agreement tables (periodic-cell_agreement_GRAVITY.csv, "axial" or
        "whole"), by its run and linker: `k` of `n` accommodated, `pct` ("91 %"), `of`
        ("91 % of 100"), `settled` and its share `settled_pct`."""
        import re
        r = one([r for r in raw(f"periodic-cell_agreement_{gravity}.csv")
                 if r["run"] == run and r["linker"] == str(linker)],
                f"periodic-cell_agreement_{gravity}.csv {run!r} at linker {linker}")
        m = re.fullmatch(r"(\d+)(?: \((\d+ %), [^)]*\))?", r["accommodated"])
        if not m:
            raise ValueError(f"{run} at linker {linker}: no share in {r['accommodated']!r}")
        n = int(r["n"])
        pct = m[2] or f"{round(100 * int(m[1]) / n)} %"
        return {"k": int(m[1]), "n": n, "pct": pct, "of": f"{pct} of {n}",
                "settled": int(r["settled"]), "settled_pct": f"{round(100 * int(r['settled']) / n)} %",
                "depth": r["deepest clash (Å)"]}

    def pc_cells(gravity: str, linker: int | None = None, least: int = 0) -> list[dict]:
        """The cells' rows ("cell, M = 26", ...) of an agreement table, at a linker (or all), of
        `least` layers or more."""
        import re
        found = []
        for r in raw(f"periodic-cell_agreement_{gravity}.csv"):
            m = re.match(r"cell, M = (\d+)", r["run"])
            if m and int(m[1]) >= least and (linker is None or r["linker"] == str(linker)):
                found.append(r)
        return found

    def nb_pc_pooled(gravity: str, linker: int, least: int) -> dict:
        """Every cell of `least` layers or more at a linker, pooled: `of` ("218 of 290 runs"),
        `pct`, and `range`, the least and largest share of those cells ("65–89 %")."""
        shares = [nb_pc_share(gravity, r["run"], linker) for r in pc_cells(gravity, linker, least)]
        k, n = sum(s["k"] for s in shares), sum(s["n"] for s in shares)
        return {"k": k, "n": n, "of": f"{k} of {n} runs", "pct": f"{round(100 * k / n)} %",
                "range": nb_pc_span(gravity, [r["run"] for r in pc_cells(gravity, linker, least)],
                                    linker)}

    def nb_pc_span(gravity: str, runs: list[str], linker: int) -> str:
        """The least and largest share of some rows at a linker: "65–73 %"."""
        pcts = sorted(int(nb_pc_share(gravity, run, linker)["pct"].split()[0]) for run in runs)
        return f"{pcts[0]} %" if pcts[0] == pcts[-1] else f"{pcts[0]}–{pcts[-1]} %"

    def nb_pc_cell_runs(gravity: str) -> int:
        """How many cell runs an agreement table holds, every linker."""
        return sum(int(r["n"]) for r in pc_cells(gravity))

    def nb_pc_inflate_table() -> str:
        """periodic-cell_inflate_cell.csv as the page's table: the cell's runs, the 20-layer
        fibril's and the tutorial protocol's in the cell beside them."""
        head = ["linker", "accommodated", "regrow cycles used (of 4)", "clashing pairs at the end",
                "worst stretch at the end (%)", "20 layers, inflate",
                "cell, tutorial protocol (M = 13, whole gravity, before \"Gravity in a cell\")"]
        lines = []
        for r in raw("periodic-cell_inflate_cell.csv"):
            fit = ratio(r["accommodated"], r["runs"])
            lines.append([r["linker"], f"**{fit}**" if r["linker"] == str(nb_pc_inflate()["cell"])
                          else fit, r["regrow_cycles"], r["clashing_pairs"], r["worst_stretch_pct"],
                          ratio(r["layers20_accommodated"], r["layers20_runs"]) + r["layers20_note"]
                          if r["layers20_accommodated"] else r["layers20_note"],
                          ratio(r["tutorial_accommodated"], r["tutorial_runs"])
                          if r["tutorial_accommodated"] else r["tutorial_note"]])
        return table(head, lines)

    def nb_pc_inflate() -> dict:
        """The shortest linker that fitted in the cell (`cell`) and on 20 layers (`layers20`),
        the tutorial protocol's share in the cell at the cell's minimum (`tutorial`, "2 of 5")
        and the runs a linker had (`runs`)."""
        rs = rows("periodic-cell_inflate_cell.csv")
        cell = min(r["linker"] for r in rs if r["accommodated"])
        at = next(r for r in rs if r["linker"] == cell)
        return {"cell": cell,
                "layers20": min(r["linker"] for r in rs if r["layers20_accommodated"] not in ("", 0)),
                "tutorial": f"{at['tutorial_accommodated']} of {at['tutorial_runs']}",
                "runs": {r["linker"]: r["runs"] for r in rs}}

    def nb_pc_52(linker: int) -> dict:
        """The 52-layer cell's re-run at a linker: "0 of 5", its seeds, clashes and stretch."""
        r = one([r for r in raw("periodic-cell_inflate_52.csv") if r["linker"] == str(linker)],
                f"periodic-cell_inflate_52.csv linker {linker}")
        return {"fits": f"{r['accommodated']} of {r['runs']}", "seeds": r["seeds"],
                "clashes": r["clashes"], "stretch": r["stretch"]}

    def nb_pc_52_minimal() -> int:
        """The shortest linker that fitted in the 52-layer cell's re-run."""
        return min(r["linker"] for r in rows("periodic-cell_inflate_52.csv") if r["accommodated"])

    def nb_pc_issue25() -> dict:
        """The 13-layer cell at linker 7 before the polish (issue 25; the model page's table,
        docs/data/model/periodic-cell_cell_search_v2.csv): "2 of 5" and the seeds that fitted."""
        found = [r for r in numbers.data("model/periodic-cell_cell_search_v2.csv")
                 if r["key"] == "13 7 before polish"]
        cell = one(found, "periodic-cell_cell_search_v2.csv key '13 7 before polish'")
        fits, seeds = str(cell["accommodated (seeds)"]).split(" (")
        seeds = seeds.rstrip(")").split(", ")
        return {"fits": fits, "seeds": in_words(seeds)}

    # ---- protofilaments: what two change ---------------------------------------------------

    def pf_kinds() -> dict[str, dict[int, dict]]:
        by: dict[str, dict[int, dict]] = {}
        for r in rows("protofilaments_two.csv"):
            by.setdefault(r["kind"], {})[r["linker"]] = r
        return by

    def nb_pf_table() -> str:
        """protofilaments_two.csv as the page's table: accommodated seeds a linker, a row a kind
        of fibril (a linker not run there left empty)."""
        by = pf_kinds()
        linkers = sorted({lk for kind in by.values() for lk in kind})
        return table(["linker", *linkers],
                     [[kind, *(at[lk]["accommodated"] if lk in at else "" for lk in linkers)]
                      for kind, at in by.items()])

    def nb_pf(kind: str) -> dict:
        """One kind's runs: the shortest linker every seed fitted (`minimal`) and "0/5" a linker
        (`at`)."""
        at = pf_kinds()[kind]
        return {"minimal": min(lk for lk, r in at.items() if r["accommodated"] == r["runs"]),
                "at": {lk: ratio(r["accommodated"], r["runs"]) for lk, r in at.items()}}

    return {name: fn for name, fn in locals().items() if name.startswith("nb_")}
