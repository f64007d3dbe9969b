//! Dry Coulomb friction at contacts: each contact either sticks — its tangential position held
//! at the point where sticking began — or slides against a kinetic force μ·f_n; an
//! active-set update switches a contact between the two when the force it needs leaves the
//! friction cone or its slip reverses.
//!
//! A sticking contact is held by a tangential anchor of stiffness k_t per unit length,
//! ½ k_t w |P (x − a)|² with P = I − n nᵀ the tangent projector at the anchor a. The anchor
//! is set once, when the contact starts to stick, and never moved while it sticks, so nothing
//! creeps: the contact only deflects elastically, by |f_t| / (k_t w), which the default k_t
//! ([`ContactParams::for_line_load`](super::ContactParams::for_line_load)) keeps below μ·10⁻⁴ of
//! the activation distance at the friction limit. A sliding contact carries the constant
//! force −μ f_n ŝ (ŝ the slip direction, f_n the normal force when the contact last changed
//! or was refreshed) as a linear potential.

use nalgebra::{Matrix3, Vector3};

/// What one (site, obstacle) contact does tangentially.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Friction {
    /// Out of contact, or on a frictionless surface.
    Free,
    /// Held at `anchor` (m) in the plane normal to `normal`.
    Stick {
        /// Where the site was when it started to stick (m).
        anchor: Vector3<f64>,
        /// The surface normal there.
        normal: Vector3<f64>,
    },
    /// Sliding: the kinetic friction force on the structure (N).
    Slide {
        /// −μ f_n ŝ (N).
        force: Vector3<f64>,
    },
}

impl Friction {
    /// Energy (J), gradient (N) and Hessian (N/m) of the tangential term at position `x` for a
    /// site standing for `length` (m) with anchor stiffness `stiffness` (N/m²).
    pub fn derivatives(
        &self,
        x: &Vector3<f64>,
        length: f64,
        stiffness: f64,
    ) -> Option<(f64, Vector3<f64>, Matrix3<f64>)> {
        match *self {
            Friction::Free => None,
            Friction::Stick { anchor, normal } => {
                let p = Matrix3::identity() - normal * normal.transpose();
                let k = stiffness * length;
                let d = p * (x - anchor);
                Some((0.5 * k * d.norm_squared(), d * k, p * k))
            }
            Friction::Slide { force } => Some((-force.dot(x), -force, Matrix3::zeros())),
        }
    }

    /// The tangential force (N) this term applies to the structure at position `x`.
    pub fn force(&self, x: &Vector3<f64>, length: f64, stiffness: f64) -> Vector3<f64> {
        self.derivatives(x, length, stiffness)
            .map_or(Vector3::zeros(), |(_, g, _)| -g)
    }
}

/// How many contacts changed in one active-set update.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrictionUpdate {
    /// Contacts that started to stick (new contacts on a rough surface, or slides that stopped).
    pub stuck: usize,
    /// Sticking contacts whose force left the friction cone: now sliding.
    pub slipped: usize,
    /// Contacts that separated.
    pub released: usize,
}

impl FrictionUpdate {
    /// True if a contact changed between sticking and sliding: the state that was solved with
    /// the old set does not satisfy Coulomb's law and must be solved again.
    pub fn changed(&self) -> bool {
        self.stuck + self.slipped > 0
    }
}
