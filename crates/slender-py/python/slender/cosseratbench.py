"""slender as a solver of the cosseratbench rod benchmark (https://github.com/jakeryderv/cosseratbench).

Registered through the entry point ``cosseratbench.solvers: slender`` (pyproject.toml), so
that ``cosseratbench run catenary -s slender -s pyelastica -s mujoco`` runs it beside the
other solvers and scores it with the benchmark's own metrics.

What slender computes is equilibria (a quasi-static Newton solver with exact Hessians), so
it runs the scenarios marked ``quasi_static`` whose result is the equilibrium. A trajectory
has the scenario's initial shape at t = 0 (``Rod.nodes``, ``Rod.directors``) and the
equilibrium in every later frame: no dynamics is computed, so the settling residual is 0.
Everything outside slender's model is reported as unsupported (``NotImplementedError``)
rather than run with something else: dynamics (``quasi_static = False``), contact (no
contact capability is declared, so the benchmark itself skips those), driven ends
(``Motion``), a rod held by nothing.

Mapping of a scenario rod to a scene rod: a straight stress-free rod of the rod's
unstretched length from its first centerline point along the chord, ``n_elements`` uniform
elements (the benchmark's material points), circular section of the rod's radius, Young's
and shear moduli and density as given, m₁ along the rod's ``normal``; pinned ends are
``pin`` supports, clamped ends ``clamp`` supports, point loads dead forces at the end
vertex; a rod held by pins only also gets a ``twist_hold`` at its start (its spin about its
own axis costs no energy, a null mode a static solve must remove). When the initial shape is not straight, the end supports are then moved (and a
clamp turned) from the straight rest shape to where the initial shape holds them, through
the session's warm re-solves (the load path is the solver's business; the equilibrium
reached is the one scored).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from cosseratbench import Capability, Scenario, Trajectory
from cosseratbench.scenario import End, EndCondition
from cosseratbench.solver import Diverged

from . import __version__
from .session import NotConvergedError, Session

_KIND = {EndCondition.PINNED: "pin", EndCondition.CLAMPED: "clamp"}


def _rotation_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Rotation vector of the smallest rotation taking unit a to unit b."""
    axis = np.cross(a, b)
    s, c = np.linalg.norm(axis), float(np.dot(a, b))
    if s < 1e-15:
        if c > 0:
            return np.zeros(3)
        raise NotImplementedError("a clamped end whose initial tangent reverses the chord")
    return axis / s * np.arctan2(s, c)


class SlenderSolver:
    """The cosseratbench adapter of slender (see the module docs)."""

    name = "slender"
    # Kirchhoff rod: extensible, unshearable; no contact of any kind.
    capabilities = frozenset({Capability.STRETCH})
    backend_version = __version__

    def settings(self, scenario: Scenario, *, n_elements: int, n_frames: int) -> dict[str, Any]:
        return {
            "method": "static equilibrium: Newton with exact Hessian, load continuation",
            "model": "discrete elastic rod (Kirchhoff, extensible)",
            "frames": "t = 0 the initial shape; every later frame the equilibrium",
            "force_tolerance": 1e-8,
            "pinned_pinned": "twist held at the start (removes the free spin about the axis)",
        }

    def _scene(self, scenario: Scenario, n_elements: int) -> tuple[dict, list]:
        rods, moves = [], []
        for i, rod in enumerate(scenario.rods):
            if rod.start_motion is not None or rod.end_motion is not None:
                raise NotImplementedError(
                    "driven clamped ends (Motion), not mapped to slender's support motion"
                )
            if rod.start is EndCondition.FREE and rod.end is EndCondition.FREE:
                raise NotImplementedError("a rod held by nothing has no static equilibrium")
            pts = np.asarray(rod.centerline, dtype=float)
            chord = pts[-1] - pts[0]
            direction = chord / np.linalg.norm(chord)
            nodes = rod.nodes(n_elements)
            supports, forces = [], []
            for end, vertex, at in ((End.START, "start", 0), (End.END, "end", -1)):
                cond = rod.condition(end)
                if cond is EndCondition.FREE:
                    continue
                k = len(supports)
                supports.append({"kind": _KIND[cond], "vertex": vertex})
                rest = pts[0] + (0.0 if at == 0 else rod.length) * direction
                translation = nodes[at] - rest
                rotation = np.zeros(3)
                if cond is EndCondition.CLAMPED:
                    t = nodes[1] - nodes[0] if at == 0 else nodes[-1] - nodes[-2]
                    rotation = _rotation_between(direction, t / np.linalg.norm(t))
                if np.any(np.abs(translation) > 1e-12) or np.any(np.abs(rotation) > 1e-12):
                    moves.append((i, k, translation, rotation))
            if EndCondition.CLAMPED not in (rod.start, rod.end):
                # Pins leave the spin of the whole rod about its own axis free: a null mode
                # of the stiffness that a static solve must fix. A twist hold at the start
                # fixes it; it carries no moment unless something twists the rod.
                supports.append({"kind": "twist_hold", "vertex": "start"})
            for load in rod.loads:
                forces.append(
                    {"vertex": "start" if load.at is End.START else "end", "force": list(load.force)}
                )
            m = rod.material
            rods.append(
                {
                    "name": f"rod{i}",
                    "elements": n_elements,
                    "centerline": {
                        "kind": "straight",
                        "start": [float(x) for x in pts[0]],
                        "direction": [float(x) for x in direction],
                        "length": rod.length,
                    },
                    "section": {"shape": "circle", "diameter": 2.0 * rod.radius},
                    "material": {
                        "young": m.youngs_modulus,
                        "shear_modulus": m.shear_modulus,
                        "density": m.density,
                    },
                    "first_director": [float(x) for x in rod.normal],
                    "supports": supports,
                    "forces": forces,
                }
            )
        return {"gravity": list(scenario.gravity), "rods": rods}, moves

    def run(self, scenario: Scenario, *, n_elements: int, n_frames: int) -> Trajectory:
        if not scenario.quasi_static:
            raise NotImplementedError(
                "dynamics: slender computes equilibria, and this scenario's result is its motion"
            )
        if scenario.obstacles:
            raise NotImplementedError("contact with obstacles")
        scene, moves = self._scene(scenario, n_elements)
        try:
            session = Session(scene)
            if not session.results().converged:
                raise NotConvergedError("the loaded scene did not converge")
            for rod, support, translation, rotation in moves:
                session.move_support(rod, support, translation=translation, rotation=rotation)
        except NotConvergedError as e:
            raise Diverged(f"slender: {e}") from e
        result = session.results()
        times = np.linspace(0.0, scenario.duration, n_frames)
        positions, directors = [], []
        for i, rod in enumerate(scenario.rods):
            r = result.rods[i]
            p = np.repeat(r.positions[None], n_frames, axis=0)
            d = np.repeat(r.frames[None, :, 0, :], n_frames, axis=0)
            p[0] = rod.nodes(n_elements)
            d[0] = rod.directors(n_elements)
            positions.append(p)
            directors.append(d)
        return Trajectory(times, tuple(positions), tuple(directors))
