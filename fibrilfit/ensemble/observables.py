"""What the ensemble says (docs/model/ensemble.md#observables): the outer diameter as a
distribution (each kept layout's, by the envelope's one definition: 2 · (r95 + R), r95 the 95th
percentile of the domain centres' distances from the axis, analysis/envelope.py), the radial
density of domain mass (the volume fraction the domains fill at each distance from the axis),
and whether the run can be trusted: the integrated autocorrelation time and effective sample
size (Sokal's automatic window), and two independent halves' agreement.
"""
from __future__ import annotations

import math

import numpy as np

SOKAL_WINDOW = 5.0  # the window M is the least with M >= c·τ(M) (Sokal 1997; emcee's c = 5)
PROTEIN_DENSITY = 0.81  # Da/Å³ (1.35 g/cm³), to read a volume fraction as a mass density


def outer_diameters(domains: np.ndarray, radius: float) -> np.ndarray:
    """Each kept layout's outer diameter (Å): domains (..., D, 3), the scored domain centres of
    one layout in the last two axes; 2 · (95th percentile of their distances from Z + R)."""
    rho = np.hypot(domains[..., 0], domains[..., 1])
    return 2.0 * (np.percentile(rho, 95, axis=-1) + radius)


def summary(values: np.ndarray, tau: float) -> dict:
    """Mean, standard error (from the effective sample size), median and the central 95 %
    interval (2.5th, 97.5th percentiles) of samples (S, R); Å, rounded to 0.01."""
    v = np.asarray(values, dtype=float)
    ess = v.size / max(tau, 1.0)
    return {"mean": round(float(v.mean()), 2), "sem": round(float(v.std() / math.sqrt(ess)), 3),
            "median": round(float(np.median(v)), 2),
            "interval_95": [round(float(x), 2) for x in np.percentile(v, [2.5, 97.5])],
            "ess": round(ess, 1)}


def autocorrelation(series: np.ndarray) -> np.ndarray:
    """The normalised autocorrelation function of series (S, R) (time first), averaged over the
    R replicas (each replica's own mean removed), by FFT."""
    x = np.asarray(series, dtype=float)
    x = x - x.mean(axis=0)
    n = len(x)
    size = 1 << (2 * n - 1).bit_length()
    f = np.fft.rfft(x, n=size, axis=0)
    acf = np.fft.irfft(f * np.conjugate(f), n=size, axis=0)[:n].mean(axis=1)
    return acf / acf[0] if acf[0] > 0 else np.zeros(n)


def integrated_time(series: np.ndarray, c: float = SOKAL_WINDOW) -> float:
    """The integrated autocorrelation time τ = 1 + 2 Σ ρ(t) (in kept samples) of series (S, R),
    summed up to Sokal's automatic window (the least M with M >= c·τ(M)); 1 for a series with
    no variance."""
    rho = autocorrelation(series)
    taus = 2.0 * np.cumsum(rho) - 1.0
    m = np.arange(len(taus)) < c * taus
    window = int(np.argmin(m)) if not m.all() else len(taus) - 1
    return float(max(taus[window], 1.0)) if rho.any() else 1.0


def halves(first: np.ndarray, second: np.ndarray) -> dict:
    """Two independent halves' means (samples (S, R) each), and their difference relative to
    the mean of both."""
    a, b = float(np.mean(first)), float(np.mean(second))
    return {"means": [round(a, 2), round(b, 2)],
            "relative_difference": round(abs(a - b) / (0.5 * (a + b)), 4)}


def _ball_points(per_axis: int = 9) -> np.ndarray:
    """Points filling the unit ball evenly: a cubic grid's points inside it (cell centres)."""
    g = (np.arange(per_axis) + 0.5) / per_axis * 2.0 - 1.0
    pts = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    return pts[(pts * pts).sum(1) <= 1.0]


def radial_density(domains: np.ndarray, radius: float, length: float, edges: np.ndarray
                   ) -> np.ndarray:
    """The volume fraction the domains (spheres of `radius`, centres (..., 3), every kept
    layout) fill in each cylindrical shell about Z (edges in Å), per layout, over a fibril of
    `length` Å: each sphere's volume spread over a grid of points filling it."""
    centres = np.asarray(domains, dtype=float).reshape(-1, 3)
    ball = _ball_points() * radius
    layouts = int(np.prod(domains.shape[:-2])) if domains.ndim > 2 else 1
    counts = np.zeros(len(edges) - 1)
    for chunk in np.array_split(centres, max(1, len(centres) // 2000)):
        pts = chunk[:, None, :2] + ball[None, :, :2]
        counts += np.histogram(np.hypot(pts[..., 0], pts[..., 1]), edges)[0]
    volume = counts * (4.0 / 3.0 * math.pi * radius ** 3 / len(ball))
    shells = math.pi * (edges[1:] ** 2 - edges[:-1] ** 2) * length
    return volume / shells / layouts


RADIAL_BIN = 2.0  # Å: the radial density's shells


def report(ens, p, scored: np.ndarray) -> dict:
    """The JSON-ready account of an ensemble of Params p's model (sphere domains): how it was
    sampled, the outer diameter's distribution over kept layouts (scored chains' domains: bool
    per chain), its autocorrelation time, effective sample size and two halves (the first and
    second half of the replicas), and the radial density of domain mass."""
    d = ens.domains[:, :, np.asarray(scored, bool)]  # (S, R, C', D, 3)
    d = d.reshape(*d.shape[:2], -1, 3)
    widths = outer_diameters(d, p.widest_diameter / 2.0)
    tau = integrated_time(widths)
    half = widths.shape[1] // 2
    edges = np.arange(0.0, float(np.hypot(d[..., 0], d[..., 1]).max()) + p.widest_diameter
                      + RADIAL_BIN, RADIAL_BIN)
    length = int(np.count_nonzero(scored)) / p.protofilaments * p.rise
    phi = radial_density(d, p.widest_diameter / 2.0, length, edges)
    return {
        "method": "hard-core Monte Carlo, pivot and crankshaft moves (docs/model/ensemble.md)",
        "seed": ens.seed, "replicas": int(ens.final.shape[0]), "sweeps": ens.sweeps,
        "thin": ens.thin, "burn_in_sweeps": ens.burn_in_sweeps,
        "acceptance": ens.acceptance, "seconds": round(ens.seconds, 2),
        "outer_diameter": {**summary(widths, tau), "tau_samples": round(tau, 2),
                           **({"halves": halves(widths[:, :half], widths[:, half:])}
                              if half else {})},
        "radial_density": {"r": (0.5 * (edges[1:] + edges[:-1])).round(2).tolist(),
                           "volume_fraction": phi.round(5).tolist(),
                           "mass_density_da_per_a3": (phi * PROTEIN_DENSITY).round(5).tolist()},
    }
