"""How the linker is counted (docs/guide/construct.md#counting): the core's last ordered residue
(the anchor), the residues a buried terminus spends getting out (the exit), the free linker
the relaxation moves, and the domain's joint; drawn with matplotlib for an example linker of 8
with an exit of 2 residues, and stamped (tools/picture_stamp.py).

    python tools/linker_figure.py [OUT.png]      # default docs/images/linker-count.png

The numbers drawn are the counting rule's (docs/model/buried-terminus.md#counting), not a
measurement: residues spent on the exit = ceil(length / spacing) - 1; free residues = linker -
exit - 1; every residue 3.5 Å (residue_spacing) from the next, fully stretched.
"""
from __future__ import annotations

import importlib.util
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, FancyBboxPatch  # noqa: E402


def _picture_stamp():
    """tools/picture_stamp.py, loaded by its path (tools/ is not a package)."""
    spec = importlib.util.spec_from_file_location(
        "picture_stamp", pathlib.Path(__file__).resolve().parent / "picture_stamp.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


picture_stamp = _picture_stamp()

ROOT = pathlib.Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "images" / "linker-count.png"
LINKER, EXIT = 8, 2          # the example: linker 8, a buried terminus that spends 2 residues
SPACING, BEAD = 3.5, 1.75    # Å: the model's residue_spacing and residue_radius


def draw(out: pathlib.Path) -> None:
    free = LINKER - EXIT - 1
    fig, ax = plt.subplots(figsize=(10, 4.2), dpi=110)
    ax.set_aspect("equal")
    ax.axis("off")
    # the core: one layer's cross-section, the surface at x = 0
    ax.add_patch(FancyBboxPatch((-24, -9), 24, 18, boxstyle="round,pad=0.4", fc="0.85", ec="0.4"))
    ax.text(-12, 6.3, "the fibril's core\n(one layer)", ha="center", va="center", fontsize=9)
    ax.plot([0, 0], [-10, 10], color="0.3", lw=1, ls=":")
    ax.text(0.3, -11.2, "surface", fontsize=8, color="0.3")
    # anchor, inside (buried), then the exit's residues on their path to the surface
    xs = [-EXIT * SPACING + i * SPACING for i in range(EXIT + 1)]
    core_res = [xs[0] - SPACING * k for k in (2, 1)]
    for x in core_res:
        ax.add_patch(Circle((x, 0), BEAD, fc="0.6", ec="0.3"))
    ax.add_patch(Circle((xs[0], 0), BEAD, fc="tab:red", ec="k", zorder=3))
    for x in xs[1:]:
        ax.add_patch(Circle((x, 0), BEAD, fc="gold", ec="k", zorder=3))
    # the free linker, out to the domain
    fx = [xs[-1] + SPACING * (i + 1) for i in range(free)]
    for x in fx:
        ax.add_patch(Circle((x, 0), BEAD, fc="tab:orange", ec="k", zorder=3))
    r = 9.0
    joint = fx[-1] + SPACING
    ax.add_patch(Circle((joint + r, 0), r, fc="tab:blue", alpha=0.55, ec="k"))
    ax.plot([joint], [0], marker="x", color="k", ms=9, mew=2, zorder=4)
    ax.text(joint + r, 0, "domain", ha="center", va="center", fontsize=10, color="white")
    # labels
    ax.annotate("anchor: the core's last\nordered residue (counted)", (xs[0], -BEAD),
                (xs[0] - 6, -17), ha="center", fontsize=8.5, arrowprops={"arrowstyle": "->"})
    ax.annotate("joint: the domain's first\nresidue's CA (not counted)", (joint, -0.5),
                (joint + 8, -17), ha="center", fontsize=8.5, arrowprops={"arrowstyle": "->"})

    def brace(x0, x1, y, text, colour):
        ax.annotate("", (x0 - BEAD, y), (x1 + BEAD, y),
                    arrowprops={"arrowstyle": "|-|", "color": colour, "lw": 1.4})
        ax.text((x0 + x1) / 2, y + 1.0, text, ha="center", va="bottom", fontsize=8.5,
                color=colour)
    brace(xs[1], xs[-1], 3.6, f"exit {EXIT}", "darkgoldenrod")
    brace(fx[0], fx[-1], 3.6, f"free linker {free}", "tab:orange")
    brace(xs[0], fx[-1], 13.0, f"linker {LINKER} = 1 anchor + {EXIT} exit + {free} free", "k")
    ax.text(core_res[0], -4.3, "core residues", fontsize=8, color="0.3", ha="center")
    ax.text(-25, -23, "gold: the exit, residues a buried anchor spends to reach the "
            "surface (held on their path)\norange: the free linker, moved by the relaxation; "
            f"every bond {SPACING} Å, fully stretched", fontsize=8, color="0.2", va="top")
    ax.set_xlim(-26, joint + 2 * r + 2)
    ax.set_ylim(-28, 20)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out)
    plt.close(fig)
    picture_stamp.stamp(out, "tools/linker_figure.py (make pictures)")


if __name__ == "__main__":
    draw(pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else OUT)
