"""The stretch check (fibrilfit/analysis/stretch.py, docs/model/linker-integrity.md): each bond's
stretch, a real shape's bond measured at its joint, and a bake's summary, on chains built by hand
whose answers are known. fibrilfit/analysis/__init__.py imports the clash checks (mathutils), so
the module is read from its file here: it is plain numpy over model/chain.py."""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from fibrilfit.model import params as P
from fibrilfit.model.chain import rest_lengths
from helpers import ROOT

_spec = importlib.util.spec_from_file_location("fibrilfit.analysis.stretch",
                                               ROOT / "fibrilfit" / "analysis" / "stretch.py")
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)


def test_bond_stretch_is_distance_over_rest_less_one():
    # two chains of three members; bonds 5 and 2 Å long against rests 4 and 2.5
    pos = np.array([[[0, 0, 0], [3, 4, 0], [3, 4, 2]],
                    [[0, 0, 0], [0, 0, 4], [0, 0, 6.5]]], dtype=float)
    s = S.bond_stretch(pos, [4.0, 2.5])
    assert s.shape == (2, 2)
    assert s == pytest.approx(np.array([[0.25, -0.2], [0.0, 0.0]]))


def _matrices(positions, turns=None):
    """World matrices (chains, members, 4, 4) with these translations, member rotations about z
    (rad) given by `turns` (members,), identity otherwise."""
    positions = np.asarray(positions, dtype=float)
    m = np.tile(np.eye(4), (*positions.shape[:2], 1, 1))
    m[..., :3, 3] = positions
    for j, a in enumerate(turns if turns is not None else []):
        m[:, j, :2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    return m


def test_a_sphere_chain_is_measured_between_centres():
    p = P.make_params(linker=3, layers=4)
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [25.0, 0, 0]]])
    starts, ends, rest = S.bond_ends(p, _matrices(pos))
    assert starts == pytest.approx(pos[:, :-1]) and ends == pytest.approx(pos[:, 1:])
    assert rest == pytest.approx(rest_lengths(p))
    stretch = S.ends_stretch(starts, ends, rest)
    assert stretch == pytest.approx(np.linalg.norm(np.diff(pos, axis=1), axis=-1)
                                    / np.asarray(rest_lengths(p)) - 1.0)


def test_a_real_shape_is_held_at_its_joint_one_spacing_from_the_last_bead():
    atoms = [[10, 0, 0, 1.5], [-10, 0, 0, 1.5], [0, 10, 0, 1.5], [0, -10, 0, 1.5],
             [0, 0, 10, 1.5], [0, 0, -10, 1.5]]
    p = P.make_params(domain_shape="hull", domain_atoms=atoms, domain_joint=[[10.0, 0, 0]],
                      linker=3, layers=4)
    assert [d.member for d in p.domains] == [3]
    # the domain turned 90° about z at (20, 0, 0): its joint (10, 0, 0) is at (20, 10, 0)
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [20.0, 0, 0]],
                    [[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [20.0, 0, 0]]])
    starts, ends, rest = S.bond_ends(p, _matrices(pos, turns=[0, 0, 0, np.pi / 2]))
    assert ends[:, 2] == pytest.approx(np.array([[20.0, 10.0, 0.0]] * 2))
    assert starts[:, 2] == pytest.approx(np.array([[7.0, 0.0, 0.0]] * 2))
    assert list(rest) == pytest.approx([3.5, 3.5, 3.5])  # the joint's bond: one spacing
    stretch = S.ends_stretch(starts, ends, rest)
    assert stretch[:, 2] == pytest.approx(np.hypot(13.0, 10.0) / 3.5 - 1.0)
    assert stretch[:, :2] == pytest.approx(0.0)


