"""report.html: one self-contained page (pictures embedded as base64, no outside file, no
script) from report.json's document, to keep, share or paste into a lab notebook.

Plain functions over the document (search/report.py makes it): no bpy, so the page can be
rebuilt from a report.json alone (`html(json.load(...), folder)`).
"""
from __future__ import annotations

import base64
import html as _html
import math
import pathlib
import shlex

from ..model.searches import search_words
from . import ensemble_words
from .run_text import count
from .span_words import span_words

STYLE = """
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;max-width:1100px;margin:24px auto;
padding:0 16px;color:#1d232a;line-height:1.45}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.15em;border-bottom:1px solid #ccd;
padding-bottom:3px;margin-top:1.6em}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #d5d8de;padding:3px 9px;
text-align:left;vertical-align:top}th{background:#f1f3f6}
.answer{font-size:1.25em;padding:10px 14px;border-radius:6px;margin:.8em 0}
.fits{background:#e3f5e6;border:1px solid #58a866}.borderline{background:#fff6dc;
border:1px solid #d6a629}.none{background:#fbe6e4;border:1px solid #c8574c}
.warn{background:#fff6dc;border-left:4px solid #d6a629;padding:4px 10px;margin:3px 0}
pre{background:#f4f5f7;padding:8px 10px;overflow-x:auto;white-space:pre-wrap}
img{max-width:100%;border:1px solid #ccd}.small{color:#5a6270;font-size:.9em}
"""


def esc(value) -> str:
    return _html.escape(str(value), quote=True)


def fmt(value) -> str:
    """A parameter value as a biologist reads it (angles also in degrees)."""
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        if len(value) > 4:
            return f"{len(value)} points"
        return ", ".join(fmt(v) for v in value)
    return str(value)


def interval(pair) -> str:
    return "–" if not pair else f"{pair[0]:.2f}–{pair[1]:.2f}"


def embedded(folder: pathlib.Path, name: str | None, alt: str) -> str:
    """An <img> with the picture inside the page (data: URI), or a line saying it is missing."""
    path = folder / name if name else None
    if path is None or not path.is_file():
        return f'<p class="small">({esc(alt)}: not drawn; see the warnings)</p>'
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f'<img alt="{esc(alt)}" src="data:image/png;base64,{data}">'


def answer_text(doc: dict) -> tuple[str, str]:
    """(css class, sentence) for the answer."""
    pf, word = doc["p_fit"], doc["answer"]
    m = doc["minimal_linker"]
    at = (f"{pf['fits']} of {pf['runs']} restarts at linker {pf['linker']} found a clash-free "
          f"layout with intact linkers")
    if word == "fits":
        return "fits", f"Fits. {at} (protocol {pf['protocol']})."
    if word == "borderline":
        return "borderline", (f"Borderline. {at}; the best layout sits at the criterion "
                              f"(stretch within 1 point of the tolerance, or grazing contacts "
                              f"only).")
    more = (f" The minimal linker found is {m['linker']}." if m.get("linker") else "")
    return "none", (f"No layout found in {pf['runs']} restarts at linker {pf['linker']} "
                    f"(protocol {pf['protocol']}). This is not a proof that none exists.{more}")


def model_rows(doc: dict) -> str:
    model, sources = doc["model"], doc.get("sources") or {}
    rows = []
    for key, value in model.items():
        deg = ""
        if key in ("twist", "pf_rotation") and isinstance(value, (int, float)):
            deg = f" ({math.degrees(value):.3f}°)"
        rows.append(f"<tr><td>{esc(key)}</td><td>{esc(fmt(value))}{esc(deg)}</td>"
                    f"<td>{esc(sources.get(key, 'default'))}</td></tr>")
    return ("<table><tr><th>parameter</th><th>value (Å, rad, frames)</th><th>source</th></tr>"
            + "".join(rows) + "</table>")


def occupancy_text(doc: dict) -> str:
    """A mixed fibril: the fraction's row, and what the answer and P(fit) speak of."""
    occ = doc.get("occupancy")
    if not occ:
        return ""
    rows = [("fraction carrying the domain", f"{100 * occ['fraction']:.4g} %"),
            ("pattern", occ["pattern_words"]), ("the answer speaks of", occ["speaks_of"]),
            ("P(fit) counts", occ["p_fit_counts"])]
    fb = doc.get("fraction_bracket")
    if fb:
        rows.append((f"the bracket on the fraction at linker {fb['linker']}", fb["text"]))
    return ("<h2>Occupancy</h2><table>" + "".join(f"<tr><th>{esc(a)}</th><td>{esc(b)}</td></tr>"
                                                for a, b in rows) + "</table>")


