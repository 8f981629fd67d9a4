"""The panel's words for options and internal names (fibrilfit/ui/panel_words.py, issue #45
item 7): labels in the panel's messages, never `--fibril:` or `core_outline`."""
from fibrilfit.model.params import ParamError
from fibrilfit.plans import PlanError
from fibrilfit.structure.errors import StructureError
from fibrilfit.ui.panel_words import error_words, in_panel_words, labels


def test_errors_name_the_field_by_its_label():
    assert error_words(ParamError("pf_rise", "must be between 0 and 10")) == \
        "Protofilament rise: must be between 0 and 10"
    assert error_words(ParamError("linker", "must be at least 1")) == "Linker: must be at least 1"
    assert error_words(StructureError("--fibril", "no chain")) == "Fibril file: no chain"
    assert error_words(StructureError("--domain-chain", "no chain Q")) == \
        "Domain chain: no chain Q"
    assert error_words(PlanError("max_linker", "must be at least 1")) == \
        "Longest linker: must be at least 1"


def test_names_inside_a_message_become_labels_but_paths_do_not():
    text = in_panel_words("set anchor, core_outline, pf_rise; see --domain-linker in "
                          "/data/core_outline.json and my_fibril.pdb")
    assert text == ("set anchor, Core outline, Protofilament rise; see Domain linker in "
                    "/data/core_outline.json and my_fibril.pdb")
    assert labels(["pf_rotation", "globule_diameter"]) == "Protofilament turn, Globule diameter"
