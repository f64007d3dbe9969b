"""The cosseratbench plug-in (skipped when cosseratbench is not installed): the benchmark
finds slender through its entry point and scores it with its own metrics."""

from __future__ import annotations

import pytest

cb = pytest.importorskip("cosseratbench")

from cosseratbench import registry  # noqa: E402
from cosseratbench.experiment import run  # noqa: E402


def test_registered_and_scored() -> None:
    solver = registry.load_solver("slender")
    cantilever = run(registry.load_experiment("cantilever"), solver)
    assert cantilever.metrics["tip_deflection_error"] < 5e-3
    catenary = run(registry.load_experiment("catenary"), solver)
    assert catenary.metrics["shape_error"] < 1e-3


def test_outside_the_model_is_unsupported() -> None:
    solver = registry.load_solver("slender")
    for name in ("pendulum", "twist"):
        result = run(registry.load_experiment(name), solver)
        assert result.missing, name
