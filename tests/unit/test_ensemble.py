"""The ensemble sampler against cases with known answers (docs/model/ensemble.md#tests): a free
freely jointed chain's end-to-end distribution, one sphere tethered beside a wall, two tethered
spheres' contact statistics, the autocorrelation time of a process whose τ is known, and a
model's two independent halves agreeing, with nothing overlapping anywhere (cell and images)."""
import dataclasses
import math

import numpy as np
import pytest
from scipy import special, stats

from fibrilfit.ensemble import density, observables, sampler, system
from fibrilfit.model import helix, params as P, start_layout
from fibrilfit.model.param_spec import ParamError

ALPHA = 0.01  # a KS test's p-value below this fails (seeds fixed: the same p every run)


def treloar_cdf(r, n: int) -> np.ndarray:
    """The exact CDF of |R| for n >= 2 unit bonds freely jointed (Treloar 1946): the density
    r / (2^(n-1) (n-2)!) Σ_k (-1)^k C(n, k) (n - 2k - r)_+^(n-2), integrated numerically."""
    grid = np.linspace(0.0, n, 40001)
    f = np.zeros_like(grid)
    for k in range(n + 1):
        t = n - 2 * k - grid
        f += np.where(t > 0, (-1) ** k * special.comb(n, k) * np.maximum(t, 0) ** (n - 2), 0.0)
    f *= grid / (2 ** (n - 1) * math.factorial(n - 2))
    cdf = np.concatenate([[0.0], np.cumsum((f[1:] + f[:-1]) / 2 * np.diff(grid))])
    return np.interp(r, grid, cdf)


def straight(n_bonds: int, bond: float = 1.0) -> np.ndarray:
    start = np.zeros((1, n_bonds + 1, 3))
    start[0, :, 0] = np.arange(n_bonds + 1) * bond
    return start


def test_treloar_reference_is_the_free_chain():
    """The reference itself, against i.i.d. uniform bond directions."""
    rng = np.random.default_rng(3)
    b = rng.standard_normal((4000, 4, 3))
    r = np.linalg.norm((b / np.linalg.norm(b, axis=-1, keepdims=True)).sum(1), axis=-1)
    assert stats.kstest(r, lambda x: treloar_cdf(x, 4)).pvalue > ALPHA
    assert treloar_cdf(np.array([4.0]), 4)[0] == pytest.approx(1.0, abs=1e-6)


def test_free_chain_end_to_end():
    """N = 4 bonds of 1.5 Å, no excluded volume: <R²> = N b² and |R| distributed as Treloar's,
    over 3000 independent replicas' last layouts (each replica from the same straight start)."""
    n, bond = 4, 1.5
    chain = system.HardCore(np.zeros(n + 1), np.full(n, bond), domains=(n,))
    ens = sampler.sample(chain, straight(n, bond), seed=11, replicas=3000, sweeps=30, thin=30,
                         burn_in=20)
    r = np.linalg.norm(ens.domains[-1, :, 0, 0], axis=-1)
    assert np.mean(r ** 2) == pytest.approx(n * bond ** 2, rel=0.05)
    assert stats.kstest(r / bond, lambda x: treloar_cdf(x, n)).pvalue > ALPHA
    # every bond kept its length
    assert np.allclose(np.linalg.norm(np.diff(ens.final, axis=2), axis=-1), bond)


def test_sphere_beside_a_wall():
    """A sphere (r = 2 Å) on a 5 Å tether from an anchor 3 Å above a wall: its centre's height
    is uniform on [r, 3 + 5] (Archimedes: a sphere's zones of equal height have equal area)."""
    chain = system.HardCore(np.array([0.0, 2.0]), np.array([5.0]), system.Wall(), domains=(1,))
    start = np.array([[[0.0, 0.0, 3.0], [0.0, 0.0, 8.0]]])
    ens = sampler.sample(chain, start, seed=5, replicas=2000, sweeps=40, thin=10, burn_in=20)
    z = ens.domains[:, :, 0, 0, 2]
    assert z.min() >= 2.0 - 1e-9
    assert stats.kstest(z[-1], stats.uniform(2.0, 6.0).cdf).pvalue > ALPHA