def fraction_plot_text(doc: dict, folder: pathlib.Path) -> str:
    """--fraction-plot: P(fit) at each fraction asked, at the report's linker, as a table (the
    plot's numbers) and the plot."""
    fp = doc.get("fraction_plot")
    if not fp:
        return ""

    def cells(r):
        failed = f" ({r['failed']} failed)" if r["failed"] else ""
        p = "–" if r["p_fit"] is None else f"{r['p_fit']:.2f}"
        return (f"<tr><td>{r['fraction_asked']:g}</td><td>{r['decorated']} of {r['subunits']} "
                f"({100 * r['fraction']:.4g} %)</td><td>{r['fits']}/{r['restarts']}{failed}</td>"
                f"<td>{p}</td><td>{interval(r['interval'])}</td>"
                f"<td>{'the report’s' if r['report_fraction'] else ''}</td></tr>")
    rows = "".join(cells(r) for r in fp["rows"])
    first, last = fp["rows"][0]["seeds"]
    return (f"<h2 id='fraction-plot'>P(fit) against the fraction at linker {fp['linker']}</h2>"
            f"<p>Each fraction: the report's model with that share of its subunits carrying the "
            f"domain (pattern random: each restart draws its own subunits with its seed), "
            f"{fp['restarts']} restarts, seeds {first}–{last}, protocol {esc(fp['protocol'])}; "
            f"P(fit) with its {esc(fp['interval'])} interval.</p>"
            f"<table><tr><th>fraction asked</th><th>decorated subunits</th>"
            f"<th>accommodated</th><th>P(fit)</th><th>95 % Wilson</th><th></th></tr>{rows}"
            f"</table>{embedded(folder, doc['files'].get('fraction_plot'), 'fraction plot')}")


def linker_rows(doc: dict) -> str:
    m, pf = doc["minimal_linker"], doc["p_fit"]
    tried = m.get("tried") or {}
    rows = "".join(
        f"<tr><td>{esc(L)}</td><td>{t['accommodated']}/{t['restarts']}</td>"
        f"<td>{'fits' if t['accommodated'] else 'no layout found'}</td></tr>"
        for L, t in sorted(tried.items(), key=lambda kv: int(kv[0])))
    found = (f"<b>{count(m['linker'], 'residue')}</b>: P(fit) {m['p_fit']:.2f} "
             f"(95 % Wilson {interval(m['interval'])})" if m.get("linker") else
             f"none up to {count(m['max_linker'], 'residue')}")
    if m.get("stopped_at_fit"):
        found += (f" from {count(m['runs'], 'restart')}, stopped at the first fit (the others could not "
                  f"change that it fits)")
    if m.get("below_settled_by_bound"):
        below = (f"; one below, at {m['linker_below']}: no layout possible, by the proven bound "
                 f"({count(m['floor'], 'residue')} at least), not simulated")
    else:
        below = (f"; one below, at {m['linker_below']}: P(fit) {m['p_fit_below']:.2f} "
                 f"(95 % Wilson {interval(m['interval_below'])})"
                 if m.get("p_fit_below") is not None else "")
    br = doc.get("bracket")
    if br:
        hi = br["open"][1] if br.get("open") else None
        bracket = (f"<p><b>The bracket</b>: impossible below {count(br['impossible_below'], 'residue')} "
                   f"(proof: the geometry, the proven bound)"
                   + (f"; fits at {br['fits_at']} (proof: a layout)" if br.get("fits_at") else "")
                   + (f"; open from {br['impossible_below']} to {hi}: neither proof reaches "
                      f"there" if hi is not None else "; closed" if br.get("fits_at") else "")
                   + ".</p>")
    else:
        bracket = ""
    return (f"{bracket}<p>Minimal linker: {found}{below}. Restarts per length: up to {m['restarts']}, "
            f"protocol {esc(pf['protocol'])}, seeds {pf['seeds'][0]}–{pf['seeds'][1]}.</p>"
            f"<table><tr><th>linker</th><th>accommodated</th><th>reading</th></tr>{rows}"
            f"</table><p class='small'>{esc(m.get('method', ''))}</p>")


def margin_text(doc: dict) -> str:
    g = doc["margin"]
    parts = []
    if g.get("linker_residues") is not None:
        n = g["linker_residues"]
        parts.append(f"the linker asked for is {count(abs(n), 'residue')} "
                     f"{'longer' if n >= 0 else 'shorter'} than the minimal linker")
    if g.get("stretch_margin") is not None:
        parts.append(f"the best layout's worst linker bond is stretched "
                     f"{100 * g['best_max_bond_stretch']:.1f} % against a tolerance of "
                     f"{100 * g['stretch_tolerance']:.1f} % (margin "
                     f"{100 * g['stretch_margin']:+.1f} points)")
    return "<p>Margin: " + ("; ".join(parts) or "not known") + ".</p>"


