"""The validation table of docs/validation.md (written by tools/validate.py, `make validate`):
for each gallery case, what the experiment says (the case file's words, from its paper, never
from a run) beside what FibrilFit says (the answer at the real linker, P(fit), and the bracket:
impossible below the bound, fits at the minimal linker, open between), and whether they agree.

Rows are plain dicts (tools/validate.py's stored rows, examples/measured.json); no bpy, no runs.
The caveats that go above the table: docs/validation.md#caveats.
"""
from __future__ import annotations

from ..exports.run_text import count


def _fit_text(row) -> str:
    f = row["fit"]
    if not f["n"]:
        return f"no run finished ({f['failed']} failed)"
    low, high = f["wilson95"]
    return f"{f['accommodated']}/{f['n']} ({low:.2f}-{high:.2f})"


def _minimal(row):
    """(minimal linker, its row) of the walk, or (None, a reason or None)."""
    m = row.get("minimal") or {}
    if "row" not in m:
        return None, m.get("status")
    r = m["row"]
    if r.get("error"):
        return None, f"not found: {r['error']}"
    if r["minimal_linker"] is None:
        if r.get("tried"):  # the lengths it ran: a walk screens some and skips others
            return None, f"no layout found at {_lengths(r['tried'])}"
        return None, f"no layout found up to {m['max']} ({m['restarts']} restarts each)"
    return r["minimal_linker"], r


def _lengths(tried: dict) -> str:
    """The walk's lengths as run, with their restarts, runs of one count grouped:
    "8, 9, 11 (2 restarts each), 13 (3 restarts)". A length it did not run is not named."""
    groups: list = []
    for length, v in sorted(tried.items(), key=lambda kv: int(kv[0])):
        n = v.get("restarts")
        if groups and groups[-1][1] == n:
            groups[-1][0].append(str(length))
        else:
            groups.append(([str(length)], n))
    return ", ".join(f"{', '.join(ls)} ({count(n, 'restart')}"
                     f"{' each' if len(ls) > 1 else ''})" for ls, n in groups)


def _minimal_text(row) -> tuple[str, str]:
    m, real = row.get("minimal") or {}, row["params"]["linker"]
    L, r = _minimal(row)
    if L is None:
        return r or "-", "-"
    below = (f"; {r['linker_below']}: 0/{m['restarts']}" if r.get("linker_below") else "")
    return (f"{L} ({r['fits']}/{r['restarts']} fit{below})", f"{real / L:.1f}")


def _envelope_text(row) -> str:
    d = row["outer_diameter"]
    if d["median"] is None:
        return "-"
    text = f"{d['median'] / 10:.1f} nm ({d['min'] / 10:.1f}-{d['max'] / 10:.1f})"
    if row["envelope_at_contour"]:
        text += ", = the stretched linker (upper bound)"
    return text


def _bound(row) -> int | None:
    return (row.get("bound") or {}).get("impossible_below")


def says(row) -> str:
    """What FibrilFit says at the real linker: "below the bound" (a proof that nothing fits),
    "no exit", "fits" (a layout was found: a proof that something fits) or "no layout found"
    (a search that failed: not a proof), docs/model/bound.md, docs/model/verdict.md#proves."""
    f, linker, B = row["fit"], row["params"]["linker"], _bound(row)
    if B is not None and linker < B:
        return "below the bound"
    if (row.get("answers") or {}).get("no exit", 0) and f["accommodated"] == 0:
        return "no exit"
    if not f["n"]:
        return "not run"
    return "fits" if f["accommodated"] else "no layout found"


def bracket(row) -> str:
    """impossible below B (proof: the bound) / fits at L (proof: a layout) / open between."""
    B, (L, r) = _bound(row), _minimal(row)
    real, fitted = row["params"]["linker"], row["fit"]["accommodated"] > 0
    if L is None and fitted:
        L = real  # the real linker's layout is the proof, the walk aside
    parts = [f"impossible below {B}" if B is not None else "bound not computed"]
    if L is not None:
        parts.append(f"fits at {L}")
        if B is not None:
            parts.append(f"below the bound: a contradiction (one of them is wrong)" if L < B
                         else f"closed: the minimum is {B}" if L == B
                         else f"open {B}-{L - 1}" if L - 1 > B else f"open at {B}")
    elif "row" not in (row.get("minimal") or {}):
        parts.append("no walk run")
    else:
        parts.append(r or "no fit found")
        if B is not None:
            parts.append(f"open from {B}")
    return " / ".join(parts)


# What a disagreement may mean: the physics the model leaves out (docs/validation.md#caveats)
LEFT_OUT = ("the model leaves out solvent, charges and kinetics, and it holds the fibril in "
            "one polymorph")


def agreement(row) -> tuple[str, str]:
    """("yes" / "no" / "no experiment", why) from the case's expected outcome (`expected`, from
    its paper) and what FibrilFit says (`says`). Against "does not fit": below the bound or no
    exit agrees as a proof; "no layout found" agrees weakly (a search that failed); "fits"
    disagrees, with what that may mean."""
    expected = row["meta"].get("expected", "unknown")
    said, B = says(row), _bound(row)
    short = not row["params"].get("periodic")
    if said == "not run":
        return "not run", ""
    if expected == "unknown" or row["meta"].get("observed", "").startswith("no experiment"):
        return "no experiment", ""  # e.g. the tutorial's toy model: its verdict is no experiment
    if expected == "fits":
        if said == "fits":
            return "yes", "a clash-free layout exists"
        if said in ("below the bound", "no exit"):
            return "no", (f"the model proves no layout exists ({said}); an estimate may be off, "
                          f"or {LEFT_OUT}")
        return "no", ("no seed found room; a failed search is not proof that none exists "
                      "(docs/model/verdict.md#proves), or an estimate is off")
    # the experiment says the domains do not fit (no fibril)
    if said in ("below the bound", "no exit"):
        return "yes", (f"proven: the linker is below the bound ({B})" if said == "below the bound"
                       else "proven: no exit")
    if said == "no layout found":
        return "yes", (f"weakly: no layout found in {row['fit']['n']} restarts, but the linker "
                       f"is not below the bound ({B}): not a proof")
    why = f"the model finds room the experiment says is missing: {LEFT_OUT}"
    if short:
        why += ("; and a short fibril has room at its ends that a long one lacks (an "
                "oligomer-sized assembly may be what fits)")
    return "no", why


