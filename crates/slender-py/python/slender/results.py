"""Results of a solve as NumPy arrays (float64, SI units).

Built from the core's JSON of a step, which is exactly the ``result.json`` that ``slender
solve`` writes (same serializer, same bits), with the rods' internal loads added.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np


def _array(values: Any, shape_tail: tuple[int, ...]) -> np.ndarray:
    a = np.asarray(values, dtype=np.float64)
    if a.size == 0:
        return a.reshape((0,) + shape_tail)
    return a.reshape((-1,) + shape_tail)


def _float(x: Optional[float]) -> float:
    """JSON null (a NaN or infinity in the core) as NaN."""
    return math.nan if x is None else float(x)


@dataclass(frozen=True)
class SolveReport:
    """What a solve reports. ``converged`` False means the state is *not* an equilibrium
    (``reason`` says why). ``inertia`` = (negative, zero, positive) eigenvalue counts of the
    Hessian at the returned state (None if not computed); ``lambda_min`` its smallest
    eigenvalue in the mass metric (1/s²), ``lambda_min_normalized`` divided by EI/(ρA L⁴)."""

    converged: bool
    reason: str
    iterations: int
    load_steps: int
    residual: float
    relative_residual: float
    energy: float
    inertia: Optional[tuple[int, int, int]]
    lambda_min: Optional[float]
    lambda_min_normalized: Optional[float]
    raw: dict = field(repr=False, compare=False)

    @classmethod
    def from_json(cls, d: dict) -> "SolveReport":
        status = d["status"]
        converged = status.get("status") == "converged"
        inertia = d.get("inertia")
        return cls(
            converged=converged,
            reason="" if converged else status.get("reason", ""),
            iterations=int(d["iterations"]),
            load_steps=int(d["load_steps"]),
            residual=_float(d["residual"]),
            relative_residual=_float(d["relative_residual"]),
            energy=_float(d["energy"]),
            inertia=None
            if inertia is None
            else (int(inertia["negative"]), int(inertia["zero"]), int(inertia["positive"])),
            lambda_min=d.get("lambda_min"),
            lambda_min_normalized=d.get("lambda_min_normalized"),
            raw=d,
        )


@dataclass(frozen=True)
class RodResult:
    """The equilibrium of one rod with n elements (n + 1 vertices).

    Arrays (float64 unless said):

    - ``positions`` (n+1, 3), m — vertex positions;
    - ``frames`` (n, 3, 3) — per edge the material frame rows (m₁, m₂, t);
    - ``curvature`` (n+1, 2), 1/m — material curvatures (κ₁, κ₂) per vertex (0 at free ends);
    - ``twist`` (n+1,), rad/m — twist rate per vertex;
    - ``edge_strain`` (n,) — axial strain |e|/l̄ − 1 per edge;
    - ``axial_force`` (n,), N — EA·ε per edge (tension positive);
    - ``bending_moment`` (n+1, 2), N m — (EI₁ Δκ₁, EI₂ Δκ₂) per vertex, material components;
    - ``twisting_moment`` (n+1,), N m — GJ Δτ per vertex;
    - ``support_forces`` / ``support_moments`` (k, 3), N / N m — what each of the k supports
      applies to the rod (moment about its vertex); ``support_positions`` (k, 3), m;
      ``support_vertices`` (k,) int64; ``support_kinds`` list of str;
    - ``applied_force`` (3,), N and ``applied_moment`` (3,), N m — resultant applied load.

    ``reports`` holds the solver report of every part of the rod (between interior clamps).
    """

    name: str
    positions: np.ndarray
    frames: np.ndarray
    curvature: np.ndarray
    twist: np.ndarray
    edge_strain: np.ndarray
    axial_force: np.ndarray
    bending_moment: np.ndarray
    twisting_moment: np.ndarray
    support_forces: np.ndarray
    support_moments: np.ndarray
    support_positions: np.ndarray
    support_vertices: np.ndarray
    support_kinds: list
    applied_force: np.ndarray
    applied_moment: np.ndarray
    min_bend_radius: float
    tight_vertices: np.ndarray
    relative_force_imbalance: float
    relative_moment_imbalance: float
    reports: list
    converged: bool
    stable: bool

    @classmethod
    def from_json(cls, d: dict) -> "RodResult":
        sup = d["supports"]
        mbr = d["min_bend_radius"]
        return cls(
            name=d["name"],
            positions=_array(d["positions"], (3,)),
            frames=_array(d["frames"], (3, 3)),
            curvature=_array(d["curvature"], (2,)),
            twist=_array(d["twist"], ()),
            edge_strain=_array(d["edge_strain"], ()),
            axial_force=_array(d["axial_force"], ()),
            bending_moment=_array(d["bending_moment"], (2,)),
            twisting_moment=_array(d["twisting_moment"], ()),
            support_forces=_array([s["force"] for s in sup], (3,)),
            support_moments=_array([s["moment"] for s in sup], (3,)),
            support_positions=_array([s["position"] for s in sup], (3,)),
            support_vertices=np.asarray([s["vertex"] for s in sup], dtype=np.int64),
            support_kinds=[s["kind"] for s in sup],
            applied_force=_array(d["applied_force"], ()),
            applied_moment=_array(d["applied_moment"], ()),
            # null: a straight rod (infinite radius).
            min_bend_radius=math.inf if mbr is None else float(mbr),
            tight_vertices=np.asarray(d["tight_vertices"], dtype=np.int64),
            relative_force_imbalance=_float(d["relative_force_imbalance"]),
            relative_moment_imbalance=_float(d["relative_moment_imbalance"]),
            reports=[SolveReport.from_json(r) for r in d["reports"]],
            converged=bool(d["converged"]),
            stable=bool(d["stable"]),
        )

    @property
    def material_directors(self) -> np.ndarray:
        """m₁ of every edge, (n, 3)."""
        return self.frames[:, 0, :]


@dataclass(frozen=True)
class StructureResult:
    """One structure (rod parts solved together): its rods, solver report, stability and
    force/moment balance."""

    rods: list
    report: SolveReport
    stable: bool
    unstable_modes: int
    followed_unstable_mode: bool
    relative_force_imbalance: float
    relative_moment_imbalance: float

    @classmethod
    def from_json(cls, d: dict) -> "StructureResult":
        st = d["stability"]
        return cls(
            rods=list(d["rods"]),
            report=SolveReport.from_json(d["report"]),
            stable=bool(st["stable"]),
            unstable_modes=int(st["unstable_modes"]),
            followed_unstable_mode=bool(st["followed_unstable_mode"]),
            relative_force_imbalance=_float(d["relative_force_imbalance"]),
            relative_moment_imbalance=_float(d["relative_moment_imbalance"]),
        )


@dataclass(frozen=True)
class ShellResult:
    """A shell strip: ``positions`` (v, 3) m, ``triangles`` (t, 3) int64 vertex indices,
    ``clamp_force`` (3,) N, and its solver report."""

    name: str
    positions: np.ndarray
    triangles: np.ndarray
    clamp_force: np.ndarray
    applied_force: np.ndarray
    report: SolveReport
    converged: bool
    raw: dict = field(repr=False, compare=False)

    @classmethod
    def from_json(cls, d: dict) -> "ShellResult":
        return cls(
            name=d["name"],
            positions=_array(d["positions"], (3,)),
            triangles=np.asarray(d["faces"], dtype=np.int64).reshape(-1, 3),
            clamp_force=_array(d["clamp_force"], ()),
            applied_force=_array(d["applied_force"], ()),
            report=SolveReport.from_json(d["report"]),
            converged=bool(d["converged"]),
            raw=d,
        )


class _Named(list):
    """A list of results that can also be indexed by name."""

    def __getitem__(self, key):  # type: ignore[override]
        if isinstance(key, str):
            for item in self:
                if item.name == key:
                    return item
            raise KeyError(f"no result named {key!r}; names: {[i.name for i in self]}")
        return super().__getitem__(key)


@dataclass(frozen=True)
class Results:
    """One equilibrium of a scene: step 0 is the loaded scene, then one per motion step.

    ``converged`` is False if any rod or shell did not converge: the shapes are then the
    last equilibrium (or the start), not an equilibrium of this step's loads. ``raw`` is the
    step as ``slender solve`` writes it to ``result.json`` (plus the internal loads).
    """

    step: int
    stage: Optional[int]
    converged: bool
    stable: bool
    pieces: int
    rods: list
    structures: list
    shells: list
    raw: dict = field(repr=False, compare=False)

    @classmethod
    def from_json(cls, text: str) -> "Results":
        d = json.loads(text)
        return cls(
            step=int(d["step"]),
            stage=d["stage"],
            converged=bool(d["converged"]),
            stable=bool(d["stable"]),
            pieces=int(d["pieces"]),
            rods=_Named(RodResult.from_json(r) for r in d["rods"]),
            structures=[StructureResult.from_json(s) for s in d["structures"]],
            shells=_Named(ShellResult.from_json(s) for s in d["shells"]),
            raw=d,
        )

    @property
    def edges_through_obstacles(self) -> list:
        """Rod edges whose centerline, and shell-strip faces whose mid-surface, run through an
        obstacle between their vertices: contact acts at the vertices, so such a shape is the
        discrete model's equilibrium but not the cable's, and the mesh must be finer than the
        obstacle there. Dicts with ``rod`` (rod or strip name), ``shell`` (bool), ``edge`` (a
        rod edge's first vertex, or a strip's face index), ``vertices``, ``obstacle``,
        ``position`` (deepest point, m) and ``depth`` (m); empty when there is none."""
        return list(self.raw.get("edges_through_obstacles", []))

    def reports(self) -> list:
        """Every solver report of the step (rods' parts, then shells)."""
        out = [r for rod in self.rods for r in rod.reports]
        out += [s.report for s in self.shells]
        return out
