"""The Markdown table of a cosseratbench results directory: per experiment variant and solver,
the outcome, every metric and the wall time (result.json of each run).

    python crates/slender-py/benches/cosseratbench_table.py results/
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def main(root: Path) -> None:
    rows = []
    for path in sorted(root.glob("*/*/*/result.json")):
        r = json.loads(path.read_text())
        experiment, variant, solver = path.parts[-4], path.parts[-3], path.parts[-2]
        if r["outcome"] == "completed":
            metrics = ", ".join(f"{k} {v:.3e}" for k, v in r["metrics"].items())
            wall = f"{r['wall_time']:.3g}"
        elif r["outcome"] == "unsupported":
            metrics = "unsupported: " + "; ".join(r.get("missing", []))
            wall = "—"
        else:
            metrics = f"{r['outcome']}: {r.get('failure', '')}"
            wall = "—"
        rows.append((experiment, variant, solver, r.get("n_elements"), metrics, wall))
    print("| experiment | variant | solver | elements | metrics | wall time (s) |")
    print("|---|---|---|---|---|---|")
    for e, v, s, n, m, w in rows:
        print(f"| {e} | {v} | {s} | {n} | {m} | {w} |")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "results"))
