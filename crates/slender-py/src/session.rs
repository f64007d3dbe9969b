//! `slender._slender.Session`: a scene solved and edited warm, with the GIL released during
//! every solve.

use nalgebra::{Rotation3, Vector3};
use pyo3::prelude::*;
use slender_core::scene::spec::{SupportSpec, UnstablePolicy};
use slender_core::scene::{EditReport, Scene, SceneStep, Session, SupportPose};

use crate::errors::{from_scene_error, guarded, scene_error};
use crate::internal_loads::step_json;
use crate::scene_text::{self, Syntax};

/// The outcome of one edit of a session (see `slender_core::scene::EditReport`).
#[pyclass(module = "slender._slender", name = "EditReport", get_all, frozen)]
#[derive(Clone, Debug)]
pub struct PyEditReport {
    /// True if every re-solved structure converged (else the last equilibrium was kept).
    pub converged: bool,
    /// Why not, if not.
    pub reason: Option<String>,
    /// Structures re-solved.
    pub structures: Vec<usize>,
    /// Newton iterations over them.
    pub iterations: usize,
    /// Load steps over them.
    pub load_steps: usize,
    /// Largest relative residual of the re-solved structures.
    pub relative_residual: f64,
    /// True if every equilibrium of the scene is stable now.
    pub stable: bool,
    /// True if an unstable equilibrium was followed to a stable one during this edit.
    pub followed_unstable_mode: bool,
}

impl From<EditReport> for PyEditReport {
    fn from(r: EditReport) -> Self {
        Self {
            converged: r.converged,
            reason: r.reason,
            structures: r.structures.into_vec(),
            iterations: r.iterations,
            load_steps: r.load_steps,
            relative_residual: r.relative_residual,
            stable: r.stable,
            followed_unstable_mode: r.followed_unstable_mode,
        }
    }
}

#[pymethods]
impl PyEditReport {
    fn __repr__(&self) -> String {
        format!(
            "EditReport(converged={}, reason={:?}, iterations={}, load_steps={}, relative_residual={:e}, stable={}, followed_unstable_mode={})",
            if self.converged { "True" } else { "False" },
            self.reason,
            self.iterations,
            self.load_steps,
            self.relative_residual,
            if self.stable { "True" } else { "False" },
            if self.followed_unstable_mode { "True" } else { "False" },
        )
    }
}

/// A compiled scene with its current equilibria (see `slender_core::scene::Session`).
#[pyclass(module = "slender._slender", name = "Session")]
pub struct PySession {
    inner: Session,
}

// The GIL is released around every solve, which needs the session to cross threads.
const _: () = {
    const fn send_and_sync<T: Send + Sync>() {}
    send_and_sync::<Session>();
};

fn new_session(py: Python<'_>, scene: Scene) -> PyResult<PySession> {
    let result = py.detach(|| guarded(|| Session::new(scene)))?;
    result
        .map(|inner| PySession { inner })
        .map_err(|e| from_scene_error(py, &e))
}

fn edit(
    py: Python<'_>,
    r: Result<EditReport, slender_core::scene::SceneError>,
) -> PyResult<PyEditReport> {
    r.map(PyEditReport::from)
        .map_err(|e| from_scene_error(py, &e))
}

fn finite3(py: Python<'_>, field: &str, v: [f64; 3]) -> PyResult<Vector3<f64>> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vector3::from(v))
    } else {
        Err(scene_error(
            py,
            field,
            &format!("{v:?}: every component must be a finite number"),
        ))
    }
}

/// The pose of a move to `position` (m) turned by the rotation vector `rotation` (rad) from
/// rest, or keeping the orientation of `current` (the support's pose now) if None.
fn target_pose(
    py: Python<'_>,
    position: [f64; 3],
    rotation: Option<[f64; 3]>,
    current: Option<SupportPose>,
) -> PyResult<SupportPose> {
    let position = finite3(py, "position", position)?;
    let rotation = match rotation {
        Some(r) => Rotation3::new(finite3(py, "rotation", r)?),
        None => current.map_or_else(Rotation3::identity, |p| p.rotation),
    };
    Ok(SupportPose { position, rotation })
}

