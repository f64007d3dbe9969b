//! The lumped (diagonal) mass of a model's free DOFs, taken from its [`MassMetric`](crate::solver::MassMetric).
//!
//! The models already attach an inertia to every DOF for their eigenvalue problems; dynamics
//! reuses it, so that the natural frequencies of the linearized equations of motion are the
//! eigenvalues the stability analysis reports (H v = ω² M v). For the discrete elastic rod it
//! is the consistent lumping: vertex mass ρA × (half of each adjacent rest edge), the same
//! masses gravity acts on (so free fall is exact), and twist inertia ρ(I₁ + I₂) × (rest edge
//! length) for the edge angle — ρJ l with J the polar moment of area. Rotary inertia of the
//! sections about their bending axes is left out, as in Euler–Bernoulli theory.

use crate::error::ModelError;
use crate::solver::EquilibriumProblem;

/// Diagonal mass matrix over the free DOFs: kg for coordinates, kg m² for angles.
#[derive(Clone, Debug, PartialEq)]
pub struct LumpedMass {
    diagonal: Vec<f64>,
}

impl LumpedMass {
    /// The mass of `model`'s free DOFs, from its [`MassMetric`](crate::solver::MassMetric).
    /// Errors if an entry is not finite and > 0 (a DOF without inertia cannot be stepped by
    /// these schemes).
    pub fn of<P: EquilibriumProblem>(model: &P) -> Result<Self, ModelError> {
        let diagonal: Vec<f64> = (0..model.n_free())
            .map(|i| model.inertia_metric(i))
            .collect();
        if let Some((i, &m)) = diagonal
            .iter()
            .enumerate()
            .find(|(_, m)| !(m.is_finite() && **m > 0.0))
        {
            return Err(ModelError::parameter(
                format!("inertia_metric[{i}]"),
                m,
                "finite and > 0 (kg or kg m²)",
            ));
        }
        Ok(Self { diagonal })
    }

    /// The diagonal entries (kg or kg m²), one per free DOF.
    pub fn diagonal(&self) -> &[f64] {
        &self.diagonal
    }

    /// Kinetic energy ½ vᵀ M v (J) of the free-DOF velocity `v` (m/s or rad/s).
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        0.5 * self
            .diagonal
            .iter()
            .zip(v)
            .map(|(m, v)| m * v * v)
            .sum::<f64>()
    }
}
