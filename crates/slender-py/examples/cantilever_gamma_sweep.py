"""The rod cantilever benchmark as a Γ sweep: slender's discrete elastic rod against the
heavy-elastica master curve (computed independently, by multiple shooting).

For each Γ = ρAgL³/EI the clamped rod of the seed's material set sags under its own weight;
Δy/Δx of its end points is compared with the master curve. Writes
cantilever_gamma_sweep.csv and cantilever_gamma_sweep.png.

    pip install ./crates/slender-py matplotlib
    python crates/slender-py/examples/cantilever_gamma_sweep.py
"""

from __future__ import annotations

import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import slender  # noqa: E402

gammas = np.logspace(-1, 3, 17)
records = {n: [slender.cantilever_case(g, n_elements=n, mesh="graded") for g in gammas] for n in (8, 30)}
curve = np.logspace(-1, 3, 81)
master = np.array([slender.heavy_elastica(g, n=1)["ratio"] for g in curve])

with open("cantilever_gamma_sweep.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(records[8][0].keys()))
    w.writeheader()
    for recs in records.values():
        w.writerows(recs)

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
a.semilogx(curve, master, "k", label="master curve (heavy elastica)")
for n, recs in records.items():
    a.semilogx(gammas, [r["ratio"] for r in recs], "o", ms=4, label=f"slender, {n} elements")
    b.loglog(gammas, [abs(r["rel_error"]) for r in recs], "o-", ms=4, label=f"{n} elements")
a.set(xlabel="Γ = ρAgL³/EI", ylabel="Δy/Δx", title="rod cantilever")
b.set(xlabel="Γ", ylabel="|relative error| of Δy/Δx", title="error against the master curve")
a.legend()
b.legend()
fig.tight_layout()
fig.savefig("cantilever_gamma_sweep.png", dpi=120)
worst = {n: max(abs(r["rel_error"]) for r in recs) for n, recs in records.items()}
print("worst |error| over Γ ∈ [0.1, 1000]:", {n: f"{e:.2e}" for n, e in worst.items()})
print("wrote cantilever_gamma_sweep.csv, cantilever_gamma_sweep.png")
