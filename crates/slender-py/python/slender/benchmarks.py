"""The validation benchmarks' master curves and cases, as plain records and NumPy arrays."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _slender


def heavy_elastica(gamma: float, n: int = 100) -> dict[str, Any]:
    """The heavy elastica (the rod cantilever's master curve) at Γ = ρAgL³/EI, by multiple
    shooting, independent of the rod model.

    Returns a dict: ``gamma``; ``clamp_curvature`` (units of 1/L); ``tip_angle`` (rad below
    the horizontal); ``dx``, ``dy`` (tip position, units of L, dy > 0 downward); ``ratio`` =
    dy/dx; ``shape``, an ``(n + 1, 2)`` float64 array of (x, y) in units of L at equal
    arc-length stations (y negative downward). Γ outside [1e-3, 1e5] raises ``ValueError``.
    """
    d = _slender.heavy_elastica(float(gamma), int(n))
    d["shape"] = np.asarray(d["shape"], dtype=np.float64).reshape(-1, 2)
    return d


def cantilever_case(
    gamma: float, n_elements: int = 20, material: str = "rod", mesh: str = "graded"
) -> dict[str, Any]:
    """One case of the rod cantilever benchmark: the clamped rod of the seed's material set
    ``material`` ("rod" or "bundle") sagging under its own weight at Γ, ``n_elements``
    elements on a ``mesh`` ("uniform", "quadratic" or "graded") mesh, solved by slender and
    scored against the heavy elastica. Returns the benchmark's record: ``ratio`` (Δy/Δx),
    ``master``, ``rel_error``, ``converged``, ``iterations``, ``load_steps``,
    ``relative_residual``, ``negative_eigenvalues``, ``lambda_min_normalized``, ``failure``.
    """
    return _slender.cantilever_case(float(gamma), int(n_elements), material, mesh)


def lateral_buckling_critical_gamma(
    w_over_l: float, nu: float, curve: str = "kirchhoff_plate"
) -> float:
    """Γ_c = ρhgL³/D of the lateral-buckling benchmark (a strip clamped with its width along
    gravity) at width ratio ``w_over_l`` and Poisson's ratio ``nu``, from the master curve
    ``curve``: "kirchhoff_plate", "vlasov_beam" (B = E w h³/12) or "vlasov_plate" (B = D w).
    """
    return _slender.lateral_buckling_critical_gamma(float(w_over_l), float(nu), curve)
