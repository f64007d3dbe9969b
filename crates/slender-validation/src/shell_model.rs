//! The two shell discretizations the benchmarks compare, behind one interface: the mid-edge
//! shell on triangles (`slender_core::shell`, design.md §3.2) and the C¹ B-spline shell
//! (`slender_core::bspline_shell`, design.md §3.4). A benchmark case names its model
//! ([`ShellModel`]), builds a [`Strip`] and runs its solves through [`StripModel`], so that
//! the cantilever, the lateral-buckling protocol and the sensitivity study are written once.

use std::fmt;
use std::str::FromStr;

use nalgebra::Rotation3;
use serde::{Deserialize, Serialize};
use slender_core::bspline_shell::{
    BsplineLoadPath, BsplineShell, BsplineShellBuilder, ClampMotion, StripEnd,
};
use slender_core::geometry::Vec3;
use slender_core::linalg::SparseSymmetricMatrix;
use slender_core::rod::Grading;
use slender_core::shell::{Clamp, LoadPath, Shell, ShellBuilder, ShellProperties};
use slender_core::solver::EquilibriumProblem;
use slender_core::ModelError;

/// Which shell discretization a benchmark runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShellModel {
    /// libshell-type discrete Kirchhoff–Love shell on triangles, mid-edge director bending,
    /// exact director clamp.
    Midedge,
    /// C¹ Kirchhoff–Love shell on one cubic B-spline patch, exact clamp.
    Bspline,
}

impl ShellModel {
    /// Both models, mid-edge first.
    pub const ALL: [ShellModel; 2] = [ShellModel::Midedge, ShellModel::Bspline];

    /// Identifier used on the command line, in files and plots.
    pub fn name(self) -> &'static str {
        match self {
            ShellModel::Midedge => "midedge",
            ShellModel::Bspline => "bspline",
        }
    }

    /// Human-readable label.
    pub fn label(self) -> &'static str {
        match self {
            ShellModel::Midedge => "mid-edge shell (triangles)",
            ShellModel::Bspline => "C¹ B-spline shell (cubic)",
        }
    }

    /// Elements across the width of a strip with `n_length` elements along and aspect ratio
    /// `width_ratio` for square elements: round(n_L·w/L), at least 1 for the B-spline (a
    /// cubic element spans the width smoothly) and at least `min_midedge` for the mid-edge
    /// shell (2 puts a mesh line on the centre line).
    pub fn square_width_elements(
        self,
        width_ratio: f64,
        n_length: usize,
        min_midedge: usize,
    ) -> usize {
        let n = (width_ratio * n_length as f64).round() as usize;
        match self {
            ShellModel::Midedge => n.max(min_midedge),
            ShellModel::Bspline => n.max(1),
        }
    }
}

impl fmt::Display for ShellModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ShellModel {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        ShellModel::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown shell model `{s}`; valid: midedge, bspline"))
    }
}

/// A strip to build: material, mesh, gravity at load factor 1, clamped at x = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StripSpec {
    /// The discretization.
    pub model: ShellModel,
    /// Material and geometry.
    pub properties: ShellProperties,
    /// Elements along the length.
    pub n_length: usize,
    /// Elements across the width.
    pub n_width: usize,
    /// Element boundaries along the length.
    pub grading: Grading,
    /// Gravity (m/s²).
    pub gravity: Vec3,
}

impl StripSpec {
    /// Builds the strip (the builders validate every field).
    pub fn build(&self) -> Result<Strip, ModelError> {
        Ok(match self.model {
            ShellModel::Midedge => Strip::Midedge(
                ShellBuilder::new(self.properties)
                    .elements(self.n_length, self.n_width)
                    .grading(self.grading)
                    .gravity(self.gravity)
                    .build()?,
            ),
            ShellModel::Bspline => Strip::Bspline(
                BsplineShellBuilder::new(self.properties)
                    .elements(self.n_length, self.n_width)
                    .grading(self.grading)
                    .gravity(self.gravity)
                    .build()?,
            ),
        })
    }
}

/// A built strip of either model.
#[derive(Clone, Debug)]
pub enum Strip {
    /// Mid-edge shell.
    Midedge(Shell),
    /// B-spline shell.
    Bspline(BsplineShell),
}

/// Runs `$body` with `$s` bound to the strip's model (a `&Shell` or a `&BsplineShell`).
#[macro_export]
macro_rules! with_strip {
    ($strip:expr, $s:ident => $body:expr) => {
        match $strip {
            $crate::shell_model::Strip::Midedge($s) => $body,
            $crate::shell_model::Strip::Bspline($s) => $body,
        }
    };
}

