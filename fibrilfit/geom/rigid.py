"""Rigid-body geometry on numpy arrays: superposition (gemmi's), screw axes, frames."""
from __future__ import annotations

import math

import numpy as np


def superpose(a: np.ndarray, b: np.ndarray):
    """Least-squares rigid transform taking points a onto points b: (R, t, rmsd), b ≈ R a + t."""
    import gemmi
    res = gemmi.superpose_positions([gemmi.Position(*p) for p in b],
                                    [gemmi.Position(*p) for p in a])
    return (np.array(res.transform.mat.tolist()), np.array(res.transform.vec.tolist()),
            float(res.rmsd))


def rotation_angle(R: np.ndarray) -> float:
    return math.acos(max(-1.0, min(1.0, (np.trace(R) - 1.0) / 2.0)))


def screw_axis(R: np.ndarray, t: np.ndarray):
    """The screw axis of x -> R x + t: (unit direction n, point p nearest the origin, angle about
    n in rad (right-handed), translation along n)."""
    angle = rotation_angle(R)
    skew = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if math.sin(angle) > 1e-3:
        n = skew / np.linalg.norm(skew)
    else:  # near 0 or 180°: the eigenvector of eigenvalue 1
        w, v = np.linalg.eig(R)
        n = np.real(v[:, np.argmin(np.abs(w - 1.0))])
        n /= np.linalg.norm(n)
    shift = float(t @ n)
    p, *_ = np.linalg.lstsq(np.eye(3) - R, t - shift * n, rcond=None)
    p = p - (p @ n) * n
    return n, p, angle, shift


def frame(u: np.ndarray, hint: np.ndarray | None = None) -> np.ndarray:
    """Rows e1, e2, u: a right-handed orthonormal frame with third axis u (e1 along hint)."""
    u = u / np.linalg.norm(u)
    if hint is None or np.linalg.norm(hint - (hint @ u) * u) < 1e-6:
        hint = np.eye(3)[np.argmin(np.abs(u))]
    e1 = hint - (hint @ u) * u
    e1 /= np.linalg.norm(e1)
    return np.array([e1, np.cross(u, e1), u])


def turn_angle(a_xy: np.ndarray, b_xy: np.ndarray) -> float:
    """Signed rotation (rad, counter-clockwise positive) about the origin that best takes the 2-D
    points a onto b (least squares)."""
    cross = np.sum(a_xy[:, 0] * b_xy[:, 1] - a_xy[:, 1] * b_xy[:, 0])
    dot = np.sum(a_xy * b_xy)
    return math.atan2(cross, dot)


def wrap(angle: float) -> float:
    """Angle in (-pi, pi]."""
    a = math.remainder(angle, 2 * math.pi)
    return math.pi if a == -math.pi else a


def euler_xyz(rot: np.ndarray) -> np.ndarray:
    """Blender's XYZ Euler angles (n, 3) of rotations (n, 3, 3): R = Rz·Ry·Rx."""
    beta = -np.arcsin(np.clip(rot[:, 2, 0], -1.0, 1.0))
    alpha = np.arctan2(rot[:, 2, 1], rot[:, 2, 2])
    gamma = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
    return np.column_stack([alpha, beta, gamma])


def cross_matrices(v: np.ndarray) -> np.ndarray:
    """(n, 3, 3) matrices [v]x with [v]x @ w = v × w, for the rows of v (n, 3)."""
    vx = np.zeros((len(v), 3, 3))
    vx[:, 0, 1], vx[:, 0, 2], vx[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    vx[:, 1, 0], vx[:, 2, 0], vx[:, 2, 1] = v[:, 2], -v[:, 1], v[:, 0]
    return vx


def joint_rotations(joint: np.ndarray, outward: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotations taking the body-frame direction `joint` onto -outward (each row of
    outward: from the pivot to the globule's centre), by the smallest turn."""
    a = joint / np.linalg.norm(joint)
    b = -outward / np.linalg.norm(outward, axis=1, keepdims=True)
    vx = cross_matrices(np.cross(a[None], b))
    cos = b @ a
    opposite = cos < -1 + 1e-9  # a half turn about any axis perpendicular to a
    k = np.where(opposite, 0.0, 1.0 / np.maximum(1.0 + cos, 1e-12))
    rot = np.eye(3)[None] + vx + (vx @ vx) * k[:, None, None]
    if opposite.any():
        perp = np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0])
        perp /= np.linalg.norm(perp)
        rot[opposite] = 2 * np.outer(perp, perp) - np.eye(3)
    return rot


def turn_about(axis: np.ndarray, angle) -> np.ndarray:
    """(n, 3, 3) rotations by `angle` (n,) about the unit vectors `axis` (n, 3) (Rodrigues)."""
    k = np.asarray(axis, float).reshape(-1, 3)
    a = np.broadcast_to(np.asarray(angle, float), (len(k),))
    kx = cross_matrices(k)
    return (np.eye(3)[None] + np.sin(a)[:, None, None] * kx
            + (1.0 - np.cos(a))[:, None, None] * (kx @ kx))
