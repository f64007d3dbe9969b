//! The mid-edge curvature II_i = 2 h_i tan α_i of one edge (see `bending.rs`) with its exact
//! gradient and Hessian in the 13 edge variables (q₀, q₁, q₂, p, φ), by the chain rule written
//! out in three layers instead of forward-mode duals over all 13 variables.
//!
//! Why: with 13-variable second-order duals every elementary operation carried a 13×13
//! Hessian (1.5 kB copied and zeroed per operation), which made the mid-edge bending about
//! half of a Newton iteration of the sensitivity study. Here the duals are 5-variable and
//! the 13×13 Hessian is formed once per edge:
//!
//! 1. Four polynomial scalars of the intermediate vector u = (n_f, n_g, e, φ) ∈ ℝ¹⁰:
//!    N² = n_f·n_f, E² = e·e, y₀ = (n_f × n_g)·e and x = n_f·n_g (gradients and constant
//!    Hessians in u written below), plus φ itself.
//! 2. II = 2 √(N²) / √(E²) · tan(c_θ atan2(y₀/√(E²), x) + σ_φ φ) as a function of those five
//!    scalars: a 5-variable [`Dual2`] (c_θ = ½ for an interior edge, 1 for a clamped edge
//!    whose "neighbour normal" is the clamp normal, 0 for a free edge).
//! 3. u as a function of the stencil: n_f = (q₁ − q₀) × (q₂ − q₀), n_g = (a − b) × (p − b),
//!    e = b − a (a, b the edge's ends in this face's order). The Hessian is
//!    Jᵀ (∇²_u II) J plus the second derivatives of the two cross products (bilinear forms
//!    weighted by ∂II/∂n_f and ∂II/∂n_g); e and φ are linear.
//!
//! The result agrees with the dual-number formulation to round-off (a test below keeps that
//! formulation as the reference) and with finite differences (`tests/shell_derivatives.rs`).

use nalgebra::{Matrix3, SMatrix, SVector};

use crate::geometry::Vec3;

use super::bending::{EdgeDirector, EDGE_VARS};
use super::dual::Dual2;

/// Dimension of the intermediate vector u = (n_f, n_g, e, φ).
const U: usize = 10;
/// Offsets of n_f, n_g, e and φ in u.
const NF: usize = 0;
const NG: usize = 3;
const E: usize = 6;
const PHI: usize = 9;
/// Offset of the neighbour's opposite vertex p and of φ among the edge variables.
const P_VAR: usize = 9;
const PHI_VAR: usize = 12;

/// II of one edge with its gradient and (when asked) Hessian in the 13 edge variables.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeJet {
    /// II = 2 h tan α (m · dimensionless = m).
    pub v: f64,
    /// ∂II/∂x (dimensionless for coordinates, m per rad for φ).
    pub g: SVector<f64, EDGE_VARS>,
    /// ∂²II/∂x² (zero when only the gradient was asked).
    pub h: SMatrix<f64, EDGE_VARS, EDGE_VARS>,
}