def _tethered_pair():
    """Two anchors 6 Å apart, each with a sphere (r = 2 Å) on a 4 Å tether."""
    chain = system.HardCore(np.array([0.0, 2.0]), np.array([4.0]), domains=(1,))
    start = np.array([[[-3.0, 0, 0], [-7.0, 0, 0]], [[3.0, 0, 0], [7.0, 0, 0]]])
    return chain, start


def test_two_tethered_spheres_contact_statistics():
    """Their centres' distance against a rejection-sampled reference (independent uniform
    tethers, kept when nothing overlaps: sphere-sphere, and each sphere off the other anchor)."""
    chain, start = _tethered_pair()
    ens = sampler.sample(chain, start, seed=7, replicas=2000, sweeps=40, thin=20, burn_in=20)
    c = ens.domains[-1, :, :, 0]  # (R, 2, 3)
    d = np.linalg.norm(c[:, 0] - c[:, 1], axis=-1)
    rng = np.random.default_rng(1)
    u = rng.standard_normal((400_000, 2, 3))
    u *= 4.0 / np.linalg.norm(u, axis=-1, keepdims=True)
    a = start[:, 0][None]
    ref = a + u
    ok = ((np.linalg.norm(ref[:, 0] - ref[:, 1], axis=-1) >= 4.0)
          & (np.linalg.norm(ref[:, 0] - a[:, 1], axis=-1) >= 2.0)
          & (np.linalg.norm(ref[:, 1] - a[:, 0], axis=-1) >= 2.0))
    dref = np.linalg.norm(ref[ok, 0] - ref[ok, 1], axis=-1)
    assert d.min() >= 4.0 - 1e-9
    assert stats.ks_2samp(d, dref).pvalue > ALPHA
    near, near_ref = np.mean(d < 5.0), np.mean(dref < 5.0)  # in contact, within 1 Å
    assert near == pytest.approx(near_ref, abs=4 * math.sqrt(near_ref * (1 - near_ref) / d.size))


def test_integrated_time_of_a_known_process():
    """AR(1) x_t = φ x_(t-1) + noise has τ = (1 + φ)/(1 - φ); emcee's estimator agrees."""
    import emcee
    rng = np.random.default_rng(2)
    phi, steps, walkers = 0.8, 20_000, 8
    x = np.zeros((steps, walkers))
    noise = rng.standard_normal((steps, walkers))
    for t in range(1, steps):
        x[t] = phi * x[t - 1] + noise[t]
    tau = observables.integrated_time(x)
    assert tau == pytest.approx((1 + phi) / (1 - phi), rel=0.1)
    assert tau == pytest.approx(float(emcee.autocorr.integrated_time(x[:, :, None], quiet=True)[0]),
                                rel=0.05)
    assert observables.integrated_time(rng.standard_normal((5000, 4))) == pytest.approx(1, abs=0.15)


def _overlaps(chain: system.HardCore, pos: np.ndarray) -> float:
    """The deepest overlap (Å) of any pair that must not overlap, by brute force over the cell
    and its images (every member against every other; bonded neighbours and anchor-anchor pairs
    left out), and the deepest entry of a member other than an anchor into the obstacle."""
    C, n = pos.shape[:2]
    flat = pos.reshape(-1, 3)
    radii = np.tile(chain.radii, C)
    ci, mi = np.arange(C * n) // n, np.arange(C * n) % n
    anchors = (mi[:, None] == 0) & (mi[None] == 0)
    bonded = (ci[:, None] == ci[None]) & (np.abs(mi[:, None] - mi[None]) <= 1)
    worst = 0.0
    for b, other in enumerate([flat] + [img(flat) for img in chain.images]):
        depth = radii[:, None] + radii[None] - np.linalg.norm(flat[:, None] - other[None], axis=-1)
        skip = anchors | bonded if b == 0 else anchors
        worst = max(worst, float(np.where(skip, -np.inf, depth).max()))
    if chain.obstacle is not None:
        worst = max(worst, float(chain.obstacle.depth(pos[:, 1:], chain.radii[1:]).max()))
    return worst


