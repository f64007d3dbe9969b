"""The Python package gives the very numbers of `slender solve` (bit for bit) on every
example scene: every step's result.json, and the vertex and reaction CSV files."""

from __future__ import annotations

import csv
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import slender

from conftest import EXAMPLES

# Time-stepped scenes ([time]) are solved by `slender solve` only (the Python session solves
# equilibria).
SCENES = sorted(
    p.name for p in EXAMPLES.glob("*.toml") if "\n[time]" not in p.read_text()
)
# Keys the Python results add to result.json's rods (the internal loads).
ADDED = {"axial_force", "bending_moment", "twisting_moment"}


def _without_time(step: dict) -> dict:
    d = dict(step)
    d.pop("seconds")
    d["rods"] = [{k: v for k, v in r.items() if k not in ADDED} for r in d["rods"]]
    return d


def _csv(path: Path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.mark.parametrize("name", SCENES)
def test_results_equal_slender_solve(name: str, slender_bin: Path, tmp_path: Path) -> None:
    scene = EXAMPLES / name
    out = tmp_path / "out"
    run = subprocess.run(
        [str(slender_bin), "solve", str(scene), "--out", str(out), "--no-preview"],
        capture_output=True,
        text=True,
    )
    assert run.returncode in (0, 1), run.stderr
    steps = slender.Session(scene).run_motion()
    step_dirs = sorted(out.glob("step_*"))
    assert len(steps) == len(step_dirs)
    for step, d in zip(steps, step_dirs):
        expected = json.loads((d / "result.json").read_text())
        expected.pop("seconds")
        # Every number of result.json, compared as parsed floats: equal means same bits.
        assert _without_time(step.raw) == expected, f"{name} {d.name}"
        for rod in step.rods:
            rows = _csv(d / f"{rod.name}_vertices.csv")
            xyz = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows])
            assert np.array_equal(xyz, rod.positions), f"{name} {d.name} {rod.name}"
            rows = _csv(d / f"{rod.name}_edges.csv")
            m1 = np.array([[float(r["m1x"]), float(r["m1y"]), float(r["m1z"])] for r in rows])
            assert np.array_equal(m1, rod.frames[:, 0, :])
    reactions = _csv(out / "reactions.csv")
    for row in reactions:
        step = steps[int(row["step"])]
        rod = step.rods[row["rod"]]
        k = int(row["support"])
        f = [float(row[c]) for c in ("fx", "fy", "fz")]
        m = [float(row[c]) for c in ("mx", "my", "mz")]
        assert np.array_equal(rod.support_forces[k], f)
        assert np.array_equal(rod.support_moments[k], m)


def test_dict_scene_equals_file_scene() -> None:
    """A scene read into a dict (and edited as data) solves to the same bits as its file."""
    path = EXAMPLES / "u_cable_moved.toml"
    a = slender.Session(path).results()
    b = slender.Session(slender.load_scene(path)).results()
    assert _without_time(a.raw) == _without_time(b.raw)


def test_json_file_equals_toml_file(tmp_path: Path) -> None:
    """The JSON form of a scene file solves to the same bits as its TOML form."""
    path = EXAMPLES / "branched_harness.toml"
    as_json = tmp_path / "scene.json"
    as_json.write_text(json.dumps(slender.load_scene(path)))
    a = slender.solve(path)
    b = slender.solve(as_json)
    assert [_without_time(s.raw) for s in a] == [_without_time(s.raw) for s in b]
