"""The real structure's CA trace in the model's layer frame (Z = the fibril axis through the
origin, layer 0 = the reference layer): for drawing it beside the coarse model."""
from __future__ import annotations

import numpy as np

from . import domain, reading
from .fibril import FibrilGeometry


def layer_frame(fibril: FibrilGeometry) -> tuple:
    """(origin, 3×3 rows X, Y, Z) of the layer frame, in the file's coordinates."""
    z = np.array(fibril.axis["direction"], float)
    x = np.array(fibril.axis["x"], float)
    return np.array(fibril.axis["point"], float), np.array([x, np.cross(z, x), z])


def ca_trace(path, fibril: FibrilGeometry, option: str = "--fibril") -> list:
    """[(chain, residue numbers, CA (n, 3) in the layer frame)] for every layer of the file,
    bottom to top per protofilament (symmetry copies built as for the measurement)."""
    loaded = reading.load(path, option, peptides=True)
    if len(loaded.chains) < 2:
        reading.expand_symmetry(loaded)
    origin, frame = layer_frame(fibril)
    chains = {c.name: c for c in loaded.chains}
    return [(name, chains[name].residues, (chains[name].ca - origin) @ frame.T)
            for q in fibril.layer_chains for name in q]


def relative_layers(fibril: FibrilGeometry) -> list:
    """Each chain of ca_trace's list (same order): its layer counted from the reference layer
    (the model's layer 0): -2, -1, 0, 1, ... per protofilament, bottom to top."""
    out = []
    for q, anchor in zip(fibril.layer_chains, fibril.anchors):
        ref = q.index(anchor["chain"])
        out.extend(i - ref for i in range(len(q)))
    return out


def on_model(chains: list, layers: list, model_layers: int, rise: float, twist: float) -> list:
    """ca_trace's chains (in the layer frame: the reference layer on the model's layer 0) moved
    by a whole number of layers along the model's screw (turn s·twist, rise s·rise), so that the
    file's layers sit on the model's layers, centred in its stack of `model_layers`: the
    deposited fibril inside the slabs, same axis, same layer phase. `layers`: relative_layers.
    Returns [(chain, residues, xyz)] and s."""
    lo, hi = min(layers), max(layers)
    s = (model_layers - 1 - (hi - lo)) // 2 - lo
    c, sn = np.cos(s * twist), np.sin(s * twist)
    turn = np.array([[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]])
    moved = [(name, residues, np.asarray(xyz, float) @ turn.T + (0.0, 0.0, s * rise))
             for name, residues, xyz in chains]
    return moved, s


def domain_ca(path, *, chain: str | None = None, residues=None, option: str = "--domain") -> list:
    """[(chain, residue numbers, CA (n, 3))] of the domain as `inspect --domain` measures it,
    in its body frame (the file's coordinates less the heavy atoms' centroid: the globule's own
    frame, domain.body_frame), in Å as the model."""
    loaded = reading.load(path, option)
    c, keep, _ = domain.select(loaded, chain=chain, residues=residues, option=option)
    used = np.unique(c.heavy_residue[keep])
    ca_keep = (c.residues >= used[0]) & (c.residues <= used[-1])
    centroid, _ = domain.body_frame(c.heavy[keep])
    return [(c.name, c.residues[ca_keep], c.ca[ca_keep] - centroid)]
