"""Draw a `--pdb-atoms` mmCIF as two projections (down the fibril axis, and from the side), core
chains grey, linker beads orange, domains coloured by chain: a picture for the docs where no
molecular viewer is at hand (docs/tutorial.md#atoms). Usage: python tools/atoms_picture.py IN.cif OUT.png"""
import sys

import gemmi
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(src: str, dst: str) -> None:
    st = gemmi.read_structure(src)
    groups = {"core": [], "linker": [], "domain": []}
    for ch in st[0]:
        for res in ch:
            for at in res:
                kind = "linker" if res.name == "UNK" else "domain" if len(ch.name) > 2 and \
                    ch.name[-1].isdigit() else "core"
                groups[kind].append(at.pos.tolist())
    fig, axes = plt.subplots(1, 2, figsize=(10, 5), dpi=100)
    colours = {"core": "0.55", "linker": "tab:orange", "domain": "tab:blue"}
    for ax, (i, j), title in ((axes[0], (0, 1), "down the fibril axis"),
                              (axes[1], (0, 2), "from the side")):
        for kind, pts in groups.items():
            if pts:
                p = np.asarray(pts)
                ax.scatter(p[:, i], p[:, j], s=1, c=colours[kind], label=kind, linewidths=0)
        ax.set_aspect("equal")
        ax.set_title(title)
        ax.set_xlabel("Å")
    axes[0].legend(markerscale=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(dst)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
