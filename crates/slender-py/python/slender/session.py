"""The incremental simulation API: a scene solved once, then edited and re-solved warm."""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Optional, Union

import numpy as np

from . import _slender
from ._slender import EditReport, SceneError
from .results import Results
from .scene import _syntax, plain


class NotConvergedError(RuntimeError):
    """A solve or an edit did not reach an equilibrium. ``report`` (an :class:`EditReport`)
    or ``results`` (a :class:`Results` marked not converged) say where and why; a session
    keeps its last equilibrium and stays usable."""

    def __init__(self, message: str, report: Any = None, results: Any = None) -> None:
        super().__init__(message)
        self.report = report
        self.results = results


def _vec3(value: Any, name: str) -> list[float]:
    # Fast path for plain sequences of three numbers (the common case of interactive edits).
    if type(value) in (list, tuple) and len(value) == 3:
        try:
            return [float(value[0]), float(value[1]), float(value[2])]
        except (TypeError, ValueError):
            pass
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        a = np.asarray([np.nan])
    if a.shape != (3,):
        e = SceneError(f"{name}: must be 3 numbers, got {value!r}")
        e.field = name
        raise e
    return [float(x) for x in a]


def _index(value: Any, name: str) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or value < 0:
        e = SceneError(f"{name}: {value!r}: must be an integer >= 0")
        e.field = name
        raise e
    return int(value)


def _move(to: Any, by: Any, position: Any, rotation: Any, translation: Any) -> EditReport:
    """A move to ``position`` (``to(position, rotation or None)``) or by ``translation``
    (``by(translation, rotation or 0)``): exactly one of the two must be given."""
    if (position is None) == (translation is None):
        raise TypeError("give exactly one of position= or translation=")
    if translation is not None:
        rot = [0.0, 0.0, 0.0] if rotation is None else _vec3(rotation, "rotation")
        return by(_vec3(translation, "translation"), rot)
    return to(_vec3(position, "position"), None if rotation is None else _vec3(rotation, "rotation"))


