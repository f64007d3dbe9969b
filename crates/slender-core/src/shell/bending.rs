//! Mid-edge director bending of one triangle (libshell's `MidedgeAngleTan`, design.md §3.2).
//!
//! Each edge carries a director; its angle from the face normal, measured about the edge
//! toward the outside of face f, is α = θ/2 + σφ, with θ the signed dihedral angle of the edge
//! (0 on a boundary edge), φ the edge's angle DOF and σ = ±1 the face's orientation of the edge.
//! On a free boundary edge φ is free, so minimization yields the natural boundary condition
//! (the `MidedgeAverage` variant would pin it and stiffen narrow strips). With the altitude
//! h_i of vertex i over its opposite edge, II_i = 2 h_i tan α_i, and the second fundamental
//! form in the edge basis is b = [[II₀+II₁, II₀], [II₀, II₀+II₂]]. The energy is
//!
//!   E = Ā (h³/12) [ ½λ (tr N)² + μ tr(N²) ],  N = ā⁻¹(b − b̄),
//!
//! which for cylindrical bending N = diag(κ, 0) is ½Dκ² per unit area, D = Eh³/(12(1−ν²)).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::geometry::Vec3;

use super::edge_jet::{edge_jet, EdgeJet};
use super::membrane::{quadratic_form, FaceRest};

/// Variables of one edge term: q₀, q₁, q₂ (9), the opposite vertex p (3) and φ (1).
pub const EDGE_VARS: usize = 13;
/// Variables of the face stencil: q₀, q₁, q₂, p₀, p₁, p₂ (18) and φ₀, φ₁, φ₂ (3).
pub const FACE_VARS: usize = 21;

/// How the director of the edge opposite local vertex `i` is determined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EdgeDirector {
    /// Interior edge: the neighbour's opposite vertex p and the angle φ (rad).
    Interior {
        /// Opposite vertex of the neighbouring face (m).
        p: Vec3,
        /// Edge angle DOF (rad).
        phi: f64,
        /// Orientation σ = ±1 of the edge as seen from this face.
        sigma: f64,
    },
    /// Free boundary edge: θ = 0, director angle σφ.
    Free {
        /// Edge angle DOF (rad).
        phi: f64,
        /// Orientation σ = ±1.
        sigma: f64,
    },
    /// Clamped edge: the director is the clamp normal n_c (unit), so α = ∠(n_f, n_c) about
    /// the edge (the exact director clamp of design.md §3.2, no penalty).
    Clamped {
        /// Clamp normal (unit).
        normal: Vec3,
    },
}

/// Value of II_i = 2 h_i tan α_i alone (no derivatives): the same formula as
/// [`edge_jet`] in plain f64, for energy evaluations in line searches.
pub fn edge_curvature_value(q: [&Vec3; 3], i: usize, director: &EdgeDirector) -> f64 {
    let n_f = (q[1] - q[0]).cross(&(q[2] - q[0]));
    let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
    let edge = b - a;
    let edge_len = edge.norm();
    let altitude = n_f.norm() / edge_len;
    let alpha = match director {
        EdgeDirector::Interior { p, phi, sigma } => {
            let n_g = (a - b).cross(&(p - b));
            let theta = (n_f.cross(&n_g).dot(&edge) / edge_len).atan2(n_f.dot(&n_g));
            0.5 * theta + sigma * phi
        }
        EdgeDirector::Free { phi, sigma } => sigma * phi,
        EdgeDirector::Clamped { normal } => {
            (n_f.cross(normal).dot(&edge) / edge_len).atan2(n_f.dot(normal))
        }
    };
    2.0 * altitude * alpha.tan()
}

/// ∂b/∂II: rows b₁₁, b₁₂, b₂₂; columns II₀, II₁, II₂.
fn sff_jacobian() -> Matrix3<f64> {
    Matrix3::new(1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0)
}