def test_core_prism_depth():
    """A bead beside the default box core (40 × 22 Å, slab 4.8 Å): its depth is its radius less
    its distance from the box face, turned with its layer; nothing above the last layer."""
    p = P.DEFAULTS
    core = system.from_params(p).obstacle
    angle, height = helix.layer_turn(p, 3)
    xy = helix.turn_xy(np.array([21.0]), np.array([0.0]), angle)[0]
    assert core.depth(np.array([[*xy, height]]), 1.75)[0] == pytest.approx(1.75 - 1.0)
    top = helix.layer_turn(p, p.layers - 1)[1] + p.slab[2] / 2 + 2.0
    assert core.depth(np.array([[0.0, 0.0, top]]), 1.75)[0] == 0.0
    assert core.depth(np.array([[0.0, 0.0, top]]), 2.5)[0] == pytest.approx(0.5)


@pytest.mark.parametrize("values", [{"layers": 6}, {"periodic": 6},
                                    {"layers": 4, "protofilaments": 2}])
def test_model_layouts_overlap_nowhere(values):
    """A small model (finite, a periodic cell with its screw images, two protofilaments) from
    its overlapping rest layout: once burn-in has repaired it, no replica overlaps anywhere
    (brute force), and every bond keeps its rest length."""
    p = P.make_params(globule_diameter=10.0, **values)
    chain = system.from_params(p)
    assert bool(chain.images) == ("periodic" in values)
    start = start_layout.rest_positions(p)
    assert _overlaps(chain, start) > 1.0  # the rest layout overlaps: burn-in must repair it
    ens = sampler.sample(chain, start, seed=4, replicas=4, sweeps=10, burn_in=5)
    assert max(_overlaps(chain, x) for x in ens.final) <= 1e-9
    bonds = np.linalg.norm(np.diff(ens.final, axis=2), axis=-1)
    assert np.allclose(bonds, chain.bonds)
    assert np.allclose(ens.final[:, :, 0], start[None, :, 0])  # anchors fixed


def test_two_independent_halves_agree():
    """Two runs of a small finite model, from different seeds: their mean outer diameters agree
    within 3 %, and each has an effective sample size of at least 50."""
    p = P.make_params(layers=6, globule_diameter=10.0)
    chain = system.from_params(p)
    start = start_layout.rest_positions(p)
    runs = [sampler.sample(chain, start, seed=s, replicas=8, sweeps=60, burn_in=20)
            for s in (1, 2)]
    widths = [observables.outer_diameters(e.domains[..., 0, :], p.globule_radius) for e in runs]
    taus = [observables.integrated_time(w) for w in widths]
    assert min(w.size / t for w, t in zip(widths, taus)) >= 50
    assert observables.halves(*widths)["relative_difference"] < 0.03
    # the report of one run: its outer diameter is the widths', and its radial density holds
    # every domain's volume (6 per layout over 6 layers' length)
    rep = observables.report(runs[0], p, np.ones(p.chains, bool))
    assert rep["outer_diameter"]["mean"] == pytest.approx(widths[0].mean(), abs=0.01)
    assert rep["outer_diameter"]["ess"] == pytest.approx(widths[0].size / taus[0], abs=0.1)
    r = np.asarray(rep["radial_density"]["r"])
    shells = math.pi * ((r + 1.0) ** 2 - (r - 1.0) ** 2) * 6 * p.rise
    volume = (np.asarray(rep["radial_density"]["volume_fraction"]) * shells).sum()
    assert volume == pytest.approx(6 * 4 / 3 * math.pi * 5.0 ** 3, rel=1e-3)


def test_what_the_sampler_does_not_model_is_refused():
    with pytest.raises(ParamError, match="occupancy"):
        system.from_params(P.make_params(occupancy=0.5))
    with pytest.raises(ParamError, match="bare_tail"):
        system.from_params(P.make_params(occupancy=0.5, bare_tail=3).replace(occupancy=1.0))


def test_radial_density_of_one_sphere():
    """One sphere of radius 5 Å centred 20 Å from the axis over 10 Å of fibril: its volume
    fraction, summed over shells with their volumes, is its volume; nothing outside 15-25 Å."""
    edges = np.arange(0.0, 40.0, 1.0)
    phi = observables.radial_density(np.array([[[20.0, 0.0, 0.0]]]), 5.0, 10.0, edges)
    shells = math.pi * (edges[1:] ** 2 - edges[:-1] ** 2) * 10.0
    assert (phi * shells).sum() == pytest.approx(4 / 3 * math.pi * 125)
    assert phi[(edges[1:] <= 15.0) | (edges[:-1] >= 25.0)].sum() == 0.0