class Session:
    """A scene compiled, solved (the loaded equilibrium, step 0) and ready to edit.

    ``scene`` is a path to a TOML/JSON scene file, or a dict with the same structure (see
    :func:`load_scene`, :func:`rod_scene`). A bad scene raises :class:`SceneError` (a
    ``ValueError``) whose message starts with the field, e.g. ``rods[0].material.young``.

    Every edit re-solves warm from the last equilibrium with the GIL released and returns an
    :class:`EditReport`; with ``check=True`` (default) an edit that does not converge raises
    :class:`NotConvergedError` (the session keeps its last equilibrium and the support stays
    where it was). Sessions are independent: several threads may each solve their own at
    once; one session is used by one thread at a time.
    """

    def __init__(self, scene: Union[str, "os.PathLike[str]", Mapping[str, Any]]) -> None:
        if isinstance(scene, Mapping):
            self._inner = _slender.Session.from_dict(plain(scene))
        elif isinstance(scene, (str, os.PathLike)):
            p = Path(scene)
            text = p.read_text(encoding="utf-8")
            if _syntax(p) == "json":
                self._inner = _slender.Session.from_json(text, str(p))
            else:
                self._inner = _slender.Session.from_toml(text, str(p))
        else:
            raise TypeError(f"scene must be a path or a dict, not {type(scene).__name__}")
        self._step = 0

    @classmethod
    def from_toml(cls, text: str) -> "Session":
        """A session of scene TOML text."""
        s = cls.__new__(cls)
        s._inner = _slender.Session.from_toml(text, "scene")
        s._step = 0
        return s

    # --- results -------------------------------------------------------------------------

    def results(self) -> Results:
        """The current equilibria as arrays (see :class:`Results`)."""
        return Results.from_json(self._inner.results(self._step))

    @property
    def converged(self) -> bool:
        """True if every structure of the scene is at a converged equilibrium."""
        return self.results().converged

    @property
    def n_structures(self) -> int:
        """Number of structures (groups of rod parts solved together)."""
        return self._inner.n_structures()

    def pose(self, rod: int, support: int) -> tuple[np.ndarray, np.ndarray]:
        """Where a support is: (position (3,) m, rotation vector (3,) rad from rest)."""
        p = self._inner.pose(_index(rod, "rod"), _index(support, "support"))
        if p is None:
            e = SceneError(f"rods[{rod}].supports[{support}]: no such support")
            e.field = f"rods[{rod}].supports[{support}]"
            raise e
        return np.asarray(p[0]), np.asarray(p[1])

    def shell_pose(self, shell: int, clamp: int) -> tuple[np.ndarray, np.ndarray]:
        """Where a shell strip's clamp is: (the centre of its edge (3,) m, rotation vector (3,)
        rad from rest)."""
        p = self._inner.shell_pose(_index(shell, "shell"), _index(clamp, "clamp"))
        if p is None:
            e = SceneError(f"shells[{shell}].clamps[{clamp}]: no such clamp")
            e.field = f"shells[{shell}].clamps[{clamp}]"
            raise e
        return np.asarray(p[0]), np.asarray(p[1])

    def scene(self) -> dict[str, Any]:
        """The scene as edited (supports as edited, gravity as set)."""
        return json.loads(self._inner.spec_json())

    def saved(self) -> dict[str, Any]:
        """The edited scene as a scene that re-solves to the current equilibrium (one motion
        stage per moved support)."""
        return json.loads(self._inner.saved_json())

    # --- edits ---------------------------------------------------------------------------

    def _checked(self, report: EditReport, check: bool, what: str) -> EditReport:
        if check and not report.converged:
            raise NotConvergedError(
                f"{what} did not converge ({report.reason}); the last equilibrium is kept",
                report=report,
            )
        return report

    def move_support(
        self,
        rod: int,
        support: int,
        position: Optional[Sequence[float]] = None,
        rotation: Optional[Sequence[float]] = None,
        *,
        translation: Optional[Sequence[float]] = None,
        check: bool = True,
    ) -> EditReport:
        """Moves support ``support`` of rod ``rod`` and re-solves warm.

        Either to the absolute ``position`` (m) with orientation ``rotation`` (rotation
        vector, rad, relative to the support's rest orientation; kept if None), or by
        ``translation`` (m) and ``rotation`` (turned further by it, about the support's
        vertex). A move too large for one Newton solve is split into load steps.
        """
        r, s = _index(rod, "rod"), _index(support, "support")
        report = _move(
            lambda p, rot: self._inner.move_support(r, s, p, rot),
            lambda t, rot: self._inner.move_support_by(r, s, t, rot),
            position,
            rotation,
            translation,
        )
        return self._checked(report, check, f"moving rods[{r}].supports[{s}]")

    def move_shell_clamp(
        self,
        shell: int,
        clamp: int,
        position: Optional[Sequence[float]] = None,
        rotation: Optional[Sequence[float]] = None,
        *,
        translation: Optional[Sequence[float]] = None,
        check: bool = True,
    ) -> EditReport:
        """Moves clamp ``clamp`` of shell strip ``shell`` (a flat cable's connector) and
        re-solves the strip warm, as :meth:`move_support` does for a rod's support.

        Either the centre of its edge to the absolute ``position`` (m) with orientation
        ``rotation`` (rotation vector, rad, relative to the clamp's rest orientation; kept if
        None), or by ``translation`` (m) and ``rotation`` (turned further by it, about the
        centre of its edge). A move too large for one Newton solve is split into load steps.
        """
        sh, c = _index(shell, "shell"), _index(clamp, "clamp")
        report = _move(
            lambda p, rot: self._inner.move_shell_clamp(sh, c, p, rot),
            lambda t, rot: self._inner.move_shell_clamp_by(sh, c, t, rot),
            position,
            rotation,
            translation,
        )
        return self._checked(report, check, f"moving shells[{sh}].clamps[{c}]")

    def add_support(self, rod: int, support: Mapping[str, Any], *, check: bool = True) -> EditReport:
        """Adds a support (``{"kind": "clip", "at": 0.3}``, like a scene's ``supports``
        entry; clip, pin, slider or twist_hold) where the rod is now, and re-solves."""
        r = _index(rod, "rod")
        report = self._inner.add_support(r, plain(dict(support)))
        return self._checked(report, check, f"adding a support to rods[{r}]")

    def remove_support(self, rod: int, support: int, *, check: bool = True) -> EditReport:
        """Removes a support and re-solves."""
        r, s = _index(rod, "rod"), _index(support, "support")
        return self._checked(self._inner.remove_support(r, s), check, f"removing rods[{r}].supports[{s}]")

    def set_gravity(self, gravity: Sequence[float], *, check: bool = True) -> EditReport:
        """Sets gravity (m/s²) and re-solves warm."""
        return self._checked(self._inner.set_gravity(_vec3(gravity, "gravity")), check, "changing gravity")

    def set_length(self, rod: int, length: float, *, check: bool = True) -> EditReport:
        """Sets rod ``rod``'s rest length (m) — cable paid out (longer) or pulled in
        (shorter) between supports that stay where they are — and re-solves from the current
        shape, in steps of at most 5 %. Only a straight rest centerline has its length edited.
        """
        r = _index(rod, "rod")
        return self._checked(
            self._inner.set_rod_length(r, float(length)), check, f"setting the length of rods[{r}]"
        )

    def length(self, rod: int) -> float:
        """The rest length (m) of rod ``rod``."""
        r = _index(rod, "rod")
        value = self._inner.rod_length(r)
        if value is None:
            e = SceneError(f"rods[{r}]: no such rod")
            e.field = f"rods[{r}]"
            raise e
        return value

    def move_obstacle(
        self,
        obstacle: int,
        translation: Sequence[float] = (0.0, 0.0, 0.0),
        rotation: Sequence[float] = (0.0, 0.0, 0.0),
        *,
        check: bool = True,
    ) -> EditReport:
        """Moves obstacle ``obstacle`` rigidly — turned by the rotation vector ``rotation``
        (rad) about its reference point (a plane's or cylinder's ``point``, a sphere's, box's
        or torus's ``center``, a mesh's bounding-box centre, as moved so far), then shifted by
        ``translation`` (m) — carrying the cables it sweeps, and re-solves every structure.
        The saved scene keeps the file's obstacle and moves it by a ``[[motion]]`` stage."""
        o = _index(obstacle, "obstacle")
        report = self._inner.move_obstacle(
            o, _vec3(translation, "translation"), _vec3(rotation, "rotation")
        )
        return self._checked(report, check, f"moving obstacles[{o}]")

    def obstacle_reference(self, obstacle: int) -> np.ndarray:
        """The point (m) obstacle ``obstacle`` turns about in :meth:`move_obstacle`."""
        o = _index(obstacle, "obstacle")
        value = self._inner.obstacle_reference(o)
        if value is None:
            e = SceneError(f"obstacles[{o}]: no such obstacle")
            e.field = f"obstacles[{o}]"
            raise e
        return np.array(value)

    def set_force(self, rod: int, force: int, value: Sequence[float], *, check: bool = True) -> EditReport:
        """Sets point force ``force`` of rod ``rod`` (the scene's ``forces[force]``) to
        ``value`` (N) and re-solves warm. A follower force's value is given as it acts at rest,
        as in the scene file; it turns with the rod."""
        r, f = _index(rod, "rod"), _index(force, "force")
        report = self._inner.set_force(r, f, _vec3(value, "value"))
        return self._checked(report, check, f"changing rods[{r}].forces[{f}]")

    def set_moment(self, rod: int, moment: int, value: Sequence[float], *, check: bool = True) -> EditReport:
        """Sets point moment ``moment`` of rod ``rod`` (the scene's ``moments[moment]``) to
        ``value`` (N m) and re-solves warm: the old moment is blended into the new one along the
        load path. A follower moment's value is given as it acts at rest, as in the scene file;
        it turns with the rod."""
        r, m = _index(rod, "rod"), _index(moment, "moment")
        report = self._inner.set_moment(r, m, _vec3(value, "value"))
        return self._checked(report, check, f"changing rods[{r}].moments[{m}]")

    def add_moment(self, rod: int, at: float, value: Sequence[float] = (0.0, 0.0, 0.0), *, check: bool = True) -> EditReport:
        """Adds a dead point moment to rod ``rod`` at the file's vertex nearest rest arc length
        ``at`` (m), set to ``value`` (N m) warm from the last equilibrium; it becomes the last
        of the rod's ``moments``."""
        r = _index(rod, "rod")
        report = self._inner.add_moment(r, float(at), _vec3(value, "value"))
        return self._checked(report, check, f"adding a moment to rods[{r}]")

    def remove_moment(self, rod: int, moment: int, *, check: bool = True) -> EditReport:
        """Removes point moment ``moment`` of rod ``rod`` (brought to zero warm first); the
        later moments move down by one."""
        r, m = _index(rod, "rod"), _index(moment, "moment")
        return self._checked(self._inner.remove_moment(r, m), check, f"removing rods[{r}].moments[{m}]")

    def add_force(self, rod: int, at: float, value: Sequence[float] = (0.0, 0.0, 0.0), *, check: bool = True) -> EditReport:
        """Adds a dead point force to rod ``rod`` at the file's vertex nearest rest arc length
        ``at`` (m), set to ``value`` (N) warm from the last equilibrium; it becomes the last of
        the rod's ``forces``."""
        r = _index(rod, "rod")
        report = self._inner.add_force(r, float(at), _vec3(value, "value"))
        return self._checked(report, check, f"adding a force to rods[{r}]")

    def remove_force(self, rod: int, force: int, *, check: bool = True) -> EditReport:
        """Removes point force ``force`` of rod ``rod`` (a dead force is brought to zero warm
        first); the later forces move down by one."""
        r, f = _index(rod, "rod"), _index(force, "force")
        return self._checked(self._inner.remove_force(r, f), check, f"removing rods[{r}].forces[{f}]")

    def set_shell_force(self, shell: int, force: int, value: Sequence[float], *, check: bool = True) -> EditReport:
        """Sets point force ``force`` of shell strip ``shell`` (the scene's
        ``shells[shell].forces[force]``, a dead force) to ``value`` (N) and re-solves the strip
        warm."""
        s, f = _index(shell, "shell"), _index(force, "force")
        report = self._inner.set_shell_force(s, f, _vec3(value, "value"))
        return self._checked(report, check, f"changing shells[{s}].forces[{f}]")

    def add_shell_force(self, shell: int, station: int, column: int, value: Sequence[float] = (0.0, 0.0, 0.0), *, check: bool = True) -> EditReport:
        """Adds a dead point force to shell strip ``shell`` at the vertex (``station``,
        ``column``) of its grid (station 0 … elements along the length, column 0 …
        width_elements across), set to ``value`` (N) warm from the last equilibrium; it becomes
        the last of the strip's ``forces``."""
        s, i, j = _index(shell, "shell"), _index(station, "station"), _index(column, "column")
        report = self._inner.add_shell_force(s, i, j, _vec3(value, "value"))
        return self._checked(report, check, f"adding a force to shells[{s}]")

    def remove_shell_force(self, shell: int, force: int, *, check: bool = True) -> EditReport:
        """Removes point force ``force`` of shell strip ``shell`` (brought to zero warm first);
        the later forces move down by one."""
        s, f = _index(shell, "shell"), _index(force, "force")
        return self._checked(self._inner.remove_shell_force(s, f), check, f"removing shells[{s}].forces[{f}]")

    def follow_stable(self) -> EditReport:
        """Follows every unstable equilibrium along its unstable mode to a stable one."""
        return self._inner.follow_stable()

    def set_unstable_policy(self, policy: str) -> None:
        """"follow" (default): unstable equilibria are followed to stable ones; "keep"."""
        self._inner.set_unstable_policy(policy)

    # --- the scene's prescribed motion ---------------------------------------------------

    @property
    def motion_steps(self) -> int:
        """Number of motion steps of the scene's ``motion`` stages."""
        return self._inner.motion_steps()

    def run_motion_step(self, step: int) -> Results:
        """Runs motion step ``step`` (1-based, in order) and returns its results (check
        ``converged``)."""
        out = Results.from_json(self._inner.run_motion_step(_index(step, "step")))
        self._step = out.step
        return out

    def run_motion(self) -> list[Results]:
        """Step 0 and every motion step, as ``slender solve`` runs them (stops after a step
        that did not converge)."""
        steps = [self.results()]
        for k in range(1, self.motion_steps + 1):
            r = self.run_motion_step(k)
            steps.append(r)
            if not r.converged:
                break
        return steps


def solve(scene: Union[str, "os.PathLike[str]", Mapping[str, Any]], *, check: bool = True) -> list[Results]:
    """Solves a scene as ``slender solve`` does: step 0 (the loaded scene) and every motion
    step. With ``check`` a step that does not converge raises :class:`NotConvergedError`
    (its ``results`` holds the steps so far, the failed one last)."""
    steps = Session(scene).run_motion()
    if check and not all(s.converged for s in steps):
        bad = next(s for s in steps if not s.converged)
        reasons = "; ".join(r.reason for r in bad.reports() if not r.converged)
        raise NotConvergedError(f"step {bad.step} did not converge: {reasons}", results=steps)
    return steps
