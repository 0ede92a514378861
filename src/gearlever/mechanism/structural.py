"""Structural analysis of a mechanism model: counts, mobility and redundant constraints from the Jacobian's rank.

The mobility formula ``W = 3n - 2 P5 - P4 + q`` (:func:`gearlever.mechanism.mobility.mobility`)
needs the number ``q`` of redundant constraints; here ``q`` is found, not
supplied: it is the number of constraint rows that the others already imply,
read from the rank of the absolute-coordinate constraint Jacobian at the sketch.

Pure numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.mechanism.constraints import constraint_jacobian, constraint_labels, sketch_pose
from gearlever.mechanism.model import MechanismModel

__all__ = ["MechanismStructure", "analyze_structure", "scaled_jacobian", "numeric_rank"]

#: Relative singular-value threshold of the rank.
RANK_TOL = 1e-9


@dataclass(frozen=True)
class MechanismStructure(Result):
    """Counts and mobility of a mechanism model.

    Attributes
    ----------
    n : int
        Moving links.
    P5 : int
        Lower pairs (revolute: a point carried by k links counts k - 1; each slider 1).
    P4 : int
        Higher pairs (gear meshes).
    W_formula : int
        ``3 n - 2 P5 - P4`` (the formula without redundant constraints).
    rank : int
        Rank of the constraint Jacobian at the sketch.
    dof : int
        ``3 n - rank``: the degrees of freedom.
    redundant : int
        ``2 P5 + P4 - rank``: the redundant constraints ``q``; ``dof = W_formula + redundant``.
    redundant_rows : tuple of str
        Constraint rows implied by the rows before them (in
        :func:`~gearlever.mechanism.constraints.constraint_labels` order):
        which constraints are redundant.
    inputs : int
        Number of ``[[inputs]]`` in the model (should equal ``dof``).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...                          "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...                          "inputs": [{"link": "crank"}]})
    >>> s = m.structure()
    >>> (s.n, s.P5, s.P4, s.W_formula, s.dof, s.redundant)
    (1, 1, 0, 1, 1, 0)
    """

    n: int
    P5: int
    P4: int
    W_formula: int
    rank: int
    dof: int
    redundant: int
    redundant_rows: tuple
    inputs: int

    def summary(self) -> dict:
        """The numbers as a dict, keys ``n, P5, P4, W_formula, dof, redundant``."""
        return {k: getattr(self, k) for k in ("n", "P5", "P4", "W_formula", "dof", "redundant")}


def scaled_jacobian(model: MechanismModel, pose=None) -> np.ndarray:
    """The constraint Jacobian with length rows and x, y columns scaled to be dimensionless.

    Rows of pins and slider normals are divided by the model's length scale
    ``L``, columns ``x, y`` multiplied by ``L``: rank decisions then do not
    depend on the length unit.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [100, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> np.abs(scaled_jacobian(m)).max()
    np.float64(1.0)
    """
    pose = sketch_pose(model) if pose is None else np.asarray(pose, dtype=float)
    J = constraint_jacobian(model, pose).copy()
    L = model.length_scale
    nj, ns = len(model.joints), len(model.sliders)
    length_rows = list(range(2 * nj)) + [2 * nj + 2 * i for i in range(ns)]
    J[..., length_rows, :] /= L
    J[..., :, 0::3] *= L
    J[..., :, 1::3] *= L
    return J


def numeric_rank(A: np.ndarray, tol: float = RANK_TOL) -> int:
    """Number of singular values above ``tol`` times the largest (0 for an empty matrix)."""
    if A.size == 0:
        return 0
    sv = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(sv > tol * max(sv[0], 1e-300)))


def independent_rows(A: np.ndarray, tol: float = RANK_TOL, block: int = 64, sv=None) -> list:
    """Indices of rows of ``A`` that raise the rank, taken greedily in order.

    Gram-Schmidt (each projection done twice), by blocks of ``block`` rows:
    a block is first cleared of the kept rows' directions in two matrix
    products, then its rows are taken one by one.  A row is kept when its
    part orthogonal to the kept rows is longer than ``tol`` times the largest
    singular value of ``A``: cubic in the size like one SVD (a 334-link
    mechanism with 331 redundant constraints, 1332 x 1002, in seconds where
    one SVD per row took hours).  When the count differs from
    :func:`numeric_rank` (a row at the threshold), the rows are decided one
    SVD each, as the definition reads.  ``sv``: the singular values of ``A``
    when the caller has them (one SVD saved).
    """
    A = np.asarray(A, dtype=float)
    if A.size == 0:
        return []
    sv = np.linalg.svd(A, compute_uv=False) if sv is None else np.asarray(sv)
    thresh = tol * max(sv[0], 1e-300)
    rank = int(np.sum(sv > thresh))
    basis = np.zeros((min(A.shape), A.shape[1]))
    keep: list = []
    for start in range(0, A.shape[0], block):
        rows = A[start : start + block].copy()
        done = basis[: len(keep)]
        for _ in range(2):
            rows -= (rows @ done.T) @ done
        first = len(keep)
        for j in range(rows.shape[0]):
            v = rows[j]
            new = basis[first : len(keep)]
            for _ in range(2):
                v -= new.T @ (new @ v)
            norm = float(np.linalg.norm(v))
            if norm > thresh and len(keep) < basis.shape[0]:
                basis[len(keep)] = v / norm
                keep.append(start + j)
    if len(keep) == rank:
        return keep
    keep, r = [], 0
    for i in range(A.shape[0]):
        if numeric_rank(A[keep + [i]], tol) > r:
            keep.append(i)
            r += 1
    return keep


def analyze_structure(model: MechanismModel) -> MechanismStructure:
    """Counts, mobility and redundant constraints of a mechanism model.

    Parameters
    ----------
    model : MechanismModel

    Returns
    -------
    MechanismStructure

    Notes
    -----
    ZRDPM paper, eq. 1 (Alimukhamedov, Abdukarimov, Sharifhodjaeva, Rustamov,
    "Structural and Kinematic Analysis of Gear and Lever Differential
    Mechanisms...", Int. J. of Psychosocial Rehabilitation 24(1), 2020):
    ``W = 3n - 2 P5 - P4 + q``.  The constraint Jacobian ``J`` (``2 P5 + P4``
    rows, ``3 n`` columns) at the sketch gives ``W = 3 n - rank J`` and
    ``q = 2 P5 + P4 - rank J``, the instantaneous mobility (G. Gogu,
    "Chebychev-Grubler-Kutzbach's criterion for mobility calculation of
    multi-loop mechanisms revisited via theory of linear transformations",
    European Journal of Mechanics A/Solids 24, 2005, pp. 427-441).

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"],
    ...               "rocker": ["O4", "B"]}, "inputs": [{"link": "crank"}]})
    >>> s = analyze_structure(m)
    >>> (s.n, s.P5, s.P4, s.W_formula, s.dof, s.redundant)
    (3, 4, 0, 1, 1, 0)
    """
    n = len(model.moving)
    p5 = len(model.joints) + len(model.sliders)
    p4 = len(model.meshes)
    J = scaled_jacobian(model)
    sv = np.linalg.svd(J, compute_uv=False) if J.size else np.zeros(0)
    rank = int(np.sum(sv > RANK_TOL * max(sv[0], 1e-300))) if sv.size else 0  # as numeric_rank
    keep = set(independent_rows(J, sv=sv)) if rank < J.shape[0] else set(range(J.shape[0]))
    labels = constraint_labels(model)
    red_rows = tuple(labels[i] for i in range(J.shape[0]) if i not in keep)
    w_formula = 3 * n - 2 * p5 - p4
    dof = 3 * n - rank
    redundant = 2 * p5 + p4 - rank
    return MechanismStructure(n, p5, p4, w_formula, rank, dof, redundant, red_rows, len(model.inputs))