/// What the benchmarks need of a strip clamped at x = 0, whatever its discretization.
pub trait StripModel: EquilibriumProblem<Hessian = SparseSymmetricMatrix> + Sized {
    /// The flat, unloaded strip.
    fn rest(&self) -> Self::State;

    /// Turns `state` rigidly by σ (rad) about the x axis, its clamp with it (the unloaded
    /// strip following its clamp).
    fn turn_rigidly(&self, sigma: f64, state: &mut Self::State);

    /// The load factor ramps gravity; the clamp stays where the state has it.
    fn ramp_gravity(&mut self);

    /// The load factor turns the clamp about x from σ = `from` to `to` (rad) at full gravity
    /// (the solver's first guess turns the strip rigidly with it).
    fn rotate_clamp(&mut self, from: f64, to: f64);

    /// Centre of the cross-section (the material line z = 0) at the clamp (`free_end`
    /// false) or at the free end (m).
    fn centre(&self, state: &Self::State, free_end: bool) -> Vec3;

    /// Whether free DOF `i` is a displacement (m) rather than an angle.
    fn is_displacement(&self, i: usize) -> bool;

    /// The deformed surface as triangles, for pictures: (positions, faces).
    fn surface(&self, state: &Self::State) -> (Vec<Vec3>, Vec<[usize; 3]>);

    /// Length L (m).
    fn length(&self) -> f64;
}

impl StripModel for Shell {
    fn rest(&self) -> Self::State {
        self.rest_state()
    }

    fn turn_rigidly(&self, sigma: f64, state: &mut Self::State) {
        let rotation = Rotation3::from_axis_angle(&Vec3::x_axis(), sigma);
        for p in state.positions.iter_mut() {
            *p = rotation * *p;
        }
        state.membrane_remainder.clear();
        let turned = state.clamps[0].moved(&rotation, &Vec3::zeros());
        self.set_clamp(turned, state);
    }

    fn ramp_gravity(&mut self) {
        self.set_load_path(LoadPath::Gravity);
    }

    fn rotate_clamp(&mut self, from: f64, to: f64) {
        self.set_load_path(LoadPath::ClampRotation { from, to });
    }

    fn centre(&self, state: &Self::State, free_end: bool) -> Vec3 {
        let mesh = self.mesh();
        let i = if free_end { mesh.n_length } else { 0 };
        let nw = mesh.n_width;
        let (lo, hi) = (nw / 2, nw.div_ceil(2));
        (state.positions[mesh.vertex(i, lo)] + state.positions[mesh.vertex(i, hi)]) * 0.5
    }

    fn is_displacement(&self, i: usize) -> bool {
        !self.dofs().is_angle(i)
    }

    fn surface(&self, state: &Self::State) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        (state.positions.clone(), self.mesh().faces.clone())
    }

    fn length(&self) -> f64 {
        self.properties().length
    }
}

/// Sub-division of each B-spline element per direction in pictures.
const PICTURE_SUBDIVISION: usize = 4;

impl StripModel for BsplineShell {
    fn rest(&self) -> Self::State {
        self.rest_state()
    }

    fn turn_rigidly(&self, sigma: f64, state: &mut Self::State) {
        let rotation = Rotation3::from_axis_angle(&Vec3::x_axis(), sigma);
        for p in state.control_points.iter_mut() {
            *p = rotation * *p;
        }
        state.membrane_remainder.clear();
        let turned: Clamp = state.clamps[0].moved(&rotation, &Vec3::zeros());
        self.set_clamp(StripEnd::Start, turned, state)
            .expect("benchmark strips are clamped at the start");
    }

    fn ramp_gravity(&mut self) {
        self.set_load_path(BsplineLoadPath::default())
            .expect("the default load path is valid");
    }

    fn rotate_clamp(&mut self, from: f64, to: f64) {
        self.set_load_path(BsplineLoadPath::clamp_motion(vec![ClampMotion::about_x(
            StripEnd::Start,
            to - from,
        )]))
        .expect("benchmark strips are clamped at the start");
    }

    fn centre(&self, state: &Self::State, free_end: bool) -> Vec3 {
        let u = if free_end {
            self.properties().length
        } else {
            0.0
        };
        self.point(state, u, 0.0)
    }

    fn is_displacement(&self, _i: usize) -> bool {
        true
    }

    fn surface(&self, state: &Self::State) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        self.tessellate(state, PICTURE_SUBDIVISION)
    }

    fn length(&self) -> f64 {
        self.properties().length
    }
}
