"""Which subunits carry the domain (issue #44): the pattern of a mixed fibril, in one place.

Pure numpy (no bpy). A subunit is one chain of the model: (layer, protofilament), numbered
layer-major like helix.chain_layers (chain c = layer * K + protofilament). The pattern is drawn
on the model's own subunits: the fibril's `layers` × K, or a periodic cell's M × K, which the
cell's images then repeat every M layers (docs/model/occupancy.md#what-fits-at-f-means).

- random: a seeded permutation of the N subunits; its first round(f·N) carry the domain. An
  exact count, and nested: under one seed a lower fraction's subunits are a subset of a higher
  one's, so a lower fraction never holds a pair of neighbours a higher one lacks.
- periodic: every k-th subunit from the first, counted along each protofilament (every k-th
  layer of each) or over the fibril (layer-major).
- layers: one letter per layer ('A' the domain, 'B' a second domain, '.' none), repeated along
  the fibril. A 'B' subunit is decorated too, with the second domain (domain_b_diameter, a
  sphere, on its own linker linker_b): a hetero-amyloid (docs/model/occupancy.md#hetero).
"""
from __future__ import annotations

import numpy as np

from . import helix
from .param_spec import ParamError

# Keeps the pattern's random stream apart from the gravity's and the start layouts' under one
# seed (start_layout.SEED_SALT is another): a seed fixes the pattern and the start together.
PATTERN_SALT = 0x0CC0
# a per-layer pattern's letters: whether the subunit is decorated (A the domain, B the second
# domain: a hetero-amyloid's other protein, docs/model/occupancy.md#hetero; '.' none)
LETTERS = {"A": True, "B": True, ".": False}
SECOND_DOMAIN = "B"
# The parameters each pattern reads (the others it ignores: the panel hides them)
PATTERN_FIELDS = {"random": ("occupancy",), "periodic": ("pattern_period", "pattern_across"),
                  "layers": ("pattern_layers",)}


def decorated(p, n_layers: int | None = None, n_pf: int | None = None,
              seed: int | None = None) -> np.ndarray:
    """bool (layers, protofilaments): True where the subunit carries the domain.

    Defaults: the model's layers (a periodic cell's M), protofilaments and seed. Raises
    ParamError for a pattern that cannot be drawn (a count of none, a bad letter)."""
    n_layers = p.layers if n_layers is None else int(n_layers)
    n_pf = p.protofilaments if n_pf is None else int(n_pf)
    seed = p.seed if seed is None else int(seed)
    n = n_layers * n_pf
    if p.pattern == "random":
        count = decorated_count(p.occupancy, n)
        flat = np.zeros(n, dtype=bool)
        flat[draw_order(n, seed)[:count]] = True
        return flat.reshape(n_layers, n_pf)
    if p.pattern == "periodic":
        if p.pattern_across == "fibril":
            return (np.arange(n) % p.pattern_period == 0).reshape(n_layers, n_pf)
        rows = np.arange(n_layers) % p.pattern_period == 0
        return np.repeat(rows[:, None], n_pf, axis=1)
    rows = layer_letters(p.pattern_layers)
    return np.repeat(rows[np.arange(n_layers) % len(rows)][:, None], n_pf, axis=1)


def second_domain(p, n_layers: int | None = None, n_pf: int | None = None) -> np.ndarray:
    """bool (layers, protofilaments): True where the subunit carries the second domain, B
    (a layers pattern's letter B; none otherwise). Defaults as decorated()'s."""
    n_layers = p.layers if n_layers is None else int(n_layers)
    n_pf = p.protofilaments if n_pf is None else int(n_pf)
    if not is_hetero(p):
        return np.zeros((n_layers, n_pf), dtype=bool)
    rows = np.array([ch == SECOND_DOMAIN for ch in letters(p.pattern_layers)])
    return np.repeat(rows[np.arange(n_layers) % len(rows)][:, None], n_pf, axis=1)


