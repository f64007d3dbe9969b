"""slender: large deformations of slender elastic structures from Python.

Scenes (the TOML/JSON format of ``slender solve``, or the same structure as a dict) are
compiled and solved by the Rust core; a :class:`Session` keeps the last equilibrium and
re-solves warm after every edit (move a support, add a clip, change gravity). Results are
NumPy arrays in SI units. Solves release the GIL.

    import slender
    s = slender.Session("examples/u_cable_moved.toml")
    s.move_support(rod=0, support=1, translation=[0.05, 0.0, 0.0])
    r = s.results()
    r.rods[0].positions          # (n + 1, 3) float64, m
"""

from __future__ import annotations

from ._slender import EditReport, SceneError, SolverPanic, __version__
from .benchmarks import cantilever_case, heavy_elastica, lateral_buckling_critical_gamma
from .results import Results, RodResult, ShellResult, SolveReport, StructureResult
from .scene import load_scene, rod_scene
from .session import NotConvergedError, Session, solve

__all__ = [
    "EditReport",
    "NotConvergedError",
    "Results",
    "RodResult",
    "SceneError",
    "Session",
    "ShellResult",
    "SolveReport",
    "SolverPanic",
    "StructureResult",
    "__version__",
    "cantilever_case",
    "heavy_elastica",
    "lateral_buckling_critical_gamma",
    "load_scene",
    "rod_scene",
    "solve",
]
