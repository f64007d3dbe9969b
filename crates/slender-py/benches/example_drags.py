"""Interactive drags of every example scene: a support of each cable (and a clamp of each flat
cable) moved by ±1 cm along gravity, alternately down and up, as a user drags it in
`slender view`. Prints, per scene and support, the median and largest time of one drag, the
largest Newton iteration count and whether every drag converged.

    python crates/slender-py/benches/example_drags.py [examples/]
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

import slender

DRAGS = 10
STEP = 0.01  # m


def drags(move) -> tuple[list[float], list[int], bool]:
    times, iterations, converged = [], [], True
    sign = -1.0
    for _ in range(DRAGS):
        t = time.perf_counter()
        report = move(sign)
        times.append(time.perf_counter() - t)
        iterations.append(report.iterations)
        converged = converged and report.converged
        sign = -sign
    return times, iterations, converged


def row(what: str, times: list[float], iterations: list[int], converged: bool) -> str:
    return (
        f"    {what:28} median {1e3 * statistics.median(times):8.2f} ms  "
        f"max {1e3 * max(times):8.2f} ms  iterations ≤ {max(iterations):4d}  "
        f"{'converged' if converged else 'NOT CONVERGED'}"
    )


def main(folder: Path) -> None:
    for path in sorted(folder.glob("*.toml")):
        started = time.perf_counter()
        session = slender.Session(path)
        cold = time.perf_counter() - started
        scene = session.scene()
        g = np.asarray(scene.get("gravity", [0.0, 0.0, 0.0]), dtype=float)
        down = g / np.linalg.norm(g) if np.linalg.norm(g) > 0 else np.array([0.0, 0.0, -1.0])
        print(f"{path.name}  (solved in {cold:.2f} s)")
        for r, rod in enumerate(scene.get("rods", [])):
            supports = rod.get("supports", [])
            movable = [k for k, s in enumerate(supports) if s.get("kind") in ("clamp", "clip", "pin")]
            if not movable:
                continue
            k = movable[-1]
            result = drags(
                lambda sign: session.move_support(
                    r, k, translation=list(sign * STEP * down), check=False
                )
            )
            print(row(f"rod {r}, support {k} ({supports[k]['kind']})", *result))
        for sh, shell in enumerate(scene.get("shells", [])):
            c = len(shell.get("clamps") or [None]) - 1
            result = drags(
                lambda sign: session.move_shell_clamp(
                    sh, c, translation=list(sign * STEP * down), check=False
                )
            )
            print(row(f"flat cable {sh}, clamp {c}", *result))


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "examples"))
