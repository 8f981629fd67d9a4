"""`--fibril FILE` / `--domain FILE` for `run` and `sweep`: the model values measured from the
files, the explicit options winning, and the `structure` block a result records."""
from __future__ import annotations

from .mapping import model_values


def block(fibril, domain, applied: dict, overridden: dict, not_in_model: list) -> dict:
    """What a result says it was computed from: files, sha256, measurements, what was used."""
    out = {}
    for key, m in (("fibril", fibril), ("domain", domain)):
        if m is not None:
            out[key] = {"file": m.file, "sha256": m.sha256, "measured": m.to_dict()}
    out["applied"] = {k: ("[... %d rows]" % len(v) if k in ("domain_atoms", "domain_spheres")
                          else v) for k, v in applied.items()}
    out["overridden"] = sorted(overridden)  # measured, but an explicit option set the value
    out["not_in_model"] = not_in_model  # measured, but this model has no such parameter
    return out


def split(fibril, domain, *, explicit: set, known: set, residue_radius: float = 1.75,
          shape: str = "sphere"):
    """(values to apply, structure block). `explicit`: parameters given as options (they win);
    `known`: the model's parameter names; `shape`: the domain_shape asked for."""
    values = model_values(fibril, domain, residue_radius=residue_radius, shape=shape)
    applied = {k: v for k, v in values.items() if k in known and k not in explicit}
    overridden = {k: v for k, v in values.items() if k in explicit}
    missing = sorted(k for k in values if k not in known)
    return applied, block(fibril, domain, applied, overridden, missing)