def is_hetero(p) -> bool:
    """Whether the pattern puts the second domain (B) on some layers: a hetero-amyloid."""
    return p.pattern == "layers" and SECOND_DOMAIN in letters(p.pattern_layers)


def letters(text: str) -> str:
    """A per-layer pattern's letters as written, without blanks, upper case."""
    return "".join(str(text).split()).upper()


def draw_order(n: int, seed: int) -> np.ndarray:
    """The random pattern's order of N subunits under `seed`: a fraction decorates its first
    round(f·N). The same for every fraction (what makes the draws nested)."""
    return np.random.default_rng([int(seed), PATTERN_SALT, int(n)]).permutation(n)


def decorated_count(fraction: float, n: int) -> int:
    """round(f·N) subunits of N, at least one: a count of none is refused (ParamError)."""
    count = int(np.floor(fraction * n + 0.5))  # half up, not numpy's half to even
    if count < 1:
        raise ParamError("occupancy", f"{fraction:g} of {n} subunits rounds to none: at least "
                                      f"{0.5 / n:.3g} ({100 * 0.5 / n:.3g} %) for this model")
    return min(count, n)


def layer_letters(text: str) -> np.ndarray:
    """A per-layer pattern's letters as bool per layer. Raises ParamError naming what is allowed."""
    text = "".join(str(text).split())
    if not text:
        raise ParamError("pattern_layers", "needs at least one letter: A (the domain), B (the "
                                           "second domain) or . (none)")
    bad = sorted({ch for ch in text.upper() if ch not in LETTERS})
    if bad:
        raise ParamError("pattern_layers", f"has {''.join(bad)!r}: only A (the domain), B (the "
                                           f"second domain) and . (none) (got {text!r})")
    rows = np.array([LETTERS[ch] for ch in text.upper()])
    if not rows.any():
        raise ParamError("pattern_layers", f"carries no domain: give at least one A or B "
                                           f"(got {text!r})")
    return rows


def repeat_layers(p) -> int:
    """Layers after which the pattern repeats along the fibril (a periodic cell must hold a
    whole number of them); 0 for a random draw, which has no repeat of its own."""
    if p.pattern == "layers":
        return len(layer_letters(p.pattern_layers))
    if p.pattern == "periodic":
        if p.pattern_across == "fibril":
            k = p.pattern_period
            return k // int(np.gcd(k, p.protofilaments))  # k·K/gcd subunits: whole layers
        return p.pattern_period
    return 0


def lattice_period(p) -> int:
    """Layers of one period of inflate's lattice start in a cell (helix.auto_cell_layers holds
    whole ones); 1 when there is none."""
    if getattr(p, "protocol", "tutorial") != "inflate" or not helix.lattice_rows(p):
        return 1
    return 2 * helix.lattice_rows(p)


def is_mixed(p) -> bool:
    """Whether some subunit lacks the domain (False: every subunit carries it, as before #44)."""
    if p.pattern == "random":
        return p.occupancy < 1.0 and decorated_count(p.occupancy, p.chains) < p.chains
    return not bool(decorated(p).all())


def decorated_chains(p) -> np.ndarray:
    """The chains (layer-major indices) that carry the domain, ascending."""
    return np.flatnonzero(decorated(p).ravel())


def model_chain_layers(p) -> tuple[np.ndarray, np.ndarray]:
    """(layer, protofilament) of each of the model's chains: the decorated subunits', in the
    order model.chain holds them (every subunit's, helix.chain_layers, when all are decorated)."""
    layer, pf = helix.chain_layers(p)
    if not is_mixed(p):
        return layer, pf
    ids = decorated_chains(p)
    return layer[ids], pf[ids]


def fraction(p) -> float:
    """The fraction of the model's subunits that carry the domain, as drawn."""
    return float(decorated(p).mean())