def test_bond_angle_of_hard_beads():
    """Three beads of radius b/2 on bonds b (touching neighbours, the linker's own geometry):
    only the outer two exclude each other, |b1 + b2| >= b, so the bond angle's cosine is
    uniform on [-1/2, 1]."""
    bond = 3.5
    chain = system.HardCore(np.full(3, bond / 2), np.full(2, bond), domains=(2,))
    ens = sampler.sample(chain, straight(2, bond), seed=9, replicas=3000, sweeps=30, thin=30,
                         burn_in=20)
    x = ens.final[:, 0]
    b1, b2 = x[:, 1] - x[:, 0], x[:, 2] - x[:, 1]
    cos = (b1 * b2).sum(-1) / bond ** 2
    assert cos.min() >= -0.5 - 1e-9
    assert stats.kstest(cos, stats.uniform(-0.5, 1.5).cdf).pvalue > ALPHA


def test_density_map_keeps_the_domains_volume_and_writes_its_header(tmp_path):
    """Centres of one domain per layer (a helix, each layer's own twist): the map of a 12-layer
    window holds one sphere's volume per rise of its length (to 1 %: the voxelised sphere, the
    window's ends on the voxel grid), and the MRC file reads back with its voxel size and
    origin."""
    import mrcfile
    p = P.DEFAULTS
    angle, height = helix.layer_turn(p, np.arange(40, dtype=float))
    xy = helix.turn_xy(np.full(40, 40.0), np.zeros(40), angle)
    centres = np.column_stack([xy, height])[None]  # one layout, one domain per layer
    dmap = density.density_map(p, centres, 15.0, voxel=2.0, layers=12)
    length = dmap.data.shape[0] * 2.0
    assert length == pytest.approx(12 * p.rise, abs=2 * 2.0)
    assert dmap.data.sum() * 8.0 == pytest.approx(length / p.rise * 4 / 3 * math.pi * 15 ** 3,
                                                  rel=0.01)
    density.write_mrc(tmp_path / "m.mrc", dmap)
    with mrcfile.open(tmp_path / "m.mrc") as f:
        assert float(f.voxel_size.x) == pytest.approx(2.0)
        assert float(f.header.origin.x) == pytest.approx(dmap.origin[0])
        assert float(f.header.origin.z) == pytest.approx(dmap.origin[2])
        assert f.data.shape == dmap.data.shape


def test_width_of_a_solid_cylinder():
    """A solid cylinder of radius a projects to 2·sqrt(a² - x²): at 10 % of its peak the width
    is 2a·sqrt(0.99)."""
    voxel, a = 0.5, 30.0
    x = (np.arange(160) + 0.5) * voxel - 40.0
    inside = (x[None, :, None] ** 2 + x[None, None, :] ** 2) <= a * a
    dmap = density.DensityMap(np.repeat(inside, 4, axis=0).astype(np.float32), voxel,
                              (-40.0, -40.0, 0.0), 1)
    assert density.width(dmap) == pytest.approx(2 * a * math.sqrt(0.99), abs=voxel)


def test_a_seed_gives_the_same_ensemble():
    """The same seed twice: the same kept layouts, bit for bit; another seed: others."""
    chain, start = _tethered_pair()
    runs = [sampler.sample(chain, start, seed=s, replicas=8, sweeps=5, burn_in=5)
            for s in (3, 3, 4)]
    assert np.array_equal(runs[0].domains, runs[1].domains)
    assert not np.array_equal(runs[0].domains, runs[2].domains)


