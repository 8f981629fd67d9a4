"""Each linker's end-to-end distance over its contour (fibrilfit/analysis/stretch.py
linker_spans and linker_stretch_block; docs/model/linker-integrity.md#linker-span), on chains
laid out by hand whose answers are known in closed form: a straight chain at rest spans its
contour exactly (1.0), a folded one less. The module is read from its file, as in
test_stretch_check.py (fibrilfit/analysis/__init__.py imports mathutils)."""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from fibrilfit.model import params as P
from fibrilfit.model.chain import chain_x
from helpers import ROOT

_spec = importlib.util.spec_from_file_location("fibrilfit.analysis.stretch",
                                               ROOT / "fibrilfit" / "analysis" / "stretch.py")
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

ATOMS = [[10, 0, 0, 1.5], [-10, 0, 0, 1.5], [0, 10, 0, 1.5], [0, -10, 0, 1.5],
         [0, 0, 10, 1.5], [0, 0, -10, 1.5]]


def _a(value):
    return pytest.approx(np.asarray(value, dtype=float))


def _matrices(positions, turns=None):
    positions = np.asarray(positions, dtype=float)
    m = np.tile(np.eye(4), (*positions.shape[:2], 1, 1))
    m[..., :3, 3] = positions
    for j, a in enumerate(turns if turns is not None else []):
        m[:, j, :2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    return m


def _fraction(p, positions, turns=None, **exit):
    distance, contour = S.linker_spans(p, *S.bond_ends(p, _matrices(positions, turns)), **exit)
    return distance / contour, contour


def test_a_straight_sphere_chain_at_rest_spans_its_contour():
    p = P.make_params(linker=6, layers=4)
    x = np.asarray(chain_x(p)) - chain_x(p)[0]
    pos = np.zeros((1, len(x), 3))
    pos[0, :, 0] = x
    fraction, contour = _fraction(p, pos)
    # anchor's bead, 5 beads 3.5 Å apart, then the bond to the sphere's surface: one bead radius
    assert contour == _a([[5 * 3.5 + p.residue_radius]])
    assert fraction == _a([[1.0]])


def test_a_folded_sphere_chain_spans_less():
    p = P.make_params(linker=3, layers=4)
    r, R = p.residue_radius, p.globule_radius
    # anchor at 0, bead 1 at (3.5, 0), bead 2 back up at (3.5, 3.5): a right angle; the sphere
    # straight on from bead 2 along +y, touching it: its surface point at (3.5, 3.5 + r)
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [3.5, 3.5, 0], [3.5, 3.5 + r + R, 0]]])
    fraction, contour = _fraction(p, pos)
    assert contour == _a([[7.0 + r]])
    assert fraction == _a([[np.hypot(3.5, 3.5 + r) / (7.0 + r)]])
    assert fraction[0, 0] < 1.0


def test_a_sphere_pulled_away_spans_more_than_its_contour():
    p = P.make_params(linker=2, layers=4)
    r, R = p.residue_radius, p.globule_radius
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [3.5 + r + R + 1.0, 0, 0]]])  # 1 Å too far
    fraction, _ = _fraction(p, pos)
    assert fraction == _a([[(3.5 + r + 1.0) / (3.5 + r)]])


def test_a_real_shape_straight_is_one_and_turned_back_less():
    p = P.make_params(domain_shape="hull", domain_atoms=ATOMS, domain_joint=[[10.0, 0, 0]],
                      linker=3, layers=4)
    # the joint (10, 0, 0) of a domain turned by π about z at (20.5, 0, 0) is at (10.5, 0, 0):
    # three spacings from the anchor, as the model counts a 3-residue linker (3 × 3.5 Å)
    straight = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [20.5, 0, 0]]])
    fraction, contour = _fraction(p, straight, turns=[0, 0, 0, np.pi])
    assert contour == _a([[3 * 3.5]]) and fraction == _a([[1.0]])
    # bead 2 folded up: (3.5, 3.5); the joint one spacing on at (7, 3.5)
    folded = np.array([[[0, 0, 0], [3.5, 0, 0], [3.5, 3.5, 0], [17.0, 3.5, 0]]])
    fraction, _ = _fraction(p, folded, turns=[0, 0, 0, np.pi])
    assert fraction == _a([[np.hypot(7.0, 3.5) / 10.5]])


def test_two_real_domains_each_linker_from_the_exit_before_it():
    p = P.make_params(domain_shape="hull", domain_atoms=ATOMS, domain_joint=[[10.0, 0, 0]],
                      further_atoms=[[1, *a] for a in ATOMS], further_joints=[[10.0, 0, 0]],
                      domain_exits=[[-10.0, 0, 0]], domain_diameters=[23.0],
                      domain_linker=[2], linker=3, layers=4)
    # domain 1 at (20.5, 0) turned π: joint (10.5, 0), exit (30.5, 0); beads at 34, 37.5;
    # domain 2 turned π at (51, 0): joint (41, 0), three spacings from the exit
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [20.5, 0, 0], [34.0, 0, 0],
                     [37.5, 0, 0], [51.0, 0, 0]]])
    fraction, contour = _fraction(p, pos, turns=[0, 0, 0, np.pi, 0, 0, np.pi])
    assert contour == _a([[10.5, 10.5]]) and fraction == _a([[1.0, 1.0]])
    block = S.linker_stretch_block(fraction * contour, contour)
    assert [d["worst"] for d in block["by_domain"]] == pytest.approx([1.0, 1.0])


def test_a_buried_anchors_exit_is_counted_from_its_ca():
    p = P.make_params(linker=3, layers=4)
    r, R = p.residue_radius, p.globule_radius
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [7.0 + r + R, 0, 0]]] * 2)
    # chain 0: its CA 6 Å behind the anchor, straight on (a 6 Å path); chain 1: on the surface
    fraction, contour = _fraction(p, pos, exit_start=np.array([[-6.0, 0, 0], [np.nan] * 3]),
                                  exit_length=np.array([6.0, 0.0]))
    assert contour[:, 0] == pytest.approx([13.0 + r, 7.0 + r])
    assert fraction == _a([[1.0], [1.0]])
    # the same path bent: its CA at (-3, -3·√3) is 6 Å from the anchor along the path but the
    # straight span is shorter than the contour
    ca = np.array([[-3.0, -3.0 * np.sqrt(3), 0], [np.nan] * 3])
    fraction, _ = _fraction(p, pos, exit_start=ca, exit_length=np.array([6.0, 0.0]))
    assert fraction[0, 0] == pytest.approx(np.hypot(10.0 + r, 3 * np.sqrt(3)) / (13.0 + r))
    assert fraction[0, 0] < 1.0


def test_the_block_gives_median_worst_and_names_the_worst():
    distance = np.array([[9.0], [5.0], [8.0]])
    contour = np.array([[10.0], [10.0], [10.0]])
    block = S.linker_stretch_block(distance, contour)
    assert block["median"] == pytest.approx(0.8) and block["worst"] == pytest.approx(0.9)
    assert block["worst_linker"] == {"chain": 0, "domain": 0}
    assert block["linkers"] == 3 and "by_domain" not in block
    assert S.linker_stretch_block(np.zeros((0, 1)), np.zeros((0, 1))) is None