def test_two_real_domains_are_held_at_their_joints_and_the_first_lets_go_at_its_exit():
    atoms = [[10, 0, 0, 1.5], [-10, 0, 0, 1.5], [0, 10, 0, 1.5], [0, -10, 0, 1.5],
             [0, 0, 10, 1.5], [0, 0, -10, 1.5]]
    p = P.make_params(domain_shape="hull", domain_atoms=atoms, domain_joint=[[10.0, 0, 0]],
                      further_atoms=[[1, *a] for a in atoms], further_joints=[[10.0, 0, 0]],
                      domain_exits=[[-10.0, 0, 0]], domain_diameters=[23.0],
                      domain_linker=[2], linker=3, layers=4)
    assert [d.member for d in p.domains] == [3, 6]
    # anchor, 2 beads, domain 1 turned 90° at (20, 0, 0) (joint at (20, 10, 0), exit at
    # (20, -10, 0)), 2 beads, domain 2 unturned at (40, -20, 0) (joint at (50, -20, 0))
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0, 0, 0], [20.0, 0, 0], [20.0, -14.0, 0],
                     [20.0, -17.5, 0], [40.0, -20.0, 0]]])
    starts, ends, rest = S.bond_ends(p, _matrices(pos, turns=[0, 0, 0, np.pi / 2, 0, 0, 0]))
    assert list(rest) == pytest.approx([3.5] * 6)  # every bond one residue spacing
    assert starts[0, 3] == pytest.approx([20.0, -10.0, 0.0])  # the exit
    assert ends[0, 2] == pytest.approx([20.0, 10.0, 0.0]) and ends[0, 5] == pytest.approx(
        [50.0, -20.0, 0.0])
    stretch = S.ends_stretch(starts, ends, rest)[0]
    assert stretch == pytest.approx([0.0, 0.0, np.hypot(13.0, 10.0) / 3.5 - 1.0, 4.0 / 3.5 - 1.0,
                                     0.0, np.hypot(30.0, 2.5) / 3.5 - 1.0])


def test_the_log_reads_only_the_scored_chains():
    log = S.StretchLog([1.0], 0.05, slice(1, 2))
    pos = np.array([[[0, 0, 0], [9, 0, 0]], [[0, 0, 0], [1.02, 0, 0]], [[0, 0, 0], [5, 0, 0]]],
                   dtype=float)
    assert log.add(pos) == pytest.approx(0.02)
    pos[1, 1, 0] = 1.03
    assert log.add(pos) == pytest.approx(0.03)  # this frame's worst, not the first's
    assert log.worst == pytest.approx([0.02, 0.03])


def _log(worst, tolerance=0.05):
    log = S.StretchLog([1.0], tolerance)
    for w in worst:
        log.add(np.array([[[0, 0, 0], [1.0 + w, 0, 0]]]))
    return log.summary()


def test_the_summary_of_a_bake_that_ends_intact():
    # frame 1 built at rest, pushed apart to 300 % at frame 2, back under 5 % at frame 4, over
    # again at frame 7, intact from frame 8 on
    s = _log([0.0, 3.0, 0.5, 0.02, 0.01, 0.03, 0.06, 0.03])
    assert s == {"max_bond_stretch_bake": pytest.approx(3.0), "max_bond_stretch_bake_frame": 2,
                 "push_apart_end_frame": 4, "max_bond_stretch_after_push": pytest.approx(0.06),
                 "frames_over_tolerance": 3, "intact_from_frame": 8}


def test_the_summary_of_a_bake_that_never_comes_back_and_one_never_over():
    s = _log([0.0, 3.0, 0.5, 0.2])
    assert s["push_apart_end_frame"] is None and s["max_bond_stretch_after_push"] is None
    assert s["intact_from_frame"] is None and s["frames_over_tolerance"] == 3
    calm = _log([0.0, 0.043217, 0.01])  # never over: pushed apart by frame 2
    assert calm["intact_from_frame"] == 1 and calm["frames_over_tolerance"] == 0
    assert calm["push_apart_end_frame"] == 2
    assert calm["max_bond_stretch_after_push"] == pytest.approx(0.043217, abs=1e-9)
    assert calm["max_bond_stretch_bake"] == pytest.approx(0.043217, abs=1e-9)  # 6 decimals
    assert calm["max_bond_stretch_bake_frame"] == 2
    assert S.StretchLog([1.0], 0.05).summary() == {}
