//! Shell strips in a scene: validation of `[[shells]]` (errors name the place in the file),
//! building the strip, and its equilibrium under the scene's gravity.
//!
//! A strip does not interact with the rods or the other strips of the scene: each structure
//! is solved on its own. It does rest on the scene's obstacles (`shell_contact_run`).

use serde::Serialize;

use crate::assembly::TermSet;
use nalgebra::Rotation3;

use crate::bspline_shell::{BsplineShell, BsplineShellBuilder, BsplineState, PointLoad, StripEnd};
use crate::geometry::Vec3;
use crate::linalg::SparseSymmetricMatrix;
use crate::shell::{rod_predictor, Clamp, Shell, ShellBuilder, ShellProperties, ShellState};
use crate::solver::{EquilibriumSolver, SolveReport, SolverParams};

use super::error::SceneError;
use super::shell_contact_run::StripContacts;
use super::spec::{RodEnd, ShellClampSpec, ShellModelSpec, ShellSpec};

/// Default number of elements along a strip's length.
pub const DEFAULT_SHELL_ELEMENTS: usize = 15;

/// The support of the older files (`support = "clamp_start"`): the edge x = 0 clamped at rest.
pub const SHELL_CLAMP: &str = "clamp_start";

/// Largest offset of a strip's clamp from its rest pose, in strip lengths.
pub const MAX_OFFSET_LENGTHS: f64 = 2.0;
/// Largest rotation of a strip's clamp from its rest pose (rad).
pub const MAX_CLAMP_TURN: f64 = 2.0 * std::f64::consts::PI;

/// A clamp of a compiled strip: which end, and its pose as a rigid motion of the end's rest
/// points (the spec's offset and rotation about the edge's rest centre).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompiledShellClamp {
    /// The clamped end.
    pub end: StripEnd,
    /// Rest centre of the clamped edge (m): (0, 0, 0) or (L, 0, 0).
    pub centre: Vec3,
    /// The pose of the file (reached from rest by the initial solve).
    pub pose: Clamp,
}

/// A strip of the scene, ready to solve.
#[derive(Clone, Debug)]
pub struct CompiledShell {
    /// Output name.
    pub name: String,
    /// The shell model: its clamps at rest, the scene's gravity and the point forces at load
    /// factor 1.
    pub model: StripModel,
    /// The clamps, in the order of the spec's `clamps`.
    pub clamps: Vec<CompiledShellClamp>,
}

/// The model of a strip.
#[derive(Clone, Debug)]
pub enum StripModel {
    /// Triangles with mid-edge directors.
    Midedge(Shell),
    /// One C¹ B-spline patch.
    Bspline(BsplineShell),
}

impl CompiledShell {
    /// Width w of the strip (m).
    pub fn width(&self) -> f64 {
        match &self.model {
            StripModel::Midedge(s) => s.properties().width,
            StripModel::Bspline(s) => s.properties().width,
        }
    }

    /// Rest length L of the strip (m).
    pub fn length(&self) -> f64 {
        match &self.model {
            StripModel::Midedge(s) => s.properties().length,
            StripModel::Bspline(s) => s.properties().length,
        }
    }

    /// Elements across the width, n_W: the result grid has n_W + 1 columns.
    pub fn width_elements(&self) -> usize {
        match &self.model {
            StripModel::Midedge(s) => s.mesh().n_width,
            StripModel::Bspline(s) => s.elements().1,
        }
    }

    /// The flat strip's points at the stations and columns of the result grid: vertex (i, j)
    /// is i·(n_W + 1) + j (m).
    pub fn rest_positions(&self) -> Vec<Vec3> {
        match &self.model {
            StripModel::Midedge(s) => s.mesh().rest_positions.clone(),
            StripModel::Bspline(s) => s.tessellate(&s.rest_state(), 1).0,
        }
    }
}

