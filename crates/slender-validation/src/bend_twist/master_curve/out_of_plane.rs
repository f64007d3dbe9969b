//! The linearized out-of-plane stability of the planar equilibrium: the reduced system whose
//! free-end moment `f = δm_x(1)` vanishes where the planar state is critical.
//!
//! A perturbation rotates the frame by an infinitesimal `φ(S)` (`δd_i = φ × d_i`). The natural
//! curvature is attached to the material frame, so `δm = K φ' + φ × m` with the lab-frame
//! stiffness `K = I − (1 − c) d₃d₃ᵀ`, and with `n` known, `δm' = −(φ × d₃) × n`; `φ(0) = 0`,
//! `δm(1) = 0`. The in-plane part (`φ_y, δm_y`) is the linearized planar equation; in the
//! out-of-plane part `δm_z ≡ 0` (the vertical torque is conserved), which leaves, with
//! `v = (δm_x + φ_z m_y, 0, −φ_x m_y)` and `k = 1 − 1/c`,
//!
//! ```text
//! φ_x' = v_x − k (d₃·v) sin θ,   φ_z' = v_z + k (d₃·v) cos θ,
//! δm_x' = Γ(1 − S)(φ_z sin θ + φ_x cos θ),     φ_x(0) = φ_z(0) = 0,  δm_x(0) = 1.
//! ```
//!
//! The planar state is critical where `f = δm_x(1) = 0`; the sign of `f` gives the parity of
//! the number of unstable out-of-plane modes (the count itself is in [`super::morse_index`]).
//! [`super::general_free_end_moments`] integrates the general (6-D, any stiffness)
//! linearization; the tests check it against Greenhill's column and lateral–torsional
//! buckling, and the reduced system above against it.
//!
//! The system grows like `e^{⅔√Γ}`; it is integrated with the continuous positive rescaling
//! `e^{−∫√(Γ(1−S))}`, which keeps the sign of `f`, and the reported stability function is
//! `f̂ = δm_x(1)/|(φ_x, φ_z, δm_x)(1)|`, which has the sign of `f`. It is integrated along
//! with the planar state ([`super::planar`]).

/// Right-hand side of the reduced out-of-plane system `(φ_x, φ_z, δm_x)` (design.md §1.2),
/// rescaled by `e^{−∫g}`.
#[allow(clippy::too_many_arguments)]
pub(super) fn out_of_plane_rhs(
    theta: f64,
    m_y: f64,
    n: f64,
    k: f64,
    g: f64,
    phi_x: f64,
    phi_z: f64,
    dm_x: f64,
) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    let vx = dm_x + phi_z * m_y;
    let vz = -phi_x * m_y;
    let d3v = st * vx - ct * vz;
    [
        vx - k * d3v * st - g * phi_x,
        vz + k * d3v * ct - g * phi_z,
        n * (phi_z * st + phi_x * ct) - g * dm_x,
    ]
}