#[pymethods]
impl PySession {
    /// Compiles and solves a scene given as TOML text (`name` starts syntax messages).
    #[staticmethod]
    #[pyo3(signature = (text, name = "scene"))]
    fn from_toml(py: Python<'_>, text: &str, name: &str) -> PyResult<Self> {
        let scene = scene_text::parse(py, text, Syntax::Toml, name)?;
        new_session(py, scene)
    }

    /// Compiles and solves a scene given as JSON text.
    #[staticmethod]
    #[pyo3(signature = (text, name = "scene"))]
    fn from_json(py: Python<'_>, text: &str, name: &str) -> PyResult<Self> {
        let scene = scene_text::parse(py, text, Syntax::Json, name)?;
        new_session(py, scene)
    }

    /// Compiles and solves a scene given as plain Python data (dict, lists, numbers, str).
    #[staticmethod]
    fn from_dict(py: Python<'_>, scene: &Bound<'_, PyAny>) -> PyResult<Self> {
        let scene = scene_text::from_object(scene)?;
        new_session(py, scene)
    }

    /// Moves support `support` of rod `rod` to `position` (m), turned by the rotation vector
    /// `rotation` (rad) relative to its rest orientation (kept if None), and re-solves warm.
    #[pyo3(signature = (rod, support, position, rotation = None))]
    fn move_support(
        &mut self,
        py: Python<'_>,
        rod: usize,
        support: usize,
        position: [f64; 3],
        rotation: Option<[f64; 3]>,
    ) -> PyResult<PyEditReport> {
        let target = target_pose(py, position, rotation, self.inner.pose(rod, support))?;
        let inner = &mut self.inner;
        let r = py.detach(|| guarded(|| inner.move_support(rod, support, target)))?;
        edit(py, r)
    }