/// Equilibrium of one strip.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShellResult {
    /// Strip name.
    pub name: String,
    /// Vertex positions (m); vertex (i, j) of station i and column j is i·(n_W + 1) + j.
    pub positions: Vec<[f64; 3]>,
    /// Triangles (vertex triples).
    pub faces: Vec<[usize; 3]>,
    /// Elements along the length and across the width.
    pub elements: [usize; 2],
    /// Total applied load (N): the weight of the whole strip, Σ mᵥ g, and the point forces.
    pub applied_force: [f64; 3],
    /// Force the clamps apply to the strip (N, both clamps together): Σ over the held
    /// vertices (control points) of ∂E/∂x (the generalized force the held DOFs need), by
    /// central differences of the strip's energy (elastic and loads; an obstacle's push on a
    /// clamped vertex is the clamp's business and not in it). The clamp moment is not
    /// reported.
    pub clamp_force: [f64; 3],
    /// In a scene with obstacles: the resultant force (N) the obstacles apply to the strip's
    /// free vertices (normal and friction; each contact is listed under its obstacle in the
    /// step's `obstacles`). Absent without obstacles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_force: Option<[f64; 3]>,
    /// In a scene with obstacles: the smallest gap (m) between the strip's mid-surface and an
    /// obstacle, less its half-thickness h/2, over its vertices (positive: no penetration;
    /// the contacts rest within the activation distance). Absent without obstacles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_gap: Option<f64>,
    /// |clamp_force + contact_force + applied_force| / |applied_force| (0 without load).
    pub relative_force_imbalance: f64,
    /// True if the start came from the equivalent rod's equilibrium (else load stepping from
    /// the flat strip).
    pub rod_predictor_used: bool,
    /// Solver report.
    pub report: SolveReport,
    /// True if the solve converged.
    pub converged: bool,
}

/// A finite vector of magnitude at most `limit`.
fn finite_vector(path: &str, v: [f64; 3], limit: f64) -> Result<Vec3, SceneError> {
    if v.iter().all(|c| c.is_finite()) && Vec3::from(v).norm() <= limit {
        Ok(Vec3::from(v))
    } else {
        Err(SceneError::new(
            path,
            format!("{v:?}: every component must be finite, magnitude at most {limit}"),
        ))
    }
}

/// A positive physical parameter within the bounds a rod's are held to
/// ([`MAGNITUDE_FLOOR`](super::magnitudes::MAGNITUDE_FLOOR) to
/// [`MAGNITUDE_LIMIT`](super::magnitudes::MAGNITUDE_LIMIT)): a strip 1e-300 m wide passed a
/// plain `> 0` and gave the solver an infinite Hessian entry.
fn positive(path: String, v: f64) -> Result<(), SceneError> {
    use super::magnitudes::{MAGNITUDE_FLOOR, MAGNITUDE_LIMIT};
    if v.is_finite() && (MAGNITUDE_FLOOR..=MAGNITUDE_LIMIT).contains(&v) {
        Ok(())
    } else {
        Err(SceneError::new(
            path,
            format!("{v}: must be finite and in [{MAGNITUDE_FLOOR:e}, {MAGNITUDE_LIMIT:e}]"),
        ))
    }
}

