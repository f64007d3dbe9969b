//! The rotary inertia of material frames whose orientations are model DOFs (the discrete
//! Cosserat rod's edge frames, the SE(3) beam's node frames).
//!
//! A frame stands for a slice of rod of length ℓ: its kinetic energy is ½ ωᵀ I ω with ω the
//! spatial angular velocity and I = R diag(J₁, J₂, J₃) Rᵀ its inertia in space, R = [d₁ d₂ d₃]
//! the frame and J_k = ρ I_k ℓ the slice's principal moments about the directors (I_k the
//! second moments of area). The inertia turns with the frame, so a frame's mass matrix is a
//! 3×3 block that depends on the state, not a diagonal: the time step handles it
//! (`incremental.rs`), the lumped mass only lists it.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::assembly::FIXED;
use crate::error::ModelError;

/// One frame's rotation DOFs and principal moments of inertia.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameInertia {
    /// Free DOFs of the frame's spatial rotation increment, components x, y, z ([`FIXED`]
    /// where a support or a planar restriction holds one).
    pub dofs: [usize; 3],
    /// Principal moments of inertia J₁, J₂, J₃ (kg m²) about the directors d₁, d₂, d₃.
    pub principal: Vector3<f64>,
}

impl FrameInertia {
    /// Which rotation components are free.
    pub fn free(&self) -> [bool; 3] {
        self.dofs.map(|i| i != FIXED)
    }

    /// The inertia in space, R diag(J) Rᵀ (kg m²), of the frame at `orientation`.
    pub fn spatial(&self, orientation: &UnitQuaternion<f64>) -> Matrix3<f64> {
        let r = orientation.to_rotation_matrix();
        let r = r.matrix();
        r * Matrix3::from_diagonal(&self.principal) * r.transpose()
    }

    /// `m` with the rows and columns of held components zeroed: the inertia the free
    /// components see (a held component does not move, and its reaction does no work).
    pub fn masked(&self, m: &Matrix3<f64>) -> Matrix3<f64> {
        let mut out = *m;
        for (k, free) in self.free().into_iter().enumerate() {
            if !free {
                out.row_mut(k).fill(0.0);
                out.column_mut(k).fill(0.0);
            }
        }
        out
    }

    /// `v` with the held components zeroed.
    pub fn masked_vector(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let free = self.free();
        Vector3::from_fn(|k, _| if free[k] { v[k] } else { 0.0 })
    }

    /// Solves m_FF x_F = b_F on the free components F of a masked `m` (x is 0 on held ones).
    pub fn solve_free(&self, m: &Matrix3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
        let free = self.free();
        let mut a = self.masked(m);
        for k in 0..3 {
            if !free[k] {
                a[(k, k)] = 1.0;
            }
        }
        let rhs = self.masked_vector(b);
        // a is symmetric positive definite on the free block and the identity elsewhere.
        a.cholesky()
            .map(|c| c.solve(&rhs))
            .unwrap_or_else(Vector3::zeros)
    }

    /// Spatial angular velocity (rad/s) of this frame in a free-DOF velocity vector (0 on
    /// held components).
    pub fn angular_velocity(&self, velocity: &[f64]) -> Vector3<f64> {
        Vector3::from_fn(|k, _| {
            let i = self.dofs[k];
            if i == FIXED {
                0.0
            } else {
                velocity[i]
            }
        })
    }

    /// Kinetic energy ½ ωᵀ I ω (J) at `orientation` with angular velocity `omega` (rad/s).
    pub fn kinetic_energy(&self, orientation: &UnitQuaternion<f64>, omega: &Vector3<f64>) -> f64 {
        let w = self.masked_vector(omega);
        0.5 * w.dot(&(self.masked(&self.spatial(orientation)) * w))
    }

    /// Angular momentum I ω (kg m²/s, in space) at `orientation` with angular velocity
    /// `omega` (rad/s), over the free components.
    pub fn momentum(
        &self,
        orientation: &UnitQuaternion<f64>,
        omega: &Vector3<f64>,
    ) -> Vector3<f64> {
        let w = self.masked_vector(omega);
        self.masked(&self.spatial(orientation)) * w
    }

    /// Checks the moments are finite and > 0 and the free components are all three or one
    /// (a planar rod turns its frames about the plane's normal only). Errors name
    /// `frames[f]`.
    pub(crate) fn validate(&self, f: usize) -> Result<(), ModelError> {
        if let Some(k) =
            (0..3).find(|&k| !(self.principal[k].is_finite() && self.principal[k] > 0.0))
        {
            return Err(ModelError::parameter(
                format!("frames[{f}].principal[{k}]"),
                self.principal[k],
                "finite and > 0 (kg m²)",
            ));
        }
        let n_free = self.free().iter().filter(|&&b| b).count();
        if n_free == 2 {
            // Two free components would let a frame turn about an axis that moves, and the
            // inertial term's chart would then need the held component's derivatives.
            return Err(ModelError::structure(
                format!("frames[{f}].dofs"),
                "a frame's rotation must be free in all three components or in one (planar)",
            ));
        }
        Ok(())
    }
}