def check_pattern(p) -> None:
    """The pattern's combinations (make_params calls this): one line each, naming the parameter."""
    if p.pattern != "random" and p.occupancy != 1.0:
        raise ParamError("occupancy", f"is set by the {p.pattern} pattern (its fraction is "
                                      f"fixed by it); give occupancy only with pattern random")
    if p.pattern == "random":
        decorated_count(p.occupancy, p.chains)
    layer_letters(p.pattern_layers)  # whatever the pattern: a bad value is refused, not kept
    check_second_domain(p)
    if p.score_layers and is_mixed(p):
        rows = decorated(p).any(axis=1)[p.score_layers:p.layers - p.score_layers]
        if not rows.any():
            raise ParamError("score_layers", f"leaves no decorated subunit to judge: the "
                                             f"{p.pattern} pattern decorates none of layers "
                                             f"{p.score_layers}-{p.layers - p.score_layers - 1}; "
                                             f"score fewer end layers, or change the pattern "
                                             f"or seed")
    if p.bare_tail and p.shape.real and is_mixed(p):
        raise ParamError("bare_tail", f"is judged against sphere domains only (not yet "
                                      f"{p.shape.name}): use domain_shape sphere, or bare_tail 0")
    repeat = repeat_layers(p)
    if p.periodic and repeat and p.periodic % repeat:
        raise ParamError("pattern", f"a {p.pattern} pattern repeating every {repeat} layers does "
                                    f"not fit a cell of {p.periodic} layers: give a cell that is "
                                    f"a multiple of {repeat} (or 'auto', which rounds up to one)")


def check_second_domain(p) -> None:
    """The second domain's combinations (docs/model/occupancy.md#hetero): B needs its
    diameter, the B fields need a B in a layers pattern, and B is built as a sphere beside one
    sphere domain A, on a linker as long as A's. One line each, naming the parameter."""
    has_b = SECOND_DOMAIN in letters(p.pattern_layers)
    if not is_hetero(p):
        for name in ("domain_b_diameter", "linker_b"):
            if getattr(p, name) is not None:
                where = ("pattern_layers has no B" if p.pattern == "layers" else
                         f"pattern is {p.pattern}, not layers")
                raise ParamError(name, f"sets the second domain, but {where}: give a layers "
                                       f"pattern with B (e.g. --pattern layers --pattern-layers "
                                       f"AB), or leave {name} unset")
        if has_b:
            raise ParamError("pattern_layers", f"B (the second domain) is read only with pattern "
                                               f"layers (pattern is {p.pattern}): use A and . "
                                               f"here, or --pattern layers")
        return
    if p.domain_b_diameter is None:
        raise ParamError("domain_b_diameter", f"is needed: pattern_layers {p.pattern_layers!r} "
                                              f"puts the second domain B on its B layers; give "
                                              f"its diameter in Å (a sphere)")
    if p.shape.real:
        raise ParamError("domain_shape", f"{p.shape.name} with a second domain (B) is not "
                                         f"supported yet: B and A are spheres (domain_shape "
                                         f"sphere)")
    if p.domain_diameters:
        raise ParamError("domain_diameters", "several domains per chain with a second domain "
                                             "(B) are not supported yet: one domain per chain")
    if p.linker_b is not None and p.linker_b != p.linker:
        raise ParamError("linker_b", f"a B linker of another length than linker ({p.linker}) "
                                     f"is not built yet (chains of two lengths): give "
                                     f"{p.linker} or leave it unset (got {p.linker_b})")
    if p.bare_tail:
        raise ParamError("bare_tail", "beside a second domain (B) is not supported yet: "
                                      "bare_tail 0")