/// Validates `[[shells]]` entry `path` (e.g. `shells[0]`) and builds it.
pub fn compile_shell(
    path: &str,
    index: usize,
    spec: &ShellSpec,
    gravity: Vec3,
) -> Result<CompiledShell, SceneError> {
    let name = spec.name.clone().unwrap_or_else(|| format!("shell{index}"));
    super::compile::check_name(&format!("{path}.name"), &name)?;
    positive(format!("{path}.length"), spec.length)?;
    positive(format!("{path}.width"), spec.width)?;
    positive(format!("{path}.thickness"), spec.thickness)?;
    let m = &spec.material;
    positive(format!("{path}.material.young"), m.young)?;
    positive(format!("{path}.material.density"), m.density)?;
    let poisson = match (m.poisson, m.shear_modulus) {
        (Some(nu), None) => nu,
        (None, Some(g)) => {
            positive(format!("{path}.material.shear_modulus"), g)?;
            m.young / (2.0 * g) - 1.0
        }
        _ => {
            return Err(SceneError::new(
                format!("{path}.material"),
                "give exactly one of `poisson` or `shear_modulus`",
            ))
        }
    };
    if !(poisson > -1.0 && poisson < 0.5) {
        let key = if m.poisson.is_some() {
            "poisson"
        } else {
            "shear_modulus"
        };
        return Err(SceneError::new(
            format!("{path}.material.{key}"),
            format!("Poisson ratio {poisson}: the shell model needs it in (-1, 0.5)"),
        ));
    }
    if let Some(s) = &spec.support {
        if s != SHELL_CLAMP {
            return Err(SceneError::new(
                format!("{path}.support"),
                format!(
                    "{s:?}: not supported; valid: \"{SHELL_CLAMP}\" (the edge x = 0 clamped), or give `clamps` (edge = \"start\", x = 0, and/or \"end\", x = L, each at any pose)"
                ),
            ));
        }
        if spec.clamps.is_some() {
            return Err(SceneError::new(
                format!("{path}.support"),
                "give either `support` (older files) or `clamps`, not both",
            ));
        }
    }
    let clamp_specs = match &spec.clamps {
        Some(c) => c.clone(),
        None => vec![ShellClampSpec {
            edge: RodEnd::Start,
            offset: [0.0; 3],
            rotate: [0.0; 3],
        }],
    };
    if clamp_specs.is_empty() {
        return Err(SceneError::new(
            format!("{path}.clamps"),
            "empty: a strip needs at least one clamp (edge = \"start\" and/or \"end\")",
        ));
    }
    let mut clamps = Vec::with_capacity(clamp_specs.len());
    for (k, c) in clamp_specs.iter().enumerate() {
        let place = format!("{path}.clamps[{k}]");
        let end = match c.edge {
            RodEnd::Start => StripEnd::Start,
            RodEnd::End => StripEnd::End,
        };
        if clamps.iter().any(|o: &CompiledShellClamp| o.end == end) {
            return Err(SceneError::new(
                format!("{place}.edge"),
                format!(
                    "{:?}: that edge is already clamped; at most one clamp per end",
                    c.edge
                ),
            ));
        }
        // A strip reaches no further than its length, and the initial solve moves the clamp
        // there in load steps (see `shell_run::move_steps`): bound both.
        let offset = finite_vector(
            &format!("{place}.offset"),
            c.offset,
            MAX_OFFSET_LENGTHS * spec.length,
        )?;
        let rotate = finite_vector(&format!("{place}.rotate"), c.rotate, MAX_CLAMP_TURN)?;
        let centre = match end {
            StripEnd::Start => Vec3::zeros(),
            StripEnd::End => Vec3::new(spec.length, 0.0, 0.0),
        };
        let rotation = Rotation3::new(rotate);
        clamps.push(CompiledShellClamp {
            end,
            centre,
            pose: Clamp {
                rotation,
                translation: centre + offset - rotation * centre,
            },
        });
    }
    let n_length = spec.elements.unwrap_or(DEFAULT_SHELL_ELEMENTS);
    if n_length < 1 {
        return Err(SceneError::new(
            format!("{path}.elements"),
            format!("{n_length}: need at least 1 element along the length"),
        ));
    }
    let n_width = spec
        .width_elements
        .unwrap_or_else(|| ((spec.width / spec.length * n_length as f64).round() as usize).max(2));
    if n_width < 1 {
        return Err(SceneError::new(
            format!("{path}.width_elements"),
            format!("{n_width}: need at least 1 element across the width"),
        ));
    }
    // The sparse Hessian grows with n_L·n_W; keep a typo from asking for a huge mesh.
    const MAX_FACES: usize = 200_000;
    if n_length.saturating_mul(n_width).saturating_mul(2) > MAX_FACES {
        return Err(SceneError::new(
            format!("{path}.elements"),
            format!(
                "{n_length} x {n_width} elements: more than {MAX_FACES} triangles; valid: 2·elements·width_elements <= {MAX_FACES}"
            ),
        ));
    }
    let properties = ShellProperties {
        length: spec.length,
        width: spec.width,
        thickness: spec.thickness,
        young: m.young,
        poisson,
        density: m.density,
    };
    let place = |e| {
        let place = if spec.grading.is_some() {
            format!("{path}.grading")
        } else {
            path.to_string()
        };
        SceneError::model(place, e)
    };
    if spec.clamps.is_some() && clamps.len() == 2 && n_length < 2 {
        return Err(SceneError::new(
            format!("{path}.elements"),
            format!("{n_length}: with both edges clamped a strip needs at least 2 elements along its length"),
        ));
    }
    for (k, f) in spec.forces.iter().enumerate() {
        let place = format!("{path}.forces[{k}]");
        if f.station > n_length {
            return Err(SceneError::new(
                format!("{place}.station"),
                format!(
                    "{}: off the strip; valid: 0..={n_length} (elements)",
                    f.station
                ),
            ));
        }
        if f.column > n_width {
            return Err(SceneError::new(
                format!("{place}.column"),
                format!(
                    "{}: off the strip; valid: 0..={n_width} (width_elements)",
                    f.column
                ),
            ));
        }
        finite_vector(
            &format!("{place}.force"),
            f.force,
            super::magnitudes::MAGNITUDE_LIMIT,
        )?;
    }
    let clamped = |end: StripEnd| clamps.iter().any(|c| c.end == end);
    let grading = spec.grading.unwrap_or_default();
    let model = match spec.model.unwrap_or_default() {
        ShellModelSpec::Midedge => {
            let mut b = ShellBuilder::new(properties)
                .elements(n_length, n_width)
                .grading(grading)
                .gravity(gravity);
            for end in StripEnd::BOTH {
                b = if clamped(end) {
                    b.clamp(end)
                } else {
                    b.free(end)
                };
            }
            for f in &spec.forces {
                b = b.point_force(f.station, f.column, Vec3::from(f.force));
            }
            StripModel::Midedge(b.build().map_err(place)?)
        }
        ShellModelSpec::Bspline => {
            let mut b = BsplineShellBuilder::new(properties)
                .elements(n_length, n_width)
                .grading(grading)
                .gravity(gravity);
            for end in StripEnd::BOTH {
                b = if clamped(end) {
                    b.clamp(end, Clamp::default())
                } else {
                    b.free(end)
                };
            }
            if !spec.forces.is_empty() {
                let stations = grading
                    .node_arclengths(n_length, spec.length)
                    .map_err(place)?;
                for f in &spec.forces {
                    b = b.point_load(PointLoad {
                        u: stations[f.station],
                        v: -0.5 * spec.width + spec.width * f.column as f64 / n_width as f64,
                        force: f.force,
                    });
                }
            }
            StripModel::Bspline(b.build().map_err(place)?)
        }
    };
    Ok(CompiledShell {
        name,
        model,
        clamps,
    })
}

