"""Shared fixtures: the repository, the `slender` binary (built if missing) and small scenes."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="session")
def slender_bin() -> Path:
    """The `slender` command-line tool of this checkout (SLENDER_BIN, or target/release)."""
    env = os.environ.get("SLENDER_BIN")
    if env:
        return Path(env)
    path = REPO / "target" / "release" / "slender"
    # Always ask cargo: it rebuilds only if the sources changed, so the comparison is with
    # the binary of this very checkout.
    subprocess.run(
        ["cargo", "build", "--release", "-p", "slender", "--quiet"], cwd=REPO, check=True
    )
    return path


def cable_scene(elements: int = 100, clips: tuple[int, ...] = ()) -> dict:
    """A 1 m cable (d = 6 mm, E = 1 GPa) clamped at both ends, sagging under gravity: the
    scene of `cargo bench -p slender-core --bench session_edit`."""
    supports = [{"kind": "clamp", "vertex": "start"}, {"kind": "clamp", "vertex": "end"}]
    supports += [{"kind": "clip", "vertex": v} for v in clips]
    return {
        "gravity": [0.0, 0.0, -9.81],
        "rods": [
            {
                "name": "cable",
                "elements": elements,
                "centerline": {
                    "kind": "straight",
                    "start": [0.0, 0.0, 0.0],
                    "direction": [1.0, 0.0, 0.0],
                    "length": 1.0,
                },
                "section": {"shape": "circle", "diameter": 0.006},
                "material": {"young": 1.0e9, "poisson": 0.4, "density": 1400.0},
                "supports": supports,
            }
        ],
    }