def _brute_violation(k: sampler.Sampler, q: np.ndarray, c: np.ndarray, rows: np.ndarray):
    """Sampler.violation without its pruning: every moved member against every sphere of the
    cell, its images and its own chain (the sampler's kernel before the overlap search)."""
    s, n, R = k.s, k.n, k.R
    x = k.x.copy()
    x[np.arange(R), c] = q
    total = np.zeros(R)
    j = np.arange(n)
    for r in range(R):
        flat = x[r].reshape(-1, 3)
        chain_of, member = np.arange(k.C * n) // n, np.arange(k.C * n) % n
        radii = np.tile(s.radii, k.C)
        for b, other in enumerate([flat] + [img(flat) for img in s.images]):
            a = flat[c[r] * n + rows]
            depth = s.radii[rows][:, None] + radii[None] - s.tolerance - np.linalg.norm(
                a[:, None] - other[None], axis=-1)
            skip = (rows[:, None] == 0) & (member[None] == 0)
            if b == 0:
                skip |= (chain_of[None] == c[r]) & (np.abs(rows[:, None] - member[None]) <= 1)
            total[r] += np.where(skip, 0.0, np.maximum(depth, 0.0)).sum()
    if s.obstacle is not None and (rows > 0).any():
        total += s.obstacle.depth(q[:, rows[rows > 0]], s.radii[rows[rows > 0]]).sum(axis=1)
    return total


@pytest.mark.parametrize("values", [{"layers": 6, "linker": 20}, {"periodic": 6, "linker": 12},
                                    {"layers": 4, "protofilaments": 2, "linker": 12}])
def test_the_overlap_search_is_the_brute_forces(values):
    """The kernel's pruned overlap (bounding spheres of SEGMENT members,
    docs/model/ensemble.md#overlap-search), and its sum over every pair (the path of a cell of
    up to PRUNE_ABOVE members), equal the sum over every pair, for every kind of
    move (pivot tails, crankshafts, the whole chain), on layouts that overlap everywhere: every
    chain a random walk of its bonds from its anchor, and after a few hundred repair steps;
    chains longer than a segment and not a multiple of it."""
    p = P.make_params(globule_diameter=10.0, **values)
    chain = system.from_params(p)
    rng = np.random.default_rng(5)
    start = chain.with_rest_bonds(start_layout.rest_positions(p))
    k = sampler.Sampler(chain, np.repeat(start[None], 3, axis=0), rng)
    assert k.n > sampler.SEGMENT and k.n % sampler.SEGMENT
    assert not k.prune  # a small cell sums every pair: the pruned search is forced here
    k.prune = True
    overlapping = 0
    for step in range(200):
        if step % 20 == 0:
            if step % 40 == 0:  # random walks from the anchors
                steps = sampler.random_axes(rng, k.R * k.C * (k.n - 1)).reshape(
                    k.R, k.C, k.n - 1, 3) * chain.bonds[:, None]
                k.x[:, :, 1:] = k.x[:, :, :1] + np.cumsum(steps, axis=2)
                k.refresh()
            c = rng.integers(0, k.C, k.R)
            q = k.x[k.ar, c]
            for rows in (np.arange(k.n), np.arange(1, k.n), np.array([k.n // 2]),
                         np.arange(k.n - 3, k.n)):
                ours = k.violation(q, c, rows)
                brute = _brute_violation(k, q, c, rows)
                assert ours == pytest.approx(brute, rel=1e-9, abs=1e-9)
                k.prune = False  # and the kernel's own sum over every pair
                assert k.violation(q, c, rows) == pytest.approx(brute, rel=1e-9, abs=1e-9)
                k.prune = True
                overlapping += int((ours > 0).sum())
        k.step(np.ones(k.R, bool))
    assert overlapping > 10  # the sums compared were not all zero


def test_the_core_alone_is_its_outline_across():
    """The map of the core alone (density.core_map): an untwisted 40 × 22 Å box seen along Y
    projects to a flat profile 40 Å across (within a voxel); the same core inside a domain map
    is the same voxels (density_map adds core_inside)."""
    p = P.make_params(twist=0.0, layers=4)
    core = dataclasses.replace(system.from_params(p).obstacle, layers=None)
    m = density.core_map(p, core, voxel=1.0, layers=4)
    assert density.width(m) == pytest.approx(40.0, abs=1.0)
    assert m.data.max() == 1.0 and m.data.sum() * 1.0 == pytest.approx(40 * 22 * 4 * p.rise,
                                                                        rel=0.05)
