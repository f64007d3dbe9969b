"""Read a VTK result written by `slender solve` into NumPy arrays, and check it against the
same scene solved from Python.

`slender solve SCENE --out DIR` writes DIR/step_NNN/shape.vtk (legacy ASCII POLYDATA: the
rods' vertices as polylines with `radius`, `curvature`, `twist` point data). This reads it
with nothing but NumPy (no VTK library), plots nothing, and prints the largest difference to
the Python results (the VTK file rounds to the `{:e}` text format: ~1e-16 relative).

    cargo build --release && pip install ./crates/slender-py
    python crates/slender-py/examples/read_vtk_result.py [examples/u_cable_moved.toml]
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import slender

REPO = Path(__file__).resolve().parents[3]


def read_vtk(path: Path) -> dict:
    """Points (n, 3), polylines (list of index arrays) and point data of a legacy ASCII
    POLYDATA file."""
    tokens = path.read_text().split()
    out: dict = {"lines": [], "point_data": {}}
    i = 0
    while i < len(tokens):
        t = tokens[i]
        if t == "POINTS":
            n = int(tokens[i + 1])
            out["points"] = np.array(tokens[i + 3 : i + 3 + 3 * n], dtype=float).reshape(n, 3)
            i += 3 + 3 * n
        elif t == "LINES":
            count = int(tokens[i + 1])
            i += 3
            for _ in range(count):
                k = int(tokens[i])
                out["lines"].append(np.array(tokens[i + 1 : i + 1 + k], dtype=int))
                i += 1 + k
        elif t == "POLYGONS":
            count = int(tokens[i + 1])
            i += 3 + 4 * count
        elif t == "SCALARS":
            name = tokens[i + 1]
            n = len(out["points"])
            start = i + 6 if tokens[i + 4] == "LOOKUP_TABLE" else i + 4
            out["point_data"][name] = np.array(tokens[start : start + n], dtype=float)
            i = start + n
        else:
            i += 1
    return out


def main() -> None:
    scene = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "examples" / "u_cable_moved.toml"
    binary = REPO / "target" / "release" / "slender"
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "out"
        subprocess.run([str(binary), "solve", str(scene), "--out", str(out), "--no-preview"], check=True)
        last = sorted(out.glob("step_*"))[-1]
        vtk = read_vtk(last / "shape.vtk")
    steps = slender.Session(scene).run_motion()
    result = steps[-1]
    print(f"{last.name}/shape.vtk: {len(vtk['points'])} points, {len(vtk['lines'])} polylines, "
          f"point data {sorted(vtk['point_data'])}")
    for line, rod in zip(vtk["lines"], result.rods):
        xyz = vtk["points"][line]
        err = np.abs(xyz - rod.positions).max()
        kappa = np.hypot(rod.curvature[:, 0], rod.curvature[:, 1])
        kerr = np.abs(vtk["point_data"]["curvature"][line] - kappa).max()
        print(f"rod {rod.name}: {len(line)} vertices, max |x_vtk - x_python| = {err:.2e} m, "
              f"max |curvature difference| = {kerr:.2e} 1/m")


if __name__ == "__main__":
    main()
