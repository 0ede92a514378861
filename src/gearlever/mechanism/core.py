"""The :class:`Mechanism` object: a model file loaded, analysed and solved."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism.constraints import constraint_jacobian, constraint_labels, constraint_residual
from gearlever.mechanism.linkage import is_linkage_file, read_linkage_model
from gearlever.mechanism.model import MechanismModel, load_model, model_from_dict, model_from_text
from gearlever.mechanism.modelfile import model_dict, model_toml
from gearlever.mechanism.solve import KinematicSystem, MechanismResult, solve
from gearlever.mechanism.structural import MechanismStructure, analyze_structure

__all__ = ["Mechanism"]


class Mechanism:
    """A planar mechanism of links, revolute pins, sliders and gears, read from a model.

    Parameters
    ----------
    model : MechanismModel
        Parsed model (see :func:`~gearlever.mechanism.model.model_from_dict`);
        usually built by :meth:`load` or :meth:`from_dict`.

    Examples
    --------
    A crank-rocker (ground 4, crank 1) with the crank as input:

    >>> m = Mechanism.from_dict({
    ...     "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"],
    ...               "coupler": ["A", "B"], "rocker": ["O4", "B"]},
    ...     "inputs": [{"link": "crank"}]})
    >>> m.structure().dof
    1
    >>> r = m.solve(np.linspace(0.0, 2 * np.pi, 5))
    >>> bool(r.closed.all()), r.point["B"].shape
    (True, (5, 2))
    """

    def __init__(self, model: MechanismModel):
        self.model = model
        self._system = None
        self._structure = None

    @classmethod
    def load(cls, path) -> Mechanism:
        """Read a model file: TOML (see :mod:`gearlever.mechanism.model`), or a linkage in the challenge's form.

        A file named ``*.links.json``, or ``*.json`` holding an object with the
        keys ``x0`` and ``edges``, is a linkage in the MIT 2.156 challenge's
        form (:func:`gearlever.mechanism.linkage.read_linkage`), opened as the
        model :func:`gearlever.mechanism.linkage.linkage_model` writes (fixed
        joints ``O<i>``, moving joints ``J<i>``, traced joint ``P``, input the
        crank).  Refusals name the file and the key.

        Examples
        --------
        >>> import json, pathlib, tempfile
        >>> p = pathlib.Path(tempfile.mkdtemp()) / "d.links.json"
        >>> _ = p.write_text(json.dumps({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
        ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]}))
        >>> m = Mechanism.load(p)
        >>> m.name, sorted(m.model.links), m.structure().dof
        ('d', ['L1', 'L2', 'crank', 'ground'], 1)
        """
        if is_linkage_file(path):
            d = read_linkage_model(path)
            try:
                return cls(model_from_dict(d))
            except GearleverError as exc:
                raise GearleverError(f"{Path(path)}: {exc}") from None
        return cls(load_model(path))

    @classmethod
    def from_dict(cls, d) -> Mechanism:
        """Build from a dict with the model file's structure."""
        return cls(model_from_dict(d))

    @classmethod
    def loads(cls, text: str) -> Mechanism:
        """Build from the TOML text of a model file (:func:`~gearlever.mechanism.model.model_from_text`).

        ``Mechanism.loads(m.dumps())`` is the same model as ``m``: same points,
        links, joints, sliders, gears, meshes, inputs and kept tables.

        Examples
        --------
        >>> m = Mechanism.loads('[points]\\nO = [0, 0]\\nA = [1, 0]\\n'
        ...     '[links]\\nground = ["O"]\\ncrank = ["O", "A"]\\n[[inputs]]\\nlink = "crank"\\n')
        >>> Mechanism.loads(m.dumps()).model == m.model
        True
        """
        return cls(model_from_text(text))

    def dumps(self) -> str:
        """The TOML text of the model (every table it holds, floats written exactly).

        The writer is :func:`gearlever.mechanism.modelfile.model_toml` with
        ``exact=True``; :meth:`loads` reads the text back to the same model.

        Examples
        --------
        >>> m = Mechanism.from_dict({"mechanism": {"units": "mm"}, "points": {"O": [0, 0], "A": [0.1, 0.2]},
        ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
        >>> print(m.dumps())
        [mechanism]
        name = "mechanism"
        units = "mm"
        <BLANKLINE>
        [points]
        O = [0.0, 0.0]
        A = [0.1, 0.2]
        <BLANKLINE>
        [links]
        ground = ["O"]
        crank = ["O", "A"]
        <BLANKLINE>
        [[inputs]]
        link = "crank"
        <BLANKLINE>
        """
        return model_toml(model_dict(self.model), exact=True)

    @property
    def name(self) -> str:
        return self.model.name

    def structure(self) -> MechanismStructure:
        """Counts, dof, redundant constraints (:func:`~gearlever.mechanism.structural.analyze_structure`)."""
        if self._structure is None:
            self._structure = analyze_structure(self.model)
        return self._structure

    @property
    def system(self) -> KinematicSystem:
        """The model compiled to reduced coordinates (built on first use)."""
        if self._system is None:
            self._system = KinematicSystem(self.model)
        return self._system

    @property
    def sketch_inputs(self) -> np.ndarray:
        """Input values of the sketch, ``(W,)``: link angles (rad) and slider displacements (0)."""
        return self.system.q0.copy()

    def solve(self, q, qdot=None, qddot=None, branch: str = "continue") -> MechanismResult:
        """Positions, velocities, accelerations over the input rows (:func:`~gearlever.mechanism.solve.solve`).

        ``branch``: ``"continue"`` (default: smooth through a branch point), ``"keep"`` or ``"stop"``.
        """
        return solve(self.system, q, qdot, qddot, branch=branch)

    def assemble(self, hold_inputs: bool = True) -> dict:
        """The model with its sketch closed to its ``[lengths]`` (:func:`~gearlever.mechanism.assemble.assemble`).

        Returns the exact model as a dict; :meth:`from_dict` loads it.
        """
        from gearlever.mechanism.assemble import assemble

        return assemble(self.model, hold_inputs=hold_inputs)

    def instant_centres(self, q, qdot=None):
        """Instant centres of every pair of links (:func:`~gearlever.mechanism.centres.instant_centres`)."""
        from gearlever.mechanism.centres import instant_centres

        return instant_centres(self.solve(q, qdot))

    def inverse_dynamics(
        self,
        q,
        qdot=None,
        qddot=None,
        loads=None,
        masses=None,
        gravity=None,
        pressure_angle=None,
        efficiency=None,
        friction=None,
        branch: str = "continue",
    ):
        """Driver torques and pair forces (:func:`~gearlever.mechanism.dynamics.inverse_dynamics`)."""
        from gearlever.mechanism.dynamics import inverse_dynamics

        return inverse_dynamics(
            self,
            q,
            qdot,
            qddot,
            loads=loads,
            masses=masses,
            gravity=gravity,
            pressure_angle=pressure_angle,
            efficiency=efficiency,
            friction=friction,
            branch=branch,
        )

    def reduced_inertia(self, q, masses=None):
        """Reduced inertia (:func:`~gearlever.mechanism.dynamics.reduced_inertia`)."""
        from gearlever.mechanism.dynamics import reduced_inertia

        return reduced_inertia(self, q, masses=masses)

    def dynamic_terms(self, q, qdot=None, masses=None, loads=None, gravity=None):
        """Mass matrix and velocity terms, tau = M q'' + b (:func:`~gearlever.mechanism.dynamics.dynamic_terms`)."""
        from gearlever.mechanism.dynamics import dynamic_terms

        return dynamic_terms(self, q, qdot, masses=masses, loads=loads, gravity=gravity)

    def simulate(
        self,
        t,
        q0,
        qdot0,
        torque=0.0,
        masses=None,
        loads=None,
        gravity=None,
        rtol: float = 1e-10,
        atol: float = 1e-12,
        max_evals: int | None = None,
        efficiency=None,
        friction=None,
    ):
        """Motion under driving torques, one per input (:func:`~gearlever.mechanism.dynamics.simulate`).

        ``max_evals`` None: the library's cap
        (:data:`gearlever.mechanism.dynamics.MAX_EVALS`).
        """
        from gearlever.mechanism.dynamics import MAX_EVALS, simulate

        return simulate(
            self,
            t,
            q0,
            qdot0,
            torque=torque,
            masses=masses,
            loads=loads,
            gravity=gravity,
            rtol=rtol,
            atol=atol,
            max_evals=MAX_EVALS if max_evals is None else max_evals,
            efficiency=efficiency,
            friction=friction,
        )

    def constraint_labels(self) -> tuple:
        """Row names of :meth:`constraint_jacobian`."""
        return constraint_labels(self.model)

    def constraint_residual(self, pose) -> np.ndarray:
        """Constraint residual at poses (:func:`~gearlever.mechanism.constraints.constraint_residual`)."""
        return constraint_residual(self.model, pose)

    def constraint_jacobian(self, pose) -> np.ndarray:
        """Absolute-coordinate constraint Jacobian (:func:`~gearlever.mechanism.constraints.constraint_jacobian`)."""
        return constraint_jacobian(self.model, pose)

    def __repr__(self) -> str:
        return f"Mechanism({self.model.name!r}, links={list(self.model.links)})"
