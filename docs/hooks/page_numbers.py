"""The numbers the user pages quote, from the files that hold them (mkdocs-macros-plugin's module:
mkdocs.yml `macros: module_name`). A page that sets `render_macros: true` in its front matter
quotes `{{ took("report_6cu7_20") }}`, `{{ reports.tutorial_20.p_fit.fits }}`,
`{{ defaults.model.stretch_tolerance }}`; an unknown name fails the build (`on_undefined:
strict`) and tests/unit/test_docs_numbers.py, which renders every such page with `variables()`
and `MACROS` without MkDocs. The sources:

- `costs`: docs/data/costs.csv, one row a command's wall time on this project's 2-core machine
  (bench/costs.py writes it: date, commit, MODEL_VERSION, bpy, load before and after);
- `reports`: docs/data/reports/NAME.json, the report.json of a report the pages quote, copied
  as written (bench/costs.py's long cases; its `stamp` names the date, commit and MODEL_VERSION);
- `maps`: the minimal linker against the ball's size: `cell` from the infinite fibril's map as
  docs/notebook/search.md#map-v5 publishes it (docs/data/notebook/search_map_v5.csv, which
  bench/docs_map.py reads), `layers20` from docs/minimal_linker.csv;
- `defaults`: the code's own defaults (fibrilfit.model.params.DEFAULTS and each command's plan),
  so a page never restates a default by hand;
- `model_version`: the code's MODEL_VERSION;
- `gallery`: examples/measured.json (what `make validate` measured), a row per case file's stem;
- `data("PATH")`: any other measured file under docs/data/ (CSV a list of rows, JSON as written,
  JSONL a list of records), and `csv_table("PATH")` renders a CSV there as a Markdown table;
- the macros of every docs/hooks/macros_*.py (its `macros(numbers)`, given this module's names,
  returns a dict): a page family's own ways of writing its numbers, kept beside this file so no
  two families edit one list.

A page whose front matter also says `numbers: data` quotes no measured time or P(fit) by hand
(tests/unit/test_docs_numbers.py): each comes from a file through the names above, so two pages
that quote one measurement print the same number.

Standard library and the package only (no bpy): the docs build and the unit tests import it.
"""
from __future__ import annotations

import csv
import functools
import importlib.util
import json
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "docs" / "data"


def model_version() -> int:
    text = (ROOT / "fibrilfit" / "model" / "version.py").read_text(encoding="utf-8")
    return int(re.search(r"^MODEL_VERSION = (\d+)", text, re.M).group(1))


