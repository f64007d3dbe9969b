//! The lumped mass of a model's free DOFs: a diagonal from its
//! [`MassMetric`](crate::solver::MassMetric) for the coordinates, and a 3×3 rotary inertia
//! block per material frame.
//!
//! The models already attach an inertia to every DOF for their eigenvalue problems; dynamics
//! reuses it for the coordinates, so that the natural frequencies of the linearized equations
//! of motion are the eigenvalues the stability analysis reports (H v = ω² M v). For the
//! discrete elastic rod it is the consistent lumping: vertex mass ρA × (half of each adjacent
//! rest edge), the same masses gravity acts on (so free fall is exact), and twist inertia
//! ρ(I₁ + I₂) × (rest edge length) for the edge angle — ρJ l with J the polar moment of area.
//! Rotary inertia of the sections about their bending axes is left out, as in Euler–Bernoulli
//! theory. The Cosserat rod and the SE(3) beam lump ρA the same way on their vertices, and
//! give each frame the full rotary inertia of the slice it stands for,
//! ρ·diag(I₂, I₁, I₁ + I₂)·ℓ about its directors (see [`FrameInertia`]): a block that turns
//! with the frame.

use nalgebra::{Matrix3, UnitQuaternion};

use crate::assembly::FIXED;
use crate::error::ModelError;

use super::flat::FlatDofs;
use super::frames::FrameInertia;

/// Mass over the free DOFs: a diagonal (kg for coordinates, kg m² for angles) and the rotary
/// inertia of the frames whose rotations are DOFs.
#[derive(Clone, Debug, PartialEq)]
pub struct LumpedMass {
    diagonal: Vec<f64>,
    frames: Vec<FrameInertia>,
}

impl LumpedMass {
    /// The mass of `model`'s free DOFs: its [`MassMetric`](crate::solver::MassMetric) on
    /// coordinates, its [`FlatDofs::frames`] on frame rotations. Errors if a coordinate's
    /// entry is not finite and > 0 (`inertia_metric[i]`: a DOF without inertia cannot be
    /// stepped by these schemes), a frame's moment is not (`frames[f].principal[k]`), a
    /// frame is free in two components only or shares a DOF with another (`frames[f].dofs`).
    pub fn of<P: FlatDofs>(model: &P) -> Result<Self, ModelError> {
        let n = model.n_free();
        let frames = if model.has_flat_dofs() {
            Vec::new()
        } else {
            model.frames()
        };
        let mut in_frame = vec![false; n];
        for (f, frame) in frames.iter().enumerate() {
            frame.validate(f)?;
            for &i in &frame.dofs {
                if i == FIXED {
                    continue;
                }
                if i >= n || in_frame[i] {
                    return Err(ModelError::structure(
                        format!("frames[{f}].dofs"),
                        format!("free DOF {i} is out of range or belongs to another frame"),
                    ));
                }
                in_frame[i] = true;
            }
        }
        let mut diagonal = vec![0.0; n];
        for (i, d) in diagonal.iter_mut().enumerate() {
            if in_frame[i] {
                continue;
            }
            let m = model.inertia_metric(i);
            if !(m.is_finite() && m > 0.0) {
                return Err(ModelError::parameter(
                    format!("inertia_metric[{i}]"),
                    m,
                    "finite and > 0 (kg or kg m²)",
                ));
            }
            *d = m;
        }
        Ok(Self { diagonal, frames })
    }

    /// The diagonal entries (kg or kg m²), one per free DOF; 0 on the rotation DOFs of
    /// frames, whose inertia is the block of [`Self::frames`].
    pub fn diagonal(&self) -> &[f64] {
        &self.diagonal
    }

    /// The frames whose rotations are DOFs, with their principal moments (kg m²).
    pub fn frames(&self) -> &[FrameInertia] {
        &self.frames
    }

    /// True if free DOF `i` turns a frame.
    pub fn is_frame_dof(&self, i: usize) -> bool {
        self.diagonal[i] == 0.0
    }

    /// The mass matrix at the frame orientations `orientations` (one per frame, in order):
    /// the diagonal plus each frame's inertia in space on its free rotation DOFs (kg, kg m²),
    /// as a dense matrix for eigenvalue problems of small models. Errors (`orientations`) if
    /// the count is not the number of frames.
    pub fn dense_matrix(
        &self,
        orientations: &[UnitQuaternion<f64>],
    ) -> Result<nalgebra::DMatrix<f64>, ModelError> {
        self.check_orientations(orientations)?;
        let n = self.diagonal.len();
        let mut m = nalgebra::DMatrix::<f64>::from_diagonal(&nalgebra::DVector::from_column_slice(
            &self.diagonal,
        ));
        for (frame, q) in self.frames.iter().zip(orientations) {
            let block: Matrix3<f64> = frame.masked(&frame.spatial(q));
            for (a, &i) in frame.dofs.iter().enumerate() {
                for (b, &j) in frame.dofs.iter().enumerate() {
                    if i != FIXED && j != FIXED && i < n && j < n {
                        m[(i, j)] += block[(a, b)];
                    }
                }
            }
        }
        Ok(m)
    }

    /// Kinetic energy ½ vᵀ M v (J) of the free-DOF velocity `v` (m/s or rad/s; the spatial
    /// angular velocity on a frame's rotation DOFs) with the frames at `orientations` (one per
    /// frame, in order; empty for a model without frames). Errors (`orientations`) if the
    /// count is not the number of frames.
    pub fn kinetic_energy_at(
        &self,
        v: &[f64],
        orientations: &[UnitQuaternion<f64>],
    ) -> Result<f64, ModelError> {
        self.check_orientations(orientations)?;
        let rotary: f64 = self
            .frames
            .iter()
            .zip(orientations)
            .map(|(f, q)| f.kinetic_energy(q, &f.angular_velocity(v)))
            .sum();
        Ok(self.kinetic_energy(v) + rotary)
    }

    /// Kinetic energy ½ Σ mᵢ vᵢ² (J) of the coordinates (m/s or rad/s): all of it for a model
    /// without frames (see [`Self::kinetic_energy_at`] for the frames').
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        0.5 * self
            .diagonal
            .iter()
            .zip(v)
            .map(|(m, v)| m * v * v)
            .sum::<f64>()
    }

    fn check_orientations(&self, orientations: &[UnitQuaternion<f64>]) -> Result<(), ModelError> {
        if orientations.len() == self.frames.len() {
            Ok(())
        } else {
            Err(ModelError::structure(
                "orientations",
                format!(
                    "got {} orientations for {} frames",
                    orientations.len(),
                    self.frames.len()
                ),
            ))
        }
    }
}