def envelope_text(doc: dict) -> str:
    e = doc["envelope"]
    best = e.get("best_layout") or {}
    over = e.get("outer_diameter_over_restarts")
    cells = [*ensemble_words.cells(doc.get("ensemble")),
             ("best layout: outer diameter", f"{best['outer_diameter']:.0f} Å"
              if best.get("outer_diameter") is not None else "–")]
    if over:
        cells.append(("over the restarts", f"median {over['median']:.0f} Å "
                                          f"({over['min']:.0f}–{over['max']:.0f})"))
    cells.append(("measured width (case)", f"{e['measured_width']:.0f} Å"
                  + (f" — {e['measured_width_source']}" if e.get("measured_width_source")
                     else "") if e.get("measured_width") else "none given"))
    return "<table>" + "".join(f"<tr><th>{esc(a)}</th><td>{esc(b)}</td></tr>"
                               for a, b in cells) + "</table>"


ENSEMBLE_CAPTION = ("The ensemble (docs/model/ensemble.md#density-map). Left: its helically "
                    "averaged map (domains and core) projected perpendicular to the axis over one "
                    "helical turn, the width's edges dashed. Middle: that projection's profile "
                    "across the axis; the width is the distance between its outermost points at "
                    "{pct:.0f} % of its peak. Right: the radial density of domain mass, its peak "
                    "dashed, the outer radius's 95 % interval shaded.")


def ensemble_picture(doc: dict, folder) -> str:
    """The ensemble's picture (exports/ensemble_plot.py) with its caption, if sampled."""
    e = doc.get("ensemble")
    if not e:
        return ""
    caption = (ENSEMBLE_CAPTION.format(pct=100 * e["width"]["fraction_of_peak"])
               if e.get("sampled") else "")
    return (embedded(pathlib.Path(folder), doc["files"].get("ensemble_plot"), "ensemble")
            + (f'<p class="small">{esc(caption)}</p>' if caption else ""))


def html(doc: dict, folder) -> str:
    """The page."""
    folder = pathlib.Path(folder)
    css, sentence = answer_text(doc)
    pf = doc["p_fit"]
    b = doc["best_layout"]
    warnings = "".join(f'<div class="warn">{esc(w)}</div>' for w in doc["warnings"]) or \
        "<p>None.</p>"
    versions = ", ".join(f"{k} {v}" for k, v in doc["versions"].items())
    files = doc["files"]
    command = shlex.join(doc["command"]) if doc.get("command") else "(not recorded)"
    p = f"{pf['p']:.2f}" if pf.get("p") is not None else "n/a"
    span = (f"; end to end, {esc(span_words(b['linker_stretch']))}"
            if b.get("linker_stretch") else "")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>FibrilFit report</title>
<style>{STYLE}</style></head><body>
<h1>FibrilFit report</h1>
<p class="small">{esc(versions)}</p>
<h2>The question</h2><p>{esc(doc['question'])}</p>
<div class="answer {css}">{esc(sentence)}</div>
{occupancy_text(doc)}{fraction_plot_text(doc, folder)}<h2>P(fit) at linker {pf['linker']}</h2>
<p>{pf['fits']} of {pf['runs']} restarts accommodated: P(fit) {p}
(95 % Wilson interval {pf['low']:.2f}–{pf['high']:.2f}){', ' + str(pf['failed']) +
' failed to run' if pf.get('failed') else ''}. Best layout: seed {b['seed']}, verdict
{esc(b['verdict'])}, {b['clashing_pairs']} clashing pair(s) of which {b['grazing_pairs']}
only graze, worst linker stretch {100 * (b['max_bond_stretch'] or 0):.1f} %{span}.
P(fit) by {esc(search_words(pf['protocol']))}.</p>
{margin_text(doc)}
<h2>Minimal linker</h2>{linker_rows(doc)}
{embedded(folder, files.get('bracket_plot'), 'bracket figure') if doc.get('bracket_figure') else ''}
<h2>The best layout</h2>{embedded(folder, files.get('render'), 'best layout render')}
<h2>The envelope</h2>{envelope_text(doc)}
{embedded(folder, files.get('envelope_plot'), 'envelope plot')}
{ensemble_picture(doc, folder)}
<h2>Warnings</h2>{warnings}
<h2>The model and where each value came from</h2>{model_rows(doc)}
<h2>To reproduce</h2><pre>{esc(command)}</pre>
<p class="small">Files beside this page: {esc(', '.join(str(v) for v in files.values()))}.</p>
</body></html>
"""