@functools.lru_cache(maxsize=None)
def costs() -> dict[str, dict]:
    """docs/data/costs.csv by key: `wall_s` the median of the repeats' wall times `wall_s_all`,
    `cpu_s` the median of their CPU times `cpu_s_all` (None where it was not recorded)."""
    def seconds(text: str) -> list[float]:
        return [float(x) for x in (text or "").split()]
    rows = {}
    with open(DATA / "costs.csv", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            r = dict(r)
            r["wall_s"] = float(r["wall_s"])
            r["wall_s_all"] = seconds(r.get("wall_s_all")) or [r["wall_s"]]
            r["repeats"] = int(r.get("repeats") or len(r["wall_s_all"]))
            r["cpu_s"] = float(r["cpu_s"]) if r.get("cpu_s") else None
            r["cpu_s_all"] = seconds(r.get("cpu_s_all"))
            r["minutes"] = round(r["wall_s"] / 60, 1)
            r["model_version"] = int(r["model_version"])
            rows[r["key"]] = r
    return rows


@functools.lru_cache(maxsize=None)
def reports() -> dict[str, dict]:
    return {p.stem: json.loads(p.read_text(encoding="utf-8"))
            for p in sorted((DATA / "reports").glob("*.json"))}


@functools.lru_cache(maxsize=None)
def script(path: str):
    """A script of the repository ("bench/docs_map.py", "tools/widths.py") loaded as a module,
    once: the pages' macros read what the tools write the way the tools read it."""
    spec = importlib.util.spec_from_file_location(pathlib.PurePosixPath(path).stem, ROOT / path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@functools.lru_cache(maxsize=None)
def maps() -> dict[str, dict[int, int]]:
    docs_map = script("bench/docs_map.py")
    cell = {d: row["minimal_linker"] for d, row in docs_map.published_map().items()}
    with open(ROOT / "docs" / "minimal_linker.csv", encoding="utf-8") as f:
        layers20 = {int(r["globule_diameter"]): int(r["minimal_linker"])
                    for r in csv.DictReader(f) if r["kind"] == "layers 20"}
    return {"cell": cell, "layers20": layers20}


@functools.lru_cache(maxsize=None)
def defaults() -> dict:
    import dataclasses
    from fibrilfit.api.plans import COMMAND_PLANS
    from fibrilfit.model.params import DEFAULTS
    return {"model": dataclasses.asdict(DEFAULTS) if dataclasses.is_dataclass(DEFAULTS)
            else dict(vars(DEFAULTS)),
            "restarts": {name: plan().search.restarts for name, plan in COMMAND_PLANS.items()
                         if hasattr(plan(), "search")}}


@functools.lru_cache(maxsize=None)
def gallery() -> dict[str, dict]:
    """examples/measured.json by case: `gallery.sup35_9xbo.fit.p_fit` (the stem of its case file)."""
    rows = json.loads((ROOT / "examples" / "measured.json").read_text(encoding="utf-8"))
    return {pathlib.Path(r["case"]).stem: r for r in rows}


def _number(text: str):
    """A CSV cell as the number it writes, else the text ("" stays "")."""
    try:
        return int(text)
    except ValueError:
        try:
            return float(text)
        except ValueError:
            return text


@functools.lru_cache(maxsize=None)
def data(path: str):
    """A measured file under docs/data/ by its path there: a CSV as a list of rows (numbers
    parsed), a JSON as written, a JSONL as a list of records. A missing file fails the page."""
    f = DATA / path
    if not f.resolve().is_relative_to(DATA.resolve()):
        raise ValueError(f"data({path!r}): only files under docs/data/")
    if f.suffix == ".csv":
        with open(f, encoding="utf-8") as fh:
            return [{k: _number(v) for k, v in r.items()} for r in csv.DictReader(fh)]
    if f.suffix == ".jsonl":
        return [json.loads(ln) for ln in f.read_text(encoding="utf-8").splitlines() if ln.strip()]
    if f.suffix == ".json":
        return json.loads(f.read_text(encoding="utf-8"))
    raise ValueError(f"data({path!r}): a .csv, .json or .jsonl file")


def csv_table(path: str, columns: dict | list | None = None) -> str:
    """A CSV under docs/data/ as a Markdown table: every column, or `columns` (a list of column
    names, or a dict of column name to the header shown), in the file's row order."""
    rows = data(path)
    if isinstance(columns, dict):
        keys, heads = list(columns), list(columns.values())
    else:
        keys = list(columns) if columns else list(rows[0]) if rows else []
        heads = keys
    missing = [k for k in keys if rows and k not in rows[0]]
    if missing:
        raise KeyError(f"csv_table({path!r}): no column {missing}")
    lines = ["| " + " | ".join(heads) + " |", "|" + "---|" * len(keys)]
    lines += ["| " + " | ".join(str(r[k]) for k in keys) + " |" for r in rows]
    return "\n".join(lines)


def variables() -> dict:
    return {"costs": costs(), "reports": reports(), "maps": maps(), "defaults": defaults(),
            "model_version": model_version(), "gallery": gallery()}


# ---- macros: how a number is written -------------------------------------------------------

def took(key: str) -> str:
    """A command's wall time as a reader wants it: seconds under two minutes, else minutes."""
    s = costs()[key]["wall_s"]
    return f"{s:.0f} s" if s >= 10 and s < 120 else f"{s:.1f} s" if s < 10 else f"{s / 60:.1f} min"


def stamp(key: str) -> str:
    """Where a time comes from: date, commit, MODEL_VERSION, load (docs/data/costs.csv)."""
    r = costs()[key]
    return (f"{r['date']}, commit {r['commit']}, MODEL_VERSION {r['model_version']}, "
            f"load {r['load_before']} → {r['load_after']}")


def report_stamp(name: str) -> str:
    s = reports()[name]["stamp"]
    return (f"{s['date']}, commit {s['commit']}, MODEL_VERSION {s['model_version']}, "
            f"bpy {s['bpy']}")


def pfit(name: str) -> str:
    """P(fit) at the report's asked linker: "8/8 at linker 8"."""
    pf = reports()[name]["p_fit"]
    return f"{pf['fits']}/{pf['runs']} at linker {pf['linker']}"


def minimal(name: str) -> int:
    return reports()[name]["minimal_linker"]["linker"]


def tried(name: str) -> str:
    """Every length the report's walk tried with its restarts: "0/8 at 5, 8/8 at 6"."""
    t = reports()[name]["minimal_linker"]["tried"]
    return ", ".join(f"{v['accommodated']}/{v['restarts']} at {k}"
                     for k, v in sorted(t.items(), key=lambda kv: int(kv[0])))


def wilson(k: int, n: int) -> str:
    """The 95 % Wilson interval of k of n, as FibrilFit computes it (fibrilfit/sweep/stats.py)."""
    from fibrilfit.sweep.stats import wilson as interval
    lo, hi = interval(k, n)
    return f"{lo:.2f}–{hi:.2f}"


def first_map_transition() -> str:
    """What docs/minimal_linker.csv's 20-layer rows say about P(fit) at the minimal linker and
    one below, in words."""
    with open(ROOT / "docs" / "minimal_linker.csv", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if r["kind"] == "layers 20"]
    sizes = sorted(int(r["globule_diameter"]) for r in rows)
    at = {(float(r["p_fit"]), int(r["restarts"])) for r in rows}
    below = {float(r["p_fit_below"]) for r in rows}
    if len(at) == 1 and below == {0.0}:
        p, n = at.pop()
        return (f"every ball size from {sizes[0]} to {sizes[-1]} Å fitted in {round(p * n)} of {n} "
                f"restarts at its minimal linker and in 0 of {n} one residue shorter")
    return (f"P(fit) at the minimal linker ranged over {sorted(a for a, _ in at)} and one residue "
            f"shorter over {sorted(below)}, for ball sizes {sizes[0]}-{sizes[-1]} Å")


def pct(x: float) -> str:
    return f"{100 * x:g} %"


def cost_table(note: str = "") -> str:
    """docs/data/costs.csv as one Markdown table: command × system × size × protofilaments, the
    median wall time and CPU time of the repeats, with what each means above it; `note` (the
    page's fast-test marker) goes on the line right above the table."""
    mv = model_version()
    legend = (
        "*Wall*: the time from start to finish on this machine (the median of the repeats; "
        "seconds in brackets above two minutes): what you wait, at the load named. *CPU s*: the processor seconds "
        "the command and every worker it started used (user + system, the median of the "
        "repeats): the work itself, which the machine's other users barely change. *Cores "
        "busy*: CPU ÷ wall, how many cores the command kept busy on average: a `run` keeps "
        "a little more than one (Blender's own threads), a command with two workers up to two; "
        "well below that, the command waited for cores other work held. On two idle cores a "
        "command takes between CPU ÷ 2 and about its CPU time. *Repeats*: how many times the "
        "command was run, in rounds over the commands (each repeat's times are in "
        "`docs/data/costs.csv`). *Load*: the 1-minute load average before → after (the medians "
        "over the repeats), which counts work at every priority.\n\n")
    head = ("| command | system | layers | protofilaments | restarts | workers | wall "
            "| CPU s | cores busy | repeats | answer | load | measured |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    lines = []
    for r in costs().values():
        when = f"{r['date']}, {r['commit']}, MODEL_VERSION {r['model_version']}, bpy {r['bpy']}"
        if r["model_version"] != mv:
            when += " (**older than the code's**)"
        cpu, busy = "not recorded", "-"
        if r["cpu_s"] is not None:
            cpu, busy = f"{r['cpu_s']:.1f}", f"{r['cpu_s'] / r['wall_s']:.2f}"
        wall = took(r["key"]) + (f" ({r['wall_s']:.1f} s)" if r["wall_s"] >= 120 else "")
        lines.append(f"| `{r['command']}` | {r['system']} | {r['layers']} | {r['protofilaments']} "
                     f"| {r['restarts']} | {r['workers']} | {wall} "
                     f"| {cpu} | {busy} | {r['repeats']} | {r['answer']} "
                     f"| {r['load_before']} → {r['load_after']} | {when} |")
    return legend + (note + "\n" if note else "") + head + "\n".join(lines)


MACROS = {"took": took, "stamp": stamp, "report_stamp": report_stamp, "pct": pct,
          "cost_table": cost_table, "pfit": pfit, "minimal": minimal, "tried": tried,
          "wilson": wilson, "first_map_transition": first_map_transition, "data": data,
          "csv_table": csv_table}


def _family_macros() -> dict:
    """The macros of every docs/hooks/macros_*.py, loaded by path (the plugin imports this file
    alone): each file's `macros(numbers)` is given this module's public names (`data`,
    `gallery`, `costs`, ...) and returns its own; a name defined twice fails."""
    import types
    numbers = types.SimpleNamespace(**{k: v for k, v in globals().items() if not k.startswith("_")})
    found: dict = {}
    for f in sorted(pathlib.Path(__file__).resolve().parent.glob("macros_*.py")):
        spec = importlib.util.spec_from_file_location(f.stem, f)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        for name, fn in module.macros(numbers).items():
            if name in found or name in MACROS:
                raise ValueError(f"{f.name}: the macro {name!r} is defined twice")
            found[name] = fn
    return found


MACROS.update(_family_macros())


# The Jinja delimiters mkdocs.yml gives the plugin: `{#anchor}` (attr_list) is not a comment
J2 = {"comment_start_string": "{##", "comment_end_string": "##}"}
FRONT = re.compile(r"\A---\n(.*?)\n---\n", re.S)


def environment():
    """A Jinja environment as the plugin renders a page: strict, with the data and the macros."""
    import jinja2
    env = jinja2.Environment(undefined=jinja2.StrictUndefined, **J2)
    env.globals.update(variables())
    env.globals.update(MACROS)
    return env


def page_text(path: pathlib.Path) -> str:
    """A page's Markdown as the site shows it: with `render_macros: true` in its front matter,
    rendered from the data (the front matter left out); any other page as it is. The docs'
    unit tests read pages through it, so they check what a reader sees."""
    import yaml
    text = pathlib.Path(path).read_text(encoding="utf-8")
    m = FRONT.match(text)
    if not (m and (yaml.safe_load(m.group(1)) or {}).get("render_macros")):
        return text
    return environment().from_string(text[m.end():]).render()


def define_env(env):
    """mkdocs-macros-plugin's entry point."""
    env.variables.update(variables())
    for name, fn in MACROS.items():
        env.macro(fn, name)