/// Second fundamental form (b₁₁, b₁₂, b₂₂) (1/m · m² = m) of a face from its three II values.
pub fn second_fundamental_form(ii: &Vector3<f64>) -> Vector3<f64> {
    sff_jacobian() * ii
}

/// Position in the 21-variable face stencil of edge variable `k` of the edge opposite vertex `i`.
fn face_slot(i: usize, k: usize) -> usize {
    match k {
        0..=8 => k,
        9..=11 => 9 + 3 * i + (k - 9),
        _ => 18 + i,
    }
}

/// Bending energy (J) of a face with directors `directors` (edge opposite local vertex i),
/// rest data `rest`, rest second fundamental form `bbar`, thickness `h` (m) and 2-D Lamé
/// constants (Pa). Adds the gradient and Hessian in the 21-variable stencil when given.
#[allow(clippy::too_many_arguments)]
pub fn bending_energy(
    q: [&Vec3; 3],
    directors: &[EdgeDirector; 3],
    rest: &FaceRest,
    bbar: &Vector3<f64>,
    h: f64,
    lambda: f64,
    mu: f64,
    grad: Option<&mut SVector<f64, FACE_VARS>>,
    hess: Option<&mut SMatrix<f64, FACE_VARS, FACE_VARS>>,
) -> f64 {
    let k = quadratic_form(&rest.abar_inv, lambda, mu, rest.area * h * h * h / 12.0);
    if grad.is_none() && hess.is_none() {
        let ii_v = Vector3::from_fn(|i, _| edge_curvature_value(q, i, &directors[i]));
        let db = second_fundamental_form(&ii_v) - bbar;
        return 0.5 * db.dot(&(k * db));
    }
    // A gradient-only assembly (a chord step, a final check) skips the Hessians.
    let hessian = hess.is_some();
    let ii: [EdgeJet; 3] = std::array::from_fn(|i| edge_jet(q, i, &directors[i], hessian));
    let ii_v = Vector3::new(ii[0].v, ii[1].v, ii[2].v);
    let j = sff_jacobian();
    let db = second_fundamental_form(&ii_v) - bbar;
    let energy = 0.5 * db.dot(&(k * db));
    // E as a function of II: weights w = ∂E/∂II and curvature c = ∂²E/∂II².
    let w = j.transpose() * k * db;
    let c = j.transpose() * k * j;
    if let Some(g) = grad {
        for (i, iii) in ii.iter().enumerate() {
            for kk in 0..EDGE_VARS {
                g[face_slot(i, kk)] += w[i] * iii.g[kk];
            }
        }
    }
    if let Some(hm) = hess {
        for (i, iii) in ii.iter().enumerate() {
            for a in 0..EDGE_VARS {
                let sa = face_slot(i, a);
                for b in 0..EDGE_VARS {
                    hm[(sa, face_slot(i, b))] += w[i] * iii.h[(a, b)];
                }
            }
            for (jj, iij) in ii.iter().enumerate() {
                let cij = c[(i, jj)];
                if cij == 0.0 {
                    continue;
                }
                for a in 0..EDGE_VARS {
                    let ga = cij * iii.g[a];
                    if ga == 0.0 {
                        continue;
                    }
                    let sa = face_slot(i, a);
                    for b in 0..EDGE_VARS {
                        hm[(sa, face_slot(jj, b))] += ga * iij.g[b];
                    }
                }
            }
        }
    }
    energy
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shell::dual::{
        cross3, cross3_const, dot3, dot3_const, point, sub3, Dual2, DualVec3,
    };

    // The forward-mode formulation the analytic edge jet replaced, kept as its reference:
    // second-order duals over all 13 edge variables.
    /// II_i = 2 h_i tan α_i of the edge opposite local vertex `i` of the face q, with derivatives
    /// in the 13 edge variables (q₀, q₁, q₂, p, φ); unused variables have zero derivatives.
    fn edge_curvature_dual(q: [&Vec3; 3], i: usize, director: &EdgeDirector) -> Dual2<EDGE_VARS> {
        edge_curvature_on(&FaceDuals::new(q, false), i, director)
    }

    /// The face's corners and normal as duals in the edge variables. The corners are variables
    /// 0–8 in every edge term of the face, so the three edges share them: built once per face.
    struct FaceDuals {
        x: [f64; EDGE_VARS],
        q: [DualVec3<EDGE_VARS>; 3],
        /// n_f = (q₁ − q₀) × (q₂ − q₀), not normalized.
        n_f: DualVec3<EDGE_VARS>,
        /// |n_f| = twice the face area.
        n_f_norm: Dual2<EDGE_VARS>,
        /// Whether only gradients are wanted ([`Dual2::first_order`]).
        first_order: bool,
    }

    impl FaceDuals {
        /// The duals of face q; with `first_order`, values and gradients only (for a
        /// gradient-only assembly, which then skips the Hessian loops of every operation).
        fn new(q: [&Vec3; 3], first_order: bool) -> Self {
            let mut x = [0.0; EDGE_VARS];
            for k in 0..3 {
                x[3 * k..3 * k + 3].copy_from_slice(q[k].as_slice());
            }
            let q: [_; 3] = std::array::from_fn(|k| {
                point::<EDGE_VARS>(&x, k).map(|c| c.with_first_order(first_order))
            });
            let n_f = cross3(&sub3(&q[1], &q[0]), &sub3(&q[2], &q[0]));
            let n_f_norm = dot3(&n_f, &n_f).sqrt();
            Self {
                x,
                q,
                n_f,
                n_f_norm,
                first_order,
            }
        }
    }

    /// [`edge_curvature`] with the face's duals built already.
    fn edge_curvature_on(face: &FaceDuals, i: usize, director: &EdgeDirector) -> Dual2<EDGE_VARS> {
        let mut x = face.x;
        if let EdgeDirector::Interior { p, phi, .. } = director {
            x[9..12].copy_from_slice(p.as_slice());
            x[12] = *phi;
        }
        if let EdgeDirector::Free { phi, .. } = director {
            x[12] = *phi;
        }
        let (qd, n_f) = (&face.q, &face.n_f);
        // The edge, in this face's counter-clockwise direction.
        let (a, b) = (&qd[(i + 1) % 3], &qd[(i + 2) % 3]);
        let edge = sub3(b, a);
        let edge_len = dot3(&edge, &edge).sqrt();
        let altitude = face.n_f_norm / edge_len;
        let phi_dual = Dual2::variable(x[12], 12).with_first_order(face.first_order);
        let alpha = match director {
            EdgeDirector::Interior { sigma, .. } => {
                let p = point::<EDGE_VARS>(&x, 3).map(|c| c.with_first_order(face.first_order));
                // The neighbour runs along the edge the other way: (b, a, p) is counter-clockwise.
                let n_g = cross3(&sub3(a, b), &sub3(&p, b));
                // Signed angle from n_f to n_g about the edge; normals need not be unit.
                let theta = (dot3(&cross3(n_f, &n_g), &edge) / edge_len).atan2(&dot3(n_f, &n_g));
                theta.scale(0.5) + phi_dual.scale(*sigma)
            }
            EdgeDirector::Free { sigma, .. } => phi_dual.scale(*sigma),
            EdgeDirector::Clamped { normal } => {
                let c = [normal.x, normal.y, normal.z];
                (dot3(&cross3_const(n_f, &c), &edge) / edge_len).atan2(&dot3_const(n_f, &c))
            }
        };
        (altitude * alpha.tan()).scale(2.0)
    }

    /// The analytic edge jet against the 13-variable dual formulation, for every kind of
    /// edge director and every edge of the face, on random bent faces: values, gradients and
    /// Hessians agree to round-off (1e-10 of each quantity's largest entry).
    #[test]
    fn analytic_edge_jet_matches_the_dual_formulation() {
        let mut rng = crate::testing::Rng(0x5EED_1234_ABCD_0001);
        let mut jitter = |s: f64| Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * s;
        for trial in 0..40 {
            let q = [
                Vec3::new(0.0, 0.0, 0.0) + jitter(0.3),
                Vec3::new(1.0, 0.0, 0.0) + jitter(0.3),
                Vec3::new(0.0, 1.0, 0.0) + jitter(0.3),
            ];
            let corners = [&q[0], &q[1], &q[2]];
            for i in 0..3 {
                let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
                // The neighbour's vertex across the edge, folded out of the plane.
                let p = a + b - q[i] + jitter(0.5);
                let sigma = if trial % 2 == 0 { 1.0 } else { -1.0 };
                let phi = 0.3 * jitter(1.0).x;
                let directors = [
                    EdgeDirector::Interior { p, phi, sigma },
                    EdgeDirector::Free { phi, sigma },
                    EdgeDirector::Clamped {
                        normal: (Vec3::new(0.0, 0.0, 1.0) + jitter(0.4)).normalize(),
                    },
                ];
                for d in &directors {
                    let reference = edge_curvature_dual(corners, i, d);
                    let jet = edge_jet(corners, i, d, true);
                    let gradient_only = edge_jet(corners, i, d, false);
                    let scale = |m: f64| m.max(1e-300);
                    let ev = (jet.v - reference.v).abs() / scale(reference.v.abs());
                    let eg = (jet.g - reference.g).amax() / scale(reference.g.amax());
                    let eh = (jet.h - reference.h).amax() / scale(reference.h.amax());
                    assert!(
                        ev < 1e-10 && eg < 1e-10 && eh < 1e-10,
                        "trial {trial}, edge {i}, {d:?}: relative differences value {ev:.1e}, \
                         gradient {eg:.1e}, Hessian {eh:.1e}"
                    );
                    assert_eq!(gradient_only.g, jet.g);
                    assert_eq!(gradient_only.v, jet.v);
                    assert!(
                        (edge_curvature_value(corners, i, d) - jet.v).abs()
                            <= 1e-12 * scale(jet.v.abs())
                    );
                }
            }
        }
    }

    /// The gradient-only evaluation (no Hessians) gives the gradient of the full evaluation
    /// to the bit, for every kind of edge director.
    #[test]
    fn gradient_only_bending_matches_the_full_gradient() {
        let rest = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let q = [
            Vec3::new(0.01, -0.02, 0.03),
            Vec3::new(1.02, 0.05, -0.04),
            Vec3::new(-0.03, 0.97, 0.08),
        ];
        let directors = [
            EdgeDirector::Interior {
                p: Vec3::new(1.1, 1.05, 0.2),
                phi: 0.07,
                sigma: 1.0,
            },
            EdgeDirector::Free {
                phi: -0.05,
                sigma: -1.0,
            },
            EdgeDirector::Clamped {
                normal: Vec3::new(0.1, 0.0, 1.0).normalize(),
            },
        ];
        let face_rest = FaceRest::new([&rest[0], &rest[1], &rest[2]]);
        let bbar = Vector3::new(0.01, -0.02, 0.03);
        let corners = [&q[0], &q[1], &q[2]];
        let mut g_full = SVector::<f64, FACE_VARS>::zeros();
        let mut h_full = SMatrix::<f64, FACE_VARS, FACE_VARS>::zeros();
        let e_full = bending_energy(
            corners,
            &directors,
            &face_rest,
            &bbar,
            0.01,
            1e6,
            2e6,
            Some(&mut g_full),
            Some(&mut h_full),
        );
        let mut g_only = SVector::<f64, FACE_VARS>::zeros();
        let e_only = bending_energy(
            corners,
            &directors,
            &face_rest,
            &bbar,
            0.01,
            1e6,
            2e6,
            Some(&mut g_only),
            None,
        );
        assert!(g_full.norm() > 0.0 && h_full.norm() > 0.0);
        assert_eq!(e_only, e_full);
        assert_eq!(g_only, g_full);
    }
}