def _measured_text(row) -> str:
    m = row.get("measured")
    return f"{m['date']}, {m['commit']}, MODEL_VERSION {m['model_version']}" if m else "-"


def experiment_text(meta: dict) -> str:
    """What the experiment says, with its paper: the case file's `observed`, `citation` and
    DOI, and a flag where the case's notes say a primary reference was not checked."""
    text = meta.get("observed", "")
    if meta.get("expected", "unknown") != "unknown":
        cited = "; ".join(x for x in (meta.get("citation"),
                                      meta.get("doi") and f"doi:{meta['doi']}") if x)
        text += f" ({cited})" if cited else " (no DOI in the case file)"
    if "not checked" in (meta.get("notes", "") + " " + meta.get("source", "")):
        text += "; primary reference not checked (the case file's notes)"
    return text


def _width_text(row) -> str:
    width, mid = row["meta"].get("envelope_width"), row["outer_diameter"]["median"]
    if not width:
        return "-"
    text = f"{width / 10:.0f} nm"
    if mid is not None:
        text += f" (predicted {mid / width:.1f}x"
        text += (", the linker's full extension, not a prediction)" if row["envelope_at_contour"]
                 else ")")
    return text


HEAD = ("| case | experiment says | FibrilFit says at the real linker (answer: P(fit)) | agree? | "
        "real linker | impossible below / fits at / open | minimal linker (walk) | margin (real "
        "/ minimal) | predicted outer diameter | measured width | measured with |")
COLUMNS = HEAD.count("|") - 1


def table(rows: list[dict]) -> str:
    """The table's Markdown: a row per case, in the order given."""
    lines = [HEAD, "|" + "---|" * COLUMNS]
    for row in rows:
        if "error" in row:
            lines.append(f"| `{row['case']}` | | not run: {row['error']} |" + " |" * (COLUMNS - 3))
            continue
        agree, why = agreement(row)
        minimal, margin = _minimal_text(row)
        changed = row["meta"].get("changed")
        lines.append("| " + " | ".join([
            f"`{row['case']}` {row['name']}" + (f" (changed: {changed})" if changed else ""),
            experiment_text(row["meta"]),
            f"{says(row)}: {_fit_text(row)}", f"**{agree}**" + (f": {why}" if why else ""),
            str(row["params"]["linker"]), bracket(row), minimal, margin, _envelope_text(row),
            _width_text(row), _measured_text(row)]) + " |")
    return "\n".join(lines)


GLANCE_HEAD = ("| system | what the experiment saw | FibrilFit's answer at the real linker | "
               "agree? |")


def _glance_says(row) -> str:
    """says() with its P(fit) and the bracket's two proofs, in a few words."""
    f, B, (L, _) = row["fit"], _bound(row), _minimal(row)
    if L is None and f["accommodated"]:
        L = row["params"]["linker"]
    text = f"{says(row)} ({f['accommodated']}/{f['n']}) at {row['params']['linker']}"
    sides = ([f"impossible below {B}"] if B is not None and B > 1 else []) + (
        [f"fits from {L}"] if L is not None else [])
    return text + (f"; {', '.join(sides)}" if sides else "")


def glance(rows: list[dict]) -> str:
    """The page's short table (issue #47 item 5): one line per case, the system, what its
    experiment saw, what FibrilFit says and whether they agree; from the same rows as table()."""
    lines = [GLANCE_HEAD, "|---|---|---|---|"]
    for row in rows:
        if "error" in row:
            lines.append(f"| `{row['case']}` | | not run: {row['error']} | |")
            continue
        agree, _ = agreement(row)
        saw = row["meta"].get("observed", "") if row["meta"].get("expected", "unknown") != \
            "unknown" else "no experiment"
        lines.append(f"| {row['name']} | {saw} | {_glance_says(row)} | **{agree}** |")
    return "\n".join(lines)


def provenance(rows: list[dict]) -> str:
    """The line under the table: every code its rows were measured with (date, commit,
    MODEL_VERSION, bpy, how many rows), and the code the bounds were computed with."""
    runs: dict = {}
    for r in rows:
        m = r.get("measured")
        if m:
            key = (m["date"], m["commit"], m["model_version"], m["bpy"])
            runs[key] = runs.get(key, 0) + 1
    text = "Rows measured: " + "; ".join(
        f"{n} on {d} at {c}, MODEL_VERSION {v}, bpy {b}" for (d, c, v, b), n in sorted(runs.items()))
    computed = sorted({(b["date"], b["commit"], b["model_version"]) for b in
                       ((r.get("bound") or {}).get("computed") for r in rows) if b})
    if computed:
        text += (". Bounds of the older rows computed (geometry, no runs) on " + "; ".join(
            f"{d} at {c}, MODEL_VERSION {v}" for d, c, v in computed))
    return text + "."