/// The cross-product matrix [v]× (so that [v]× x = v × x).
fn cross_matrix(v: &Vec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// II of the edge opposite local vertex `i` of face q with its gradient, and its Hessian if
/// `hessian`.
pub fn edge_jet(q: [&Vec3; 3], i: usize, director: &EdgeDirector, hessian: bool) -> EdgeJet {
    let (ia, ib) = ((i + 1) % 3, (i + 2) % 3);
    let (a, b) = (q[ia], q[ib]);
    let u1 = q[1] - q[0];
    let u2 = q[2] - q[0];
    let n_f = u1.cross(&u2);
    let e = b - a;
    // The neighbour's normal (or the clamp normal), the weight of θ and that of φ.
    let (n_g, c_theta, sigma_phi, phi) = match director {
        EdgeDirector::Interior { p, phi, sigma } => ((a - b).cross(&(p - b)), 0.5, *sigma, *phi),
        EdgeDirector::Free { phi, sigma } => (Vec3::zeros(), 0.0, *sigma, *phi),
        EdgeDirector::Clamped { normal } => (*normal, 1.0, 0.0, 0.0),
    };
    let y0 = n_f.cross(&n_g).dot(&e);
    let x = n_f.dot(&n_g);

    // Layer 2: II of the five scalars (N², E², y₀, x, φ).
    let var = |v: f64, k: usize| Dual2::<5>::variable(v, k);
    let sqrt_e = var(e.dot(&e), 1).sqrt();
    let altitude = var(n_f.dot(&n_f), 0).sqrt() / sqrt_e;
    let mut alpha = var(phi, 4).scale(sigma_phi);
    if c_theta != 0.0 {
        // Free edges skip θ: atan2 has no derivative at (0, 0).
        let theta = (var(y0, 2) / sqrt_e).atan2(&var(x, 3));
        alpha = theta.scale(c_theta) + alpha;
    }
    let f = (altitude * alpha.tan()).scale(2.0);

    // Layer 1: gradients of the five scalars in u (columns).
    let mut grads = SMatrix::<f64, U, 5>::zeros();
    grads.fixed_view_mut::<3, 1>(NF, 0).copy_from(&(2.0 * n_f));
    grads.fixed_view_mut::<3, 1>(E, 1).copy_from(&(2.0 * e));
    grads
        .fixed_view_mut::<3, 1>(NF, 2)
        .copy_from(&n_g.cross(&e));
    grads
        .fixed_view_mut::<3, 1>(NG, 2)
        .copy_from(&e.cross(&n_f));
    grads
        .fixed_view_mut::<3, 1>(E, 2)
        .copy_from(&n_f.cross(&n_g));
    grads.fixed_view_mut::<3, 1>(NF, 3).copy_from(&n_g);
    grads.fixed_view_mut::<3, 1>(NG, 3).copy_from(&n_f);
    grads[(PHI, 4)] = 1.0;
    let grad_u: SVector<f64, U> = grads * f.g;

    // Layer 3: the Jacobian of u in the edge variables (block k = point k, p is block 3).
    let mut jac = SMatrix::<f64, U, EDGE_VARS>::zeros();
    jac.fixed_view_mut::<3, 3>(NF, 0)
        .copy_from(&cross_matrix(&(q[2] - q[1])));
    jac.fixed_view_mut::<3, 3>(NF, 3)
        .copy_from(&(-cross_matrix(&u2)));
    jac.fixed_view_mut::<3, 3>(NF, 6)
        .copy_from(&cross_matrix(&u1));
    let interior = match director {
        EdgeDirector::Interior { p, .. } => {
            // n_g = v₁ × v₂ with v₁ = a − b, v₂ = p − b.
            let (v1, v2) = (a - b, p - b);
            jac.fixed_view_mut::<3, 3>(NG, 3 * ia)
                .copy_from(&(-cross_matrix(&v2)));
            jac.fixed_view_mut::<3, 3>(NG, P_VAR)
                .copy_from(&cross_matrix(&v1));
            let mut db = cross_matrix(&(p - a));
            db += jac.fixed_view::<3, 3>(NG, 3 * ib);
            jac.fixed_view_mut::<3, 3>(NG, 3 * ib).copy_from(&db);
            true
        }
        _ => false,
    };
    for c in 0..3 {
        jac[(E + c, 3 * ia + c)] -= 1.0;
        jac[(E + c, 3 * ib + c)] += 1.0;
    }
    if !matches!(director, EdgeDirector::Clamped { .. }) {
        jac[(PHI, PHI_VAR)] = 1.0;
    }
    let g = jac.transpose() * grad_u;
    if !hessian {
        return EdgeJet {
            v: f.v,
            g,
            h: SMatrix::zeros(),
        };
    }

    // ∇²_u II = Σ_st (∂²II/∂s∂t) ∇s ∇tᵀ + Σ_s (∂II/∂s) ∇²s.
    let mut hess_u: SMatrix<f64, U, U> = grads * f.h * grads.transpose();
    for c in 0..3 {
        hess_u[(NF + c, NF + c)] += 2.0 * f.g[0];
        hess_u[(E + c, E + c)] += 2.0 * f.g[1];
        hess_u[(NF + c, NG + c)] += f.g[3];
        hess_u[(NG + c, NF + c)] += f.g[3];
    }
    // y₀ = det(n_f, n_g, e): ∂²/∂n_f∂n_g = −[e]×, ∂²/∂n_f∂e = [n_g]×, ∂²/∂n_g∂e = −[n_f]×.
    let gy = f.g[2];
    let blocks = [
        (NF, NG, -cross_matrix(&e)),
        (NF, E, cross_matrix(&n_g)),
        (NG, E, -cross_matrix(&n_f)),
    ];
    for (r, c, m) in blocks {
        let m = m * gy;
        let mut rc = hess_u.fixed_view_mut::<3, 3>(r, c);
        rc += m;
        let mut cr = hess_u.fixed_view_mut::<3, 3>(c, r);
        cr += m.transpose();
    }
    let mut h = jac.transpose() * hess_u * jac;
    // The cross products' second derivatives: for n = v₁ × v₂ and weight w = ∂II/∂n,
    // δ(w·n) twice is δv₁ᵀ W δ′v₂ + δv₂ᵀ Wᵀ δ′v₁ with W = −[w]×.
    let w_f = -cross_matrix(&grad_u.fixed_rows::<3>(NF).into_owned());
    add_bilinear(&mut h, &[(0, -1.0), (1, 1.0)], &[(0, -1.0), (2, 1.0)], &w_f);
    if interior {
        let w_g = -cross_matrix(&grad_u.fixed_rows::<3>(NG).into_owned());
        add_bilinear(
            &mut h,
            &[(ia, 1.0), (ib, -1.0)],
            &[(3, 1.0), (ib, -1.0)],
            &w_g,
        );
    }
    EdgeJet { v: f.v, g, h }
}

/// Adds S₁ᵀ W S₂ + S₂ᵀ Wᵀ S₁ to `h`, where S₁ and S₂ pick signed sums of 3-blocks of the
/// variables (v₁ = Σ s·x_block over `first`, v₂ likewise over `second`).
fn add_bilinear(
    h: &mut SMatrix<f64, EDGE_VARS, EDGE_VARS>,
    first: &[(usize, f64)],
    second: &[(usize, f64)],
    w: &Matrix3<f64>,
) {
    for &(b1, s1) in first {
        for &(b2, s2) in second {
            let m = w * (s1 * s2);
            let mut v12 = h.fixed_view_mut::<3, 3>(3 * b1, 3 * b2);
            v12 += m;
            let mut v21 = h.fixed_view_mut::<3, 3>(3 * b2, 3 * b1);
            v21 += m.transpose();
        }
    }
}
