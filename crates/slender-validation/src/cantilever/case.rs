//! One cantilever run: a horizontal rod clamped at x = 0, gravity −y scaled to reach Γ,
//! solved from the straight state, measured by Δy/Δx between its end points (seed §3).

use std::time::Instant;

use serde::{Deserialize, Serialize};
use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, Rod};
use slender_core::solver::{EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::materials::RodMaterialSet;
use crate::rod_model::{BenchmarkRod, RodModel, RodSpec};

/// Mesh families of the benchmark.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MeshKind {
    /// Equal elements.
    Uniform,
    /// s_j = L (j/N)²: graded toward the clamp, independent of Γ.
    Quadratic,
    /// The Γ-aware boundary-layer grading ([`Grading::BoundaryLayer`]): slender's default.
    Graded,
}

impl MeshKind {
    /// All mesh kinds.
    pub const ALL: [MeshKind; 3] = [MeshKind::Uniform, MeshKind::Quadratic, MeshKind::Graded];

    /// Name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Quadratic => "quadratic",
            Self::Graded => "graded",
        }
    }

    /// Parses [`Self::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == s)
    }

    /// The node grading for a cantilever at gravito-bending parameter `gamma`.
    pub fn grading(self, gamma: f64) -> Grading {
        match self {
            Self::Uniform => Grading::Uniform,
            Self::Quadratic => Grading::Power { exponent: 2.0 },
            Self::Graded => Grading::BoundaryLayer { gamma },
        }
    }
}

/// Parameters of one cantilever run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CantileverCase {
    /// Material and geometry set.
    pub material: RodMaterialSet,
    /// Mesh family.
    pub mesh: MeshKind,
    /// Number of elements.
    pub n_elements: usize,
    /// Gravito-bending parameter Γ = ρAgL³/EI (> 0).
    pub gamma: f64,
}

/// What a cantilever run measured.
#[derive(Clone, Debug)]
pub struct CantileverRun {
    /// The case.
    pub case: CantileverCase,
    /// Δy/Δx between the end points of the computed equilibrium (NaN if not converged).
    pub ratio: f64,
    /// Solver report: status, iterations, residual, inertia, λ_min.
    pub report: SolveReport,
    /// Wall time of the solve (s), build excluded.
    pub seconds: f64,
    /// Vertex positions of the returned state (m).
    pub positions: Vec<Vec3>,
}

impl CantileverCase {
    /// The rod of this case, for any model.
    pub fn spec(&self) -> Result<RodSpec, ModelError> {
        if !(self.gamma.is_finite() && self.gamma > 0.0) {
            return Err(ModelError::parameter("gamma", self.gamma, "finite and > 0"));
        }
        let g = self.material.gravity_for_gamma(self.gamma);
        Ok(RodSpec {
            curve: RestCurve::Straight {
                start: [0.0; 3],
                direction: [1.0, 0.0, 0.0],
                length: self.material.length,
            },
            properties: self.material.properties,
            shear: self.material.shear(),
            elements: self.n_elements,
            grading: self.mesh.grading(self.gamma),
            first_director: Vec3::z(),
            gravity: Vec3::new(0.0, -g, 0.0),
            preload_gravity: Vec3::zeros(),
            planar_axis: None,
            darboux: Default::default(),
        })
    }

    /// Builds the clamped discrete elastic rod of this case.
    pub fn build(&self) -> Result<Rod, ModelError> {
        self.spec()?.build_der()
    }

    /// Solves the discrete elastic rod from the straight state in one call (the solver picks
    /// its own load steps).
    pub fn run(&self, params: &SolverParams) -> Result<CantileverRun, ModelError> {
        self.run_with(RodModel::Der, params)
    }

    /// Solves the rod of `model` from the straight state in one call.
    pub fn run_with(
        &self,
        model: RodModel,
        params: &SolverParams,
    ) -> Result<CantileverRun, ModelError> {
        params.validate()?;
        crate::with_rod_model!(model, P => self.run_model::<P>(model, params))
    }

    fn run_model<P: BenchmarkRod>(
        &self,
        model: RodModel,
        params: &SolverParams,
    ) -> Result<CantileverRun, ModelError> {
        let rod = P::from_spec(&self.spec()?.for_model(model))?;
        let start = rod.rest().clone();
        let clock = Instant::now();
        let mut solver = EquilibriumSolver::new(&rod, &start, *params);
        let solution = solver.solve(&rod, &start, 0.0, 1.0);
        let seconds = clock.elapsed().as_secs_f64();
        let positions = P::positions(&solution.state).to_vec();
        let ratio = if solution.report.converged() {
            end_point_ratio(&positions)
        } else {
            f64::NAN
        };
        Ok(CantileverRun {
            case: *self,
            ratio,
            report: solution.report,
            seconds,
            positions,
        })
    }
}

/// Δy/Δx between the first and last points, with y measured downward (positive sag).
pub fn end_point_ratio(positions: &[Vec3]) -> f64 {
    let (a, b) = (positions[0], positions[positions.len() - 1]);
    (a.y - b.y) / (b.x - a.x)
}
