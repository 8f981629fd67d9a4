"""scene.fibrilfit.domains: the sidebar's list of a chain's domains (docs/guide/sidebar.md#domains),
the command line's `--domain FILE ... --domain-linker ...`; the logic is structure/domain_list.py.

Each entry keeps its file, chain, residues, its measurement (JSON) and the linker to the next
domain. The panel's parameters read the list (values_from_list: the real-shape rows for the panel's
domain shape, and domain_linker); a change of the list (filled) writes the diameters, and the
linker from the numbering when the fibril's and the first domain's agree, into the panel's own
fields, where the user may still edit them as the command line's options override what a file
measured.
"""
import bpy
from bpy.props import IntProperty, StringProperty

from ..model import params as P
from ..structure import domain_list as logic

LINKER_MAX = P.field_spec("domain_linker")["max"]


class FIBRILFIT_PG_domain(bpy.types.PropertyGroup):
    """One domain of the chain (the list's `name` is what it shows)."""

    filepath: StringProperty(name="File", subtype="FILE_PATH",
                             description="The domain's structure file")
    chain: StringProperty(name="Chain", description="The domain's chain in its file")
    residues: StringProperty(name="Residues", description="The domain's residues, a-b")
    option: StringProperty(name="Option", default="--domain", options={"HIDDEN"},
                           description="--domain, or --full-length for a domain of a "
                                       "full-length model")
    measured: StringProperty(name="Measured", options={"HIDDEN"},
                             description="The domain's measurement, its shape included (JSON)")
    linker: IntProperty(name="Linker to next", min=0, max=LINKER_MAX, default=10,
                        description="Residues between this domain and the next one outward "
                                    "(the command line's --domain-linker); the last domain's "
                                    "is not used")


class FIBRILFIT_UL_domains(bpy.types.UIList):
    """A row per domain, short enough for the default sidebar (issue #45 item 9): its file's
    name, chain, residues and diameter; the selected domain's linker to the next is set under
    the list (panels.draw_domains)."""

    def draw_item(self, context, layout, data, item, icon, active_data, active_propname,
                  index=0, flt_flag=0):
        layout.label(text=row_text(item), icon="MESH_UVSPHERE")


def file_stem(path: str) -> str:
    """A structure file's name without its folder and extensions: 1gfl for /x/1gfl.pdb.gz."""
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    for ext in (".gz", ".pdb", ".ent", ".cif", ".mmcif", ".mcif"):
        name = name[:-len(ext)] if name.lower().endswith(ext) else name
    return name


def row_text(e) -> str:
    """A list entry as its row shows it: "1gfl A 2-231, 44 Å"."""
    d = logic.from_text(e.measured).globule_diameter if e.measured else 0.0
    return f"{file_stem(e.filepath)} {e.chain} {e.residues}, {d:.0f} Å"


CLASSES = (FIBRILFIT_PG_domain, FIBRILFIT_UL_domains)


def domains(settings) -> list:
    """The list's measured domains (structure.DomainSize), from the core outward."""
    return [logic.from_text(e.measured) for e in settings.domains]


def values_from_list(settings, values: dict) -> dict:
    """The values the list gives over the panel's `values` (properties.values): none when it is
    empty; else the shape's rows for values' domain_shape, and domain_linker."""
    if not len(settings.domains):
        return {}
    return logic.shape_values(domains(settings), [e.linker for e in settings.domains],
                              shape=values["domain_shape"],
                              residue_radius=values["residue_radius"],
                              residue_spacing=values["residue_spacing"])


def add(settings, path: str, dom, *, option: str = "--domain") -> None:
    """Append a measured domain (logic.measure) to the list and make it the active entry."""
    e = settings.domains.add()
    e.filepath, e.chain, e.option = path, dom.chain, option
    e.residues = f"{dom.residues[0]}-{dom.residues[1]}"
    e.measured = logic.to_text(dom)
    e.name = f"{dom.file} {dom.chain} {e.residues}, {dom.globule_diameter:.1f} Å"
    settings.domain_index = len(settings.domains) - 1


def replace(settings, measured: list, option: str, linkers) -> None:
    """The list made of `measured` [(path, DomainSize)] in chain order (`option`: --domain or
    --full-length), each linker to the next from `linkers` (Params.domain_linker, None with one
    domain); the fields the list gives (its real-shape rows, domain_linker) emptied, the
    diameters left as they are (Load case: a case's [structure], already in the panel)."""
    settings.domains.clear()
    for path, dom in measured:
        add(settings, path, dom, option=option)
    for e, gap in zip(settings.domains, linkers or ()):
        e.linker = gap
    settings.domain_index = 0
    for name in logic.SHAPE_PARAMS + ("domain_linker",):
        setattr(settings, name, "")


def filled(settings, fibril: dict | None, *, first_changed: bool) -> list:
    """After the list changed: the diameters from its domains, domain_linker's text and the
    real-shape rows emptied (the list gives them), and when the first domain changed, the linker
    from the numbering when it applies. Returns the names of the fields written."""
    for name in logic.SHAPE_PARAMS + ("domain_linker",):
        setattr(settings, name, "")
    if not len(settings.domains):
        settings.domain_diameters = ""
        return []
    doms = domains(settings)
    size = logic.sizes(doms)
    settings.globule_diameter = size["globule_diameter"]
    settings.domain_diameters = ", ".join(f"{d:g}" for d in size["domain_diameters"] or ())
    written = ["globule_diameter"] + (["domain_diameters"] if len(doms) > 1 else [])
    linker = logic.numbering_linker(fibril, doms[0]) if first_changed else None
    if linker is not None:
        settings.linker = linker
        written.append("linker")
    return written


def set_gaps(settings, fibril: dict | None, start: int = 0) -> None:
    """The linkers between the list's domains from `start` on, from their numbering where it
    runs outward (a full-length model's always does); left as they are otherwise."""
    doms = domains(settings)
    found = logic.gaps(doms[start:], fibril)
    for e, gap in zip(list(settings.domains)[start:], found or ()):
        e.linker = gap
