"""Scenes as Python data: read a scene file into a dict, or build one rod's scene from NumPy
arrays. The dict has the structure of the TOML/JSON format (README: "Scene files")."""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any, Union

import numpy as np

from . import _slender
from ._slender import SceneError

PathLike = Union[str, "os.PathLike[str]"]


def _syntax(path: Path) -> str:
    return "json" if path.suffix.lower() == ".json" else "toml"


def load_scene(path: PathLike) -> dict[str, Any]:
    """Reads a scene file (TOML, or JSON for ``.json``) into a dict with every default filled
    in. Bad content raises :class:`SceneError` (a ``ValueError``) naming the field."""
    p = Path(path)
    text = p.read_text(encoding="utf-8")
    return json.loads(_slender.normalize_scene(text, _syntax(p), str(p)))


def plain(value: Any) -> Any:
    """``value`` with NumPy arrays and scalars turned into lists and Python numbers (exactly),
    tuples into lists, mappings into dicts: scene data the core reads."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def _points(centerline: Any) -> np.ndarray:
    try:
        pts = np.asarray(centerline, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise _error("rods[0].centerline.points", f"not an array of numbers: {e}") from None
    if pts.ndim != 2 or pts.shape[1] != 3 or pts.shape[0] < 2:
        raise _error(
            "rods[0].centerline.points",
            f"shape {pts.shape}: must be (n, 3) with n >= 2 points (m)",
        )
    if not np.all(np.isfinite(pts)):
        raise _error("rods[0].centerline.points", "every coordinate must be a finite number")
    return pts


def _error(field: str, message: str) -> SceneError:
    e = SceneError(f"{field}: {message}")
    e.field = field
    return e


def rod_scene(
    centerline: Any,
    *,
    section: Mapping[str, Any],
    material: Mapping[str, Any] | None = None,
    supports: Iterable[Mapping[str, Any]] = (),
    elements: int | None = None,
    gravity: Sequence[float] = (0.0, 0.0, 0.0),
    forces: Iterable[Mapping[str, Any]] = (),
    moments: Iterable[Mapping[str, Any]] = (),
    first_director: Sequence[float] | None = None,
    name: str = "rod",
    solver: Mapping[str, Any] | None = None,
    **rod_keys: Any,
) -> dict[str, Any]:
    """The scene of one rod whose rest centerline is the polyline ``centerline``, an
    ``(n, 3)`` array of points (m).

    Without ``elements`` the points are the rod's nodes (n − 1 elements); with it the
    polyline is remeshed uniformly by arc length. ``section`` is a scene section, e.g.
    ``{"shape": "circle", "diameter": 0.006}`` or ``{"shape": "stiffness", "ea": ...,
    "ei1": ..., "ei2": ..., "gj": ..., "linear_density": ...}``; ``material`` e.g.
    ``{"young": 2e8, "poisson": 0.4, "density": 1500.0}`` (not with a stiffness section).
    ``supports``, ``forces``, ``moments`` and any further rod key (``line_loads``,
    ``grading``, ``closed``, …) are as in a scene file. Nothing is checked here beyond the
    array's shape: :class:`Session` validates the scene and names the field of any error.
    """
    pts = _points(centerline)
    rod: dict[str, Any] = {
        "name": name,
        "centerline": {"kind": "polyline", "points": pts.tolist()},
        "section": plain(dict(section)),
        "supports": plain(list(supports)),
        "forces": plain(list(forces)),
        "moments": plain(list(moments)),
    }
    if material is not None:
        rod["material"] = plain(dict(material))
    if elements is not None:
        rod["elements"] = int(elements)
    if first_director is not None:
        rod["first_director"] = plain(first_director)
    rod.update(plain(rod_keys))
    scene: dict[str, Any] = {"gravity": plain(gravity), "rods": [rod]}
    if solver is not None:
        scene["solver"] = plain(dict(solver))
    return scene
