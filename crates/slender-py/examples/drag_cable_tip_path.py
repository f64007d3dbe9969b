"""Drag a cable's clamped end along a path and plot the path of its free tip.

A 0.6 m cable (d = 6 mm, E = 200 MPa) is clamped at one end and hangs under gravity; the
clamp is carried around a horizontal circle of radius 0.15 m while it pitches up and down
by ±0.5 rad, in 48 warm re-solves (each edit starts from the previous equilibrium, as in
`slender view`; a pure translation would only move the hanging cable rigidly). The free tip's path, the
clamp's path and a few shapes are plotted to drag_cable_tip_path.png.

    pip install ./crates/slender-py matplotlib
    python crates/slender-py/examples/drag_cable_tip_path.py
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import slender  # noqa: E402

x = np.linspace(0.0, 0.6, 41)
scene = slender.rod_scene(
    np.stack([x, np.zeros_like(x), np.zeros_like(x)], axis=1),  # rest centerline (m)
    section={"shape": "circle", "diameter": 0.006},
    material={"young": 2.0e8, "poisson": 0.45, "density": 1500.0},
    supports=[{"kind": "clamp", "vertex": "start"}],
    gravity=[0.0, 0.0, -9.81],
    name="cable",
)
session = slender.Session(scene)
radius, steps = 0.15, 48
clamp_path, tip_path, shapes = [], [], []
for k in range(steps + 1):
    a = 2.0 * math.pi * k / steps
    # Absolute clamp pose: on the circle (starting at the origin), pitched about y by
    # 0.5 sin(a) rad from its rest orientation.
    target = [radius * (1.0 - math.cos(a)), radius * math.sin(a), 0.0]
    report = session.move_support(0, 0, position=target, rotation=[0.0, 0.5 * math.sin(a), 0.0])
    rod = session.results().rods["cable"]
    clamp_path.append(rod.positions[0])
    tip_path.append(rod.positions[-1])
    if k % 12 == 0:
        shapes.append(rod.positions)
    print(f"step {k:2d}: {report.iterations} Newton iterations, tip at {np.round(rod.positions[-1], 4)} m")

clamp_path, tip_path = np.array(clamp_path), np.array(tip_path)
fig = plt.figure(figsize=(10, 4.5))
top = fig.add_subplot(1, 2, 1)
top.plot(clamp_path[:, 0], clamp_path[:, 1], "k--", label="clamp")
top.plot(tip_path[:, 0], tip_path[:, 1], "C3", label="free tip")
for p in shapes:
    top.plot(p[:, 0], p[:, 1], "C0", lw=0.8, alpha=0.6)
top.set(xlabel="x (m)", ylabel="y (m)", title="top view", aspect="equal")
top.legend()
ax = fig.add_subplot(1, 2, 2, projection="3d")
ax.plot(*clamp_path.T, "k--")
ax.plot(*tip_path.T, "C3")
for p in shapes:
    ax.plot(*p.T, "C0", lw=0.8)
ax.set(xlabel="x (m)", ylabel="y (m)", zlabel="z (m)", title="tip path while dragging the clamp")
fig.tight_layout()
fig.savefig("drag_cable_tip_path.png", dpi=120)
print("wrote drag_cable_tip_path.png")
