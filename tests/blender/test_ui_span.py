"""The sidebar's result box says how far the linkers span of their full length (the result's
`linker_stretch`, docs/model/linker-integrity.md#linker-span) in the printed result's words,
under the worst bond's line, for the run the box shows: a new check's replaces the last, a bake
or Clear takes it with the rest of the result."""
import bpy
from ui_fakes import FakeLayout, run, run_steps, stored_result
from ui_fakes import ui  # noqa: F401 (a fixture)

from fibrilfit.exports.span_words import end_to_end
from fibrilfit.ui import panels

SAID = "end to end: "  # where the printed result's line starts (exports/span_words.py)


def _labels(context) -> list:
    log = []
    panels.draw_run(FakeLayout(log), context)
    return [text for kind, text in log if kind == "label"]


def _printed(result: dict) -> str:
    """The printed result's line on the linkers' span (exports/run_text.py prints
    end_to_end's), without its label."""
    line = end_to_end(result["linker_stretch"])
    assert line.startswith(SAID)
    return line[len(SAID):]


def _box_span(labels: list) -> str:
    """The box's lines from "End to end: " to the next line of its own (the bound's, the
    colours' note), joined as one text, without the label."""
    at = next(i for i, t in enumerate(labels) if t.startswith("End to end: "))
    assert labels[at - 1].startswith("Max stretch ")  # the linker's evidence, together
    lines = [labels[at][len(SAID):]]
    for t in labels[at + 1:]:
        if t.startswith(("Bound:", "Impossible below", "Red: clash", "Lengths in")):
            break
        lines.append(t)
    return " ".join(lines)


def test_the_box_says_the_shown_runs_span_in_the_printed_results_words(ui, scene):
    run_steps()
    first = stored_result(scene)
    assert first["linker_stretch"]["linkers"] == 8  # SMALL: 8 layers, every one scored
    assert _box_span(_labels(bpy.context)) == _printed(first)
    ui.score_layers = 2  # a new check of the same layout: the middle 4 layers' linkers
    run("check_intersections")
    second = stored_result(scene)
    assert second["linker_stretch"]["linkers"] == 4
    shown = _box_span(_labels(bpy.context))
    assert shown == _printed(second) and shown != _printed(first)
    assert "(median of 4;" in shown
    run("bake")  # a new bake: the last check's result is gone, its span too
    assert ui.linker_stretch == ""
    assert not any(t.startswith("End to end") for t in _labels(bpy.context))
    run("check_intersections")
    assert _box_span(_labels(bpy.context)) == _printed(stored_result(scene))
    run("clear")
    assert ui.linker_stretch == ""
    assert not any(t.startswith("End to end") for t in _labels(bpy.context))
