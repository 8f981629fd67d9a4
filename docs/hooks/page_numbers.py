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
  docs/notebook/search.md#map-v5 publishes it (bench/docs_map.py reads it), `layers20` from
  docs/minimal_linker.csv;
- `defaults`: the code's own defaults (fibrilfit.model.params.DEFAULTS and each command's plan),
  so a page never restates a default by hand;
- `model_version`: the code's MODEL_VERSION.

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
    rows = {}
    with open(DATA / "costs.csv", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            r = dict(r)
            r["wall_s"] = float(r["wall_s"])
            r["minutes"] = round(r["wall_s"] / 60, 1)
            r["model_version"] = int(r["model_version"])
            rows[r["key"]] = r
    return rows


@functools.lru_cache(maxsize=None)
def reports() -> dict[str, dict]:
    return {p.stem: json.loads(p.read_text(encoding="utf-8"))
            for p in sorted((DATA / "reports").glob("*.json"))}


@functools.lru_cache(maxsize=None)
def maps() -> dict[str, dict[int, int]]:
    spec = importlib.util.spec_from_file_location("docs_map", ROOT / "bench" / "docs_map.py")
    docs_map = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(docs_map)
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


def variables() -> dict:
    return {"costs": costs(), "reports": reports(), "maps": maps(), "defaults": defaults(),
            "model_version": model_version()}


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


def cost_table() -> str:
    """docs/data/costs.csv as one Markdown table: command × system × size × protofilaments."""
    mv = model_version()
    head = ("| command | system | layers | protofilaments | restarts | minutes on 2 cores "
            "(wall s) | answer | load | measured |\n|---|---|---|---|---|---|---|---|---|\n")
    lines = []
    for r in costs().values():
        when = f"{r['date']}, {r['commit']}, MODEL_VERSION {r['model_version']}, bpy {r['bpy']}"
        if r["model_version"] != mv:
            when += " (**older than the code's**)"
        lines.append(f"| `{r['command']}` | {r['system']} | {r['layers']} | {r['protofilaments']} "
                     f"| {r['restarts']} | {r['minutes']} ({r['wall_s']:.1f}) | {r['answer']} "
                     f"| {r['load_before']} → {r['load_after']} | {when} |")
    return head + "\n".join(lines)


MACROS = {"took": took, "stamp": stamp, "report_stamp": report_stamp, "pct": pct,
          "cost_table": cost_table, "pfit": pfit, "minimal": minimal, "tried": tried,
          "wilson": wilson, "first_map_transition": first_map_transition}


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
