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
//! the activation distance at the friction limit.
//!
//! A sliding contact carries a lagged, convex dissipation potential (as in IPC's lagged
//! friction) D(x) = m φ_ε(|P (x − o)|), with o the slide's origin, P = I − n nᵀ the tangent
//! projector at its (lagged) normal n, m = μ f_n the kinetic force magnitude (f_n lagged: the
//! normal force when the contact last changed or was refreshed), and φ_ε the C¹ smoothing of
//! |s|: φ(s) = s for s ≥ ε, s²/(2ε) + ε/2 below. The force −∇D never exceeds m, always
//! opposes the slip from o, and D is convex with bounded slope, so the energy stays bounded
//! below — unlike a dead force −m ŝ (a linear potential), which drags on a contact that lifts
//! off or turns. The smoothing slip is ε = m / (k_t w), the anchor's deflection at the
//! friction limit: below it D is the sticking anchor ½ k_t w |P (x − o)|² (plus a constant),
//! above it the anchor's pull capped at m. A slide is thus an elastic–perfectly-plastic
//! anchor: a contact that starts to slide takes its anchor as origin (its force is the
//! anchor's pull capped to the cone, no jump), one whose slip from the origin falls back
//! within ε sticks again at the origin (no jump either), and where a piece of a load path or
//! a time step starts the origin is dragged to ε behind the contact along its slip
//! ([`Friction::restarted`]), so that the force opposes the slip of that piece or step while
//! keeping its value at the start.

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
    /// Sliding against the potential m φ_ε(|P (x − origin)|) (see the module docs).
    Slide {
        /// Where the slip is measured from (m).
        origin: Vector3<f64>,
        /// The (lagged) surface normal n of the tangent projector P = I − n nᵀ.
        normal: Vector3<f64>,
        /// The kinetic force magnitude m = μ f_n (N), f_n lagged.
        magnitude: f64,
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
            Friction::Slide {
                origin,
                normal,
                magnitude,
            } => {
                if magnitude <= 0.0 {
                    return Some((0.0, Vector3::zeros(), Matrix3::zeros()));
                }
                let p = Matrix3::identity() - normal * normal.transpose();
                let eps = Self::smoothing(magnitude, length, stiffness);
                let u = p * (x - origin);
                let r = u.norm();
                if r >= eps {
                    let hat = u / r;
                    Some((
                        magnitude * r,
                        hat * magnitude,
                        (p - hat * hat.transpose()) * (magnitude / r),
                    ))
                } else {
                    let k = magnitude / eps;
                    Some((0.5 * k * r * r + 0.5 * magnitude * eps, u * k, p * k))
                }
            }
        }
    }

    /// The smoothing slip ε (m) of a slide of force magnitude `magnitude` (N) at a site
    /// standing for `length` (m) with anchor stiffness `stiffness` (N/m²): the anchor's
    /// deflection at that force, ε = m / (k_t w).
    pub fn smoothing(magnitude: f64, length: f64, stiffness: f64) -> f64 {
        magnitude / (stiffness * length)
    }

    /// A sliding contact's slip from its origin, P (x − o) (m); zero otherwise.
    pub fn slip(&self, x: &Vector3<f64>) -> Vector3<f64> {
        match *self {
            Friction::Slide { origin, normal, .. } => {
                let d = x - origin;
                d - normal * normal.dot(&d)
            }
            _ => Vector3::zeros(),
        }
    }

    /// This term where a piece of a load path or a time step starts at `x`, with `normal` the
    /// surface normal there: a sliding contact's origin is dragged to ε behind `x` along its
    /// slip (and its normal renewed), so that its force keeps its value at `x` and opposes
    /// the slip from `x` on; a slide still within ε of its origin, and any other term, is
    /// kept.
    pub fn restarted(
        &self,
        x: &Vector3<f64>,
        normal: &Vector3<f64>,
        length: f64,
        stiffness: f64,
    ) -> Friction {
        let Friction::Slide { magnitude, .. } = *self else {
            return *self;
        };
        let eps = Self::smoothing(magnitude, length, stiffness);
        let u = self.slip(x);
        let u = u - normal * normal.dot(&u);
        let r = u.norm();
        if r < eps || r == 0.0 {
            return *self;
        }
        Friction::Slide {
            origin: x - u * (eps / r),
            normal: *normal,
            magnitude,
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