fn arr(v: Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Solves a strip: its loads at its clamps' rest poses, then the clamps moved to the poses
/// of the file (see [`ShellRun::new`](super::shell_run::ShellRun::new)). The strip alone: a
/// scene's obstacles are not seen here (a [`Session`](super::Session) solves a scene's strips
/// on its obstacles).
pub fn solve_shell(c: &CompiledShell, params: &SolverParams) -> ShellResult {
    let mut c = c.clone();
    let run = super::shell_run::ShellRun::new(&mut c, params);
    run.result(&c)
}

/// The loaded strip at its clamps' rest poses: Newton from the equivalent rod's equilibrium
/// mapped onto the strip (as the shell cantilever does) when only the start is clamped; if
/// that is not possible, the rod does not converge or Newton fails from there, load stepping
/// from the flat strip. Returns the solution and whether the rod predictor gave it.
pub(crate) fn solve_midedge_loaded(
    shell: &Shell,
    solver: &mut EquilibriumSolver<ShellState, SparseSymmetricMatrix>,
    params: &SolverParams,
) -> (crate::solver::Solution<ShellState>, bool) {
    let flat = shell.rest_state();
    let cantilever = !shell.is_clamped(StripEnd::End);
    if cantilever && shell.point_forces().is_empty() {
        if let Ok(Some(guess)) = rod_predictor(shell, 1.0, params) {
            let s = solver.solve(shell, &guess, 1.0, 1.0);
            if s.report.converged() {
                return (s, true);
            }
        }
    }
    (solver.solve(shell, &flat, 0.0, 1.0), false)
}

/// The result of a mid-edge strip at `state`.
pub(crate) fn midedge_result(
    name: &str,
    shell: &Shell,
    state: &ShellState,
    report: &SolveReport,
    rod_predictor_used: bool,
    contacts: Option<&StripContacts>,
) -> ShellResult {
    let weight: f64 = shell.vertex_masses().iter().sum();
    let applied =
        shell.gravity() * weight + shell.point_forces().iter().map(|(_, f)| *f).sum::<Vec3>();
    let clamp = clamp_force(shell, state);
    let contact: Option<Vec3> = contacts.map(|c| {
        c.contacts
            .iter()
            .map(|(f, _, _)| f.force + f.friction)
            .sum()
    });
    let imbalance = (clamp + contact.unwrap_or_default() + applied).norm();
    let mesh = shell.mesh();
    ShellResult {
        name: name.to_string(),
        positions: state.positions.iter().map(|p| arr(*p)).collect(),
        faces: mesh.faces.clone(),
        elements: [mesh.n_length, mesh.n_width],
        applied_force: arr(applied),
        clamp_force: arr(clamp),
        contact_force: contact.map(arr),
        min_gap: contacts.map(|c| c.min_gap),
        relative_force_imbalance: if applied.norm() > 0.0 {
            imbalance / applied.norm()
        } else {
            imbalance
        },
        rod_predictor_used,
        converged: report.converged(),
        report: report.clone(),
    }
}

/// The result of a B-spline strip at `state`.
pub(crate) fn bspline_result(
    name: &str,
    shell: &BsplineShell,
    state: &BsplineState,
    report: &SolveReport,
) -> ShellResult {
    let weight: f64 = shell.masses().iter().sum();
    let applied = shell.gravity() * weight + shell.point_load_total();
    let clamp = bspline_clamp_force(shell, state);
    let imbalance = (clamp + applied).norm();
    let (positions, faces) = shell.tessellate(state, 1);
    let (n_length, n_width) = shell.elements();
    ShellResult {
        name: name.to_string(),
        positions: positions.iter().map(|p| arr(*p)).collect(),
        faces,
        elements: [n_length, n_width],
        applied_force: arr(applied),
        clamp_force: arr(clamp),
        contact_force: None,
        min_gap: None,
        relative_force_imbalance: if applied.norm() > 0.0 {
            imbalance / applied.norm()
        } else {
            imbalance
        },
        rod_predictor_used: false,
        converged: report.converged(),
        report: report.clone(),
    }
}

/// As [`clamp_force`] over the held control points (those without a free DOF: the clamp's
/// two rows): by partition of unity their generalized forces sum to the clamp force.
fn bspline_clamp_force(shell: &BsplineShell, state: &BsplineState) -> Vec3 {
    let mut s = state.clone();
    // The exact energy, not the Newton step's mixed-integration-point merit.
    s.membrane_remainder.clear();
    let held: Vec<usize> = (0..s.control_points.len())
        .filter(|&k| shell.dof(k, 0).is_none())
        .collect();
    held_force(
        &mut s,
        &held,
        1e-8 * shell.properties().length,
        |s, k| &mut s.control_points[k],
        |s| shell.energy_terms(s, 1.0, TermSet::ALL),
    )
}

/// Σ over the clamped vertices of ∂E/∂x (N): the force the clamp must apply. The shell's
/// assembly gives the gradient on free DOFs only, so the held ones are differentiated here by
/// central differences of the total energy, Richardson-extrapolated over steps h and 2h
/// (h = 1e-8·L): the stiff membrane of the small graded elements next to the clamp makes the
/// O(h²) error of a plain central difference large (measured 1e-3 of the weight at 1e-7·L).
fn clamp_force(shell: &Shell, state: &ShellState) -> Vec3 {
    let mut s = state.clone();
    held_force(
        &mut s,
        &shell.mesh().clamp_vertices,
        1e-8 * shell.properties().length,
        |s, v| &mut s.positions[v],
        |s| shell.energy_terms(s, 1.0, TermSet::ALL),
    )
}

/// Σ over the `held` points of ∂E/∂x (N) by central differences of `energy` with steps h and
/// 2h, Richardson-extrapolated; `point` gives a held point of the state to perturb.
fn held_force<S>(
    s: &mut S,
    held: &[usize],
    h: f64,
    point: impl Fn(&mut S, usize) -> &mut Vec3,
    energy: impl Fn(&S) -> f64,
) -> Vec3 {
    let mut f = Vec3::zeros();
    for &k in held {
        for c in 0..3 {
            let x = point(s, k)[c];
            let mut central = |step: f64| {
                point(s, k)[c] = x + step;
                let up = energy(s);
                point(s, k)[c] = x - step;
                let down = energy(s);
                point(s, k)[c] = x;
                (up - down) / (2.0 * step)
            };
            let (d1, d2) = (central(h), central(2.0 * h));
            f[c] += (4.0 * d1 - d2) / 3.0;
        }
    }
    f
}

/// Δy/Δx (y downward) between the centres of the clamp and the free end of a solved strip:
/// the seed's cantilever measure, for tests and reports.
pub fn centre_line_ratio(r: &ShellResult) -> f64 {
    let [nl, nw] = r.elements;
    let centre = |i: usize| {
        let (lo, hi) = (nw / 2, nw.div_ceil(2));
        let a = Vec3::from(r.positions[i * (nw + 1) + lo]);
        let b = Vec3::from(r.positions[i * (nw + 1) + hi]);
        (a + b) * 0.5
    };
    let (a, b) = (centre(0), centre(nl));
    (a.y - b.y) / (b.x - a.x)
}
