"""Cost of a warm re-solve called from Python, against the same edit in Rust.

The scene and the edit are those of `cargo bench -p slender-core --bench session_edit`: a 1 m
cable of 100 elements clamped at both ends (and with three clips), its end clamp dragged
across the span by ±1 cm per call (alternating, so every call is a real re-solve from the
previous equilibrium). Prints the median time per call over repeated timeit batches.

    python crates/slender-py/benches/session_edit.py
"""

from __future__ import annotations

import statistics
import timeit

import slender


def scene(clips: tuple[int, ...]) -> dict:
    supports = [{"kind": "clamp", "vertex": "start"}, {"kind": "clamp", "vertex": "end"}]
    supports += [{"kind": "clip", "vertex": v} for v in clips]
    return {
        "gravity": [0.0, 0.0, -9.81],
        "rods": [
            {
                "name": "cable",
                "elements": 100,
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


def bench(name: str, clips: tuple[int, ...], number: int = 200, repeat: int = 15) -> None:
    session = slender.Session(scene(clips))
    sign = [1.0]

    def drag() -> None:
        r = session.move_support(0, 1, translation=[0.0, 0.01 * sign[0], 0.0])
        assert r.converged
        sign[0] = -sign[0]

    # The same number of calls per batch keeps the pose alternating as in the Rust bench.
    for _ in range(20):
        drag()
    times = timeit.repeat(drag, number=number, repeat=repeat)
    per_call = sorted(t / number for t in times)
    med = statistics.median(per_call)
    print(f"{name:45s} median {med * 1e6:8.1f} µs   min {per_call[0] * 1e6:8.1f} µs   ({repeat} × {number} calls)")


if __name__ == "__main__":
    bench("python warm_drag_1cm/n100_two_clamps", ())
    bench("python warm_drag_1cm/n100_two_clamps_three_clips", (25, 50, 75))