def occupancy_block(p) -> dict:
    """The result's "occupancy" (a mixed fibril only): what the answer speaks of, the pattern as
    drawn and where it came from (docs/model/occupancy.md#what-fits-at-f-means)."""
    mask = decorated(p)
    layer, pf = np.nonzero(mask)
    n = int(mask.size)
    block = {
        "pattern": p.pattern,
        "fraction": round(float(mask.mean()), 6),
        "decorated": int(mask.sum()),
        "subunits": n,
        "on": (f"a periodic cell of {p.layers} layers, its pattern repeated every {p.layers} "
               f"layers of the infinite fibril" if p.periodic else
               f"a fibril of {p.layers} layers with two ends"),
        "decorated_subunits": [[int(k), int(j)] for k, j in zip(layer, pf)],
        "bare_tail": p.bare_tail,
    }
    if p.pattern == "random":
        block.update(occupancy=p.occupancy, drawn_with="seed", seed=p.seed,
                     draw=f"the first round(f·N) of a permutation of the N subunits "
                          f"(numpy default_rng([seed, {PATTERN_SALT:#x}, N])): nested in f")
    elif p.pattern == "periodic":
        block.update(pattern_period=p.pattern_period, pattern_across=p.pattern_across)
    else:
        block.update(pattern_layers=p.pattern_layers)
    if is_hetero(p):  # which decorated subunits carry B, and its size and linker
        b = second_domain(p)[layer, pf]
        block.update(second_domain={
            "letter": SECOND_DOMAIN, "diameter": p.domain_b_diameter,
            "linker": p.linker if p.linker_b is None else p.linker_b,
            "subunits": [[int(k), int(j)] for k, j in zip(layer[b], pf[b])]})
    return block


def pattern_words(p) -> str:
    """The pattern in a few words, for the printed result and the report."""
    if p.pattern == "random":
        count = decorated_count(p.occupancy, p.chains)
        return f"a random draw of {count} of {p.chains}, seed {p.seed}"
    if p.pattern == "periodic":
        how = ("along each protofilament" if p.pattern_across == "protofilament"
               else "over the fibril")
        return f"every {p.pattern_period}th subunit {how}"
    return f"the layers pattern {p.pattern_layers!r}, repeated"


def speaks_of(p) -> str:
    """What a run's answer at this fraction is about
    (docs/model/occupancy.md#what-fits-at-f-means)."""
    where = (f"the infinite fibril that repeats a cell of {p.layers} layers, pattern and all"
             if p.periodic else f"a fibril of {p.layers} layers with two ends")
    drawn = " drawn with the run's seed" if p.pattern == "random" else ""
    return f"this pattern{drawn} on {where}"


def report_block(p, restarts: int) -> dict:
    """report.json's "occupancy": the fraction, the pattern, and what P(fit) counts."""
    return {"fraction": round(fraction(p), 6), "pattern": p.pattern,
            "pattern_words": pattern_words(p), "speaks_of": speaks_of(p),
            "p_fit_counts": ("restarts that each draw their own pattern and start from their seed"
                             if p.pattern == "random" else
                             "restarts of one fixed pattern, each its own start"),
            "restarts": int(restarts)}


def exit_bound(p, hetero: bool = False) -> dict:
    """The linker bound a mixed fibril keeps: only the buried exit's (no linker up to its
    residues leaves the core). The excluded-volume inequalities of model/bound.py count every
    subunit decorated, so below their bound a mixed fibril may still fit: they are not applied
    (docs/model/occupancy.md#bound). `hetero`: a mixed fibril of two domain sizes (A and B),
    whose excluded-volume bound (the fraction's, with two sizes) is not built
    (docs/model/bound.md#hetero). With interface termini, the shortest of the protofilaments'
    own exits (a mixed fibril may decorate that protofilament alone)."""
    if hetero:
        return {"impossible_below": int(p.pf_exit_residues().min()) + 1,
                "method": "the buried exit alone: no excluded-volume bound computed for a "
                          "mixed fibril of two domain sizes (A and B; "
                          "docs/model/bound.md#hetero)",
                "over": "a mixed hetero-amyloid: the exit only", "fails_below": None,
                "exit_residues": int(p.exit_residues)}
    return {"impossible_below": int(p.pf_exit_residues().min()) + 1,
            "method": "the buried exit alone (the excluded-volume bound counts every subunit "
                      "decorated: not applied to a mixed fibril, docs/model/occupancy.md#bound)",
            "over": "a mixed fibril: the exit only", "fails_below": None,
            "exit_residues": int(p.exit_residues)}