    /// Moves support `support` of rod `rod` by `translation` (m) and turns it by the rotation
    /// vector `rotation` (rad, about its vertex), and re-solves warm.
    #[pyo3(signature = (rod, support, translation, rotation = [0.0, 0.0, 0.0]))]
    fn move_support_by(
        &mut self,
        py: Python<'_>,
        rod: usize,
        support: usize,
        translation: [f64; 3],
        rotation: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let t = finite3(py, "translation", translation)?;
        let r = finite3(py, "rotation", rotation)?;
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.move_support_by(rod, support, r, t)))?;
        edit(py, out)
    }

    /// Moves clamp `clamp` of shell strip `shell` so that the centre of its edge is at
    /// `position` (m), turned by the rotation vector `rotation` (rad) relative to its rest
    /// orientation (kept if None), and re-solves the strip warm.
    #[pyo3(signature = (shell, clamp, position, rotation = None))]
    fn move_shell_clamp(
        &mut self,
        py: Python<'_>,
        shell: usize,
        clamp: usize,
        position: [f64; 3],
        rotation: Option<[f64; 3]>,
    ) -> PyResult<PyEditReport> {
        let target = target_pose(py, position, rotation, self.inner.shell_pose(shell, clamp))?;
        let inner = &mut self.inner;
        let r = py.detach(|| guarded(|| inner.move_shell_clamp(shell, clamp, target)))?;
        edit(py, r)
    }

    /// Moves clamp `clamp` of shell strip `shell` by `translation` (m) and turns it by the
    /// rotation vector `rotation` (rad, about the centre of its edge), and re-solves warm.
    #[pyo3(signature = (shell, clamp, translation, rotation = [0.0, 0.0, 0.0]))]
    fn move_shell_clamp_by(
        &mut self,
        py: Python<'_>,
        shell: usize,
        clamp: usize,
        translation: [f64; 3],
        rotation: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let t = finite3(py, "translation", translation)?;
        let r = finite3(py, "rotation", rotation)?;
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.move_shell_clamp_by(shell, clamp, r, t)))?;
        edit(py, out)
    }

    /// Adds a support (a dict like a scene's `supports` entry; not a clamp) to rod `rod`
    /// where the rod is now, and re-solves.
    fn add_support(
        &mut self,
        py: Python<'_>,
        rod: usize,
        support: &Bound<'_, PyAny>,
    ) -> PyResult<PyEditReport> {
        let path = format!("rods[{rod}].supports[+]");
        let value = scene_text::to_value(support, &path)?;
        let spec: SupportSpec = serde_path_to_error::deserialize(value).map_err(|e| {
            let sub = e.path().to_string();
            let field = if sub == "." {
                path.clone()
            } else {
                format!("{path}{sub}")
            };
            scene_error(py, &field, &e.inner().to_string())
        })?;
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.add_support(rod, spec)))?;
        edit(py, out)
    }

    /// Removes support `support` of rod `rod` and re-solves.
    fn remove_support(
        &mut self,
        py: Python<'_>,
        rod: usize,
        support: usize,
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.remove_support(rod, support)))?;
        edit(py, out)
    }

    /// Sets rod `rod`'s rest length (m): cable paid out or pulled in between supports that
    /// stay where they are; re-solved from the current shape in steps of at most 5 %.
    fn set_rod_length(
        &mut self,
        py: Python<'_>,
        rod: usize,
        length: f64,
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.set_rod_length(rod, length)))?;
        edit(py, out)
    }

    /// The rest length (m) of rod `rod`'s centerline, or None for an unknown rod.
    fn rod_length(&self, rod: usize) -> Option<f64> {
        self.inner.rod_length(rod)
    }

    /// Moves obstacle `obstacle` rigidly — turned by the rotation vector `rotation` (rad)
    /// about its reference point, then shifted by `translation` (m) — carrying the cables it
    /// sweeps, and re-solves every structure.
    fn move_obstacle(
        &mut self,
        py: Python<'_>,
        obstacle: usize,
        translation: [f64; 3],
        rotation: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| {
            guarded(|| inner.move_obstacle_by(obstacle, rotation.into(), translation.into()))
        })?;
        edit(py, out)
    }

    /// The point (m) obstacle `obstacle` turns about, as moved so far; None for an unknown
    /// obstacle.
    fn obstacle_reference(&self, obstacle: usize) -> Option<[f64; 3]> {
        self.inner.obstacle_reference(obstacle).map(Into::into)
    }

    /// Sets gravity (m/s²) and re-solves warm.
    fn set_gravity(&mut self, py: Python<'_>, gravity: [f64; 3]) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.set_gravity(gravity)))?;
        edit(py, out)
    }

    /// Sets point force `force` of rod `rod` (its scene's `forces[force]`) to `value` (N; a
    /// follower force's as it acts at rest) and re-solves warm.
    fn set_force(
        &mut self,
        py: Python<'_>,
        rod: usize,
        force: usize,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.set_force(rod, force, value)))?;
        edit(py, out)
    }

    /// Sets point moment `moment` of rod `rod` (its scene's `moments[moment]`) to `value` (N m;
    /// a follower moment's as it acts at rest) and re-solves warm, the old moment blended into
    /// the new one.
    fn set_moment(
        &mut self,
        py: Python<'_>,
        rod: usize,
        moment: usize,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.set_moment(rod, moment, value)))?;
        edit(py, out)
    }

    /// Adds a dead point moment to rod `rod` at the file's vertex nearest rest arc length `at`
    /// (m), set to `value` (N m); it becomes the last of the rod's `moments`.
    fn add_moment(
        &mut self,
        py: Python<'_>,
        rod: usize,
        at: f64,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.add_moment(rod, at, value)))?;
        edit(py, out)
    }

    /// Removes point moment `moment` of rod `rod` (brought to zero warm first).
    fn remove_moment(
        &mut self,
        py: Python<'_>,
        rod: usize,
        moment: usize,
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.remove_moment(rod, moment)))?;
        edit(py, out)
    }

    /// Adds a dead point force to rod `rod` at the file's vertex nearest rest arc length `at`
    /// (m), set to `value` (N); it becomes the last of the rod's `forces`.
    fn add_force(
        &mut self,
        py: Python<'_>,
        rod: usize,
        at: f64,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.add_force(rod, at, value)))?;
        edit(py, out)
    }

    /// Removes point force `force` of rod `rod` (a dead force is brought to zero warm first).
    fn remove_force(&mut self, py: Python<'_>, rod: usize, force: usize) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.remove_force(rod, force)))?;
        edit(py, out)
    }

    /// Sets point force `force` of shell strip `shell` (its scene's `forces[force]`, a dead
    /// force) to `value` (N) and re-solves the strip warm.
    fn set_shell_force(
        &mut self,
        py: Python<'_>,
        shell: usize,
        force: usize,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.set_shell_force(shell, force, value)))?;
        edit(py, out)
    }

    /// Adds a dead point force to shell strip `shell` at grid vertex (`station`, `column`),
    /// set to `value` (N) warm; it becomes the last of the strip's `forces`.
    fn add_shell_force(
        &mut self,
        py: Python<'_>,
        shell: usize,
        station: usize,
        column: usize,
        value: [f64; 3],
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.add_shell_force(shell, station, column, value)))?;
        edit(py, out)
    }

    /// Removes point force `force` of shell strip `shell` (brought to zero warm first).
    fn remove_shell_force(
        &mut self,
        py: Python<'_>,
        shell: usize,
        force: usize,
    ) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        let out = py.detach(|| guarded(|| inner.remove_shell_force(shell, force)))?;
        edit(py, out)
    }

    /// Follows every unstable equilibrium along its unstable mode to a stable one.
    fn follow_stable(&mut self, py: Python<'_>) -> PyResult<PyEditReport> {
        let inner = &mut self.inner;
        Ok(py.detach(|| guarded(|| inner.follow_stable()))?.into())
    }

    /// What to do with unstable equilibria from now on: "follow" or "keep".
    fn set_unstable_policy(&mut self, py: Python<'_>, policy: &str) -> PyResult<()> {
        let p = match policy {
            "follow" => UnstablePolicy::Follow,
            "keep" => UnstablePolicy::Keep,
            other => {
                return Err(scene_error(
                    py,
                    "unstable",
                    &format!("{other:?}: must be \"follow\" or \"keep\""),
                ))
            }
        };
        self.inner.set_unstable_policy(p);
        Ok(())
    }

    /// Number of motion steps over all stages of the scene's `motion`.
    fn motion_steps(&self) -> usize {
        self.inner.motion_steps()
    }

    /// Runs motion step `step` (1-based, in order) and returns its results as JSON text.
    fn run_motion_step(&mut self, py: Python<'_>, step: usize) -> PyResult<String> {
        let n = self.inner.motion_steps();
        if step == 0 || step > n {
            return Err(scene_error(
                py,
                "step",
                &format!("{step}: must be in 1..={n} (the scene's motion steps)"),
            ));
        }
        let inner = &mut self.inner;
        py.detach(|| {
            guarded(|| {
                let s = inner.run_motion_step(step);
                step_json(inner, &s)
            })
        })
    }

    /// The results of the current equilibria as JSON text (`step` labels them).
    #[pyo3(signature = (step = 0))]
    fn results(&self, py: Python<'_>, step: usize) -> PyResult<String> {
        let inner = &self.inner;
        py.detach(|| {
            guarded(|| {
                let s: SceneStep = inner.results(step, None, 1.0, 1);
                step_json(inner, &s)
            })
        })
    }

    /// Where support `support` of rod `rod` is: (position (m), rotation vector (rad)
    /// relative to rest), or None if there is no such support.
    fn pose(&self, rod: usize, support: usize) -> Option<([f64; 3], [f64; 3])> {
        self.inner.pose(rod, support).map(|p| {
            let r = p.rotation.scaled_axis();
            ([p.position.x, p.position.y, p.position.z], [r.x, r.y, r.z])
        })
    }

    /// Where clamp `clamp` of shell strip `shell` is: (the centre of its edge (m), rotation
    /// vector (rad) relative to rest), or None if there is no such clamp.
    fn shell_pose(&self, shell: usize, clamp: usize) -> Option<([f64; 3], [f64; 3])> {
        self.inner.shell_pose(shell, clamp).map(|p| {
            let r = p.rotation.scaled_axis();
            ([p.position.x, p.position.y, p.position.z], [r.x, r.y, r.z])
        })
    }

    /// The scene as edited, as JSON text (supports as edited, gravity as set).
    fn spec_json(&self) -> String {
        serde_json::to_string(self.inner.spec()).expect("a scene serializes")
    }

    /// The edited scene as a file that re-solves to the current equilibrium (JSON text).
    fn saved_json(&self) -> String {
        serde_json::to_string(&self.inner.saved()).expect("a scene serializes")
    }

    /// Number of structures (groups of rod parts solved together).
    fn n_structures(&self) -> usize {
        self.inner.compiled().structures.len()
    }
}
