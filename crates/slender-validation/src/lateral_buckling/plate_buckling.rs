//! Linear buckling of the clamped Kirchhoff plate under its in-plane self-weight: the
//! master curve a converged shell must reach (design.md §1.3, last paragraph).
//!
//! Lengths are in units of `L`: the plate is `x ∈ [0, 1]`, `z ∈ [−a/2, a/2]`, `a = w/L`,
//! clamped at `x = 0`, free elsewhere, gravity along `−z` (in its plane).
//!
//! 1. **Pre-buckling membrane forces.** Plane-stress linear elasticity with membrane
//!    stiffness `A = Eh/(1−ν²)` under the body force `−ρgh e_z` per area:
//!    `Π = ½∫ A [ε_xx² + ε_zz² + 2ν ε_xx ε_zz + ½(1−ν) γ²] dA + ∫ ρgh U_z dA`, by Ritz with
//!    `U_x, U_z ∈ span{x P_m(2x−1) P_n(2z/a)}` (vanishing at the clamp). The membrane forces
//!    `N = ρghL · n(x, z)` are linear in the load and `n` depends only on `ν` and `a`.
//! 2. **Buckling.** The second variation for the out-of-plane deflection `u`,
//!    `Π₂ = ½∫ D [(u_xx + u_zz)² − 2(1−ν)(u_xx u_zz − u_xz²)] dA + ½∫ N_ij u_,i u_,j dA`.
//!    With `ρghL = Γ_shell D/L²` this is `K_b c = Γ (−K_g) c` in units `D = L = 1`; the
//!    smallest positive `Γ` is `Γ_shell,c`. Ritz basis `u ∈ span{x² P_m(2x−1) P_n(2z/a)}`,
//!    which enforces `u = u_x = 0` at the clamp.
//!
//! Bending and membrane stiffness are Kronecker sums of 1-D Legendre integrals; the
//! geometric stiffness is integrated with tensor Gauss rules exact for the polynomial
//! integrands. Ritz from above in the buckling basis, so `Γ_c` decreases as the buckling
//! basis grows; the membrane field converges in energy, with the clamp-corner stress
//! singularity as the slowest part.
//!
//! # Measured (ν = 0.35, default bases; tests in `tests/lateral_buckling_master_curve.rs`)
//!
//! | w/L | 0.01 | 0.05 | 0.1 | 0.2 | 0.3 | 0.5 | 0.75 | 1.0 |
//! |---|---|---|---|---|---|---|---|---|
//! | Γ_c plate | 13.833 | 14.273 | 14.871 | 16.194 | 17.650 | 20.809 | 24.991 | 29.148 |
//! | Vlasov, B = E w h³/12 | 13.827 | 14.239 | 14.789 | 15.977 | 17.251 | 19.953 | 23.485 | 27.077 |
//! | Vlasov, B = D w | 14.761 | 15.201 | 15.787 | 17.056 | 18.415 | 21.300 | 25.071 | 28.905 |
//!
//! The plate starts on the beam-stiffness edge of the Vlasov band (its narrow-strip limit
//! is `12.854 (1−ν) √(2(1+ν))`), crosses the band as `w/L` grows, and leaves it above the
//! plate-stiffness edge near `w/L ≈ 0.8` (+0.8 % at `w/L = 1`). Changing the basis by 8
//! orders moves `Γ_c` by < 1.3e-4; replacing the plane-stress prestress by beam statics moves
//! it by < 3e-5 up to `w/L = 0.2` and 0.22 % at `w/L = 1`.

use super::error::{check_poisson_ratio, check_positive_aspect_ratio, LateralBucklingError};
use super::generalized_eigen::largest_pencil_eigenvalue;
use super::legendre::{gauss_legendre, legendre_with_derivatives};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// Orders of a tensor Legendre basis: `P_m(2x−1)` for `m < along_length`, `P_n(2z/a)` for
/// `n < across_width`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TensorOrders {
    /// Number of Legendre polynomials along the length.
    pub along_length: usize,
    /// Number of Legendre polynomials across the width.
    pub across_width: usize,
}

/// The two Ritz bases of the plate computation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PlateDiscretization {
    /// Out-of-plane (buckling) basis `x² P_m P_n`.
    pub buckling: TensorOrders,
    /// In-plane (pre-buckling) basis `x P_m P_n`, for each of `U_x`, `U_z`.
    pub membrane: TensorOrders,
}

/// Smallest accepted order in each direction.
pub const ORDER_MIN: usize = 2;
/// Largest accepted order in each direction.
pub const ORDER_MAX: usize = 80;
/// Largest accepted number of unknowns of one Ritz problem (dense solves).
pub const UNKNOWNS_MAX: usize = 4000;

impl PlateDiscretization {
    /// Defaults that converge `Γ_c` to better than 0.1 % for `w/L ∈ [0.01, 2]` (measured
    /// against bases with 8–16 more polynomials per direction; the tests check < 0.5 %).
    /// Narrow strips need more polynomials along the length (the clamp layer has width
    /// `~w`), wide ones more across the width. The buckling load is insensitive to the
    /// membrane order (< 1e-6 relative beyond these), so the membrane basis is only
    /// slightly richer than the buckling basis.
    pub fn default_for(w_over_l: f64) -> Self {
        let along = if w_over_l >= 0.3 {
            24
        } else if w_over_l >= 0.1 {
            28
        } else if w_over_l >= 0.03 {
            40
        } else {
            60
        };
        let across = if w_over_l >= 1.0 {
            16
        } else if w_over_l >= 0.5 {
            12
        } else {
            8
        };
        Self {
            buckling: TensorOrders {
                along_length: along,
                across_width: across,
            },
            membrane: TensorOrders {
                along_length: along + 4,
                across_width: across + 2,
            },
        }
    }

    /// Both bases enlarged by `extra` polynomials in each direction (convergence studies).
    pub fn refined(&self, extra: usize) -> Self {
        let grow = |o: TensorOrders| TensorOrders {
            along_length: o.along_length + extra,
            across_width: o.across_width + extra,
        };
        Self {
            buckling: grow(self.buckling),
            membrane: grow(self.membrane),
        }
    }

    fn validate(&self) -> Result<(), LateralBucklingError> {
        let check = |name, value: usize| {
            if (ORDER_MIN..=ORDER_MAX).contains(&value) {
                Ok(())
            } else {
                Err(LateralBucklingError::InvalidSize {
                    name,
                    value,
                    min: ORDER_MIN,
                    max: ORDER_MAX,
                })
            }
        };
        check("buckling.along_length", self.buckling.along_length)?;
        check("buckling.across_width", self.buckling.across_width)?;
        check("membrane.along_length", self.membrane.along_length)?;
        check("membrane.across_width", self.membrane.across_width)?;
        let size = |name, value: usize| {
            if value <= UNKNOWNS_MAX {
                Ok(())
            } else {
                Err(LateralBucklingError::InvalidSize {
                    name,
                    value,
                    min: 1,
                    max: UNKNOWNS_MAX,
                })
            }
        };
        size(
            "buckling unknowns",
            self.buckling.along_length * self.buckling.across_width,
        )?;
        size(
            "membrane unknowns",
            2 * self.membrane.along_length * self.membrane.across_width,
        )
    }
}

/// Values and derivatives (with respect to the physical coordinate) of a 1-D basis at a
/// set of points: `d[k][q][m]` is the `k`-th derivative of function `m` at point `q`.
struct Table1d {
    d: [Vec<Vec<f64>>; 3],
}

/// Which clamp factor multiplies `P_m(2x − 1)` along the length.
#[derive(Clone, Copy)]
enum ClampFactor {
    /// No factor (the width direction): `P_n(2z/a)`.
    None,
    /// `x`: in-plane displacements vanish at the clamp.
    Linear,
    /// `x²`: deflection and slope vanish at the clamp.
    Quadratic,
}

/// Tabulates `c(x) P_m(t)` for `m < order` at reference points `t ∈ [−1, 1]`, with
/// derivatives in the physical coordinate (`d/dx = d/dt / half_length`). Along the length
/// `x = half_length (t + 1) ∈ [0, 1]` enters the clamp factor `c(x)`; across the width
/// (`ClampFactor::None`) only the scaling `z = half_length · t` matters.
fn tabulate(points: &[f64], order: usize, half_length: f64, factor: ClampFactor) -> Table1d {
    let mut d: [Vec<Vec<f64>>; 3] = Default::default();
    let inv = 1.0 / half_length;
    for &t in points {
        let [p, dp, ddp] = legendre_with_derivatives(order, t);
        let x = half_length * (t + 1.0); // used only by the clamp factors
        let (mut v0, mut v1, mut v2) = (vec![0.0; order], vec![0.0; order], vec![0.0; order]);
        for m in 0..order {
            let (p0, p1, p2) = (p[m], dp[m] * inv, ddp[m] * inv * inv);
            (v0[m], v1[m], v2[m]) = match factor {
                ClampFactor::None => (p0, p1, p2),
                ClampFactor::Linear => (x * p0, p0 + x * p1, 2.0 * p1 + x * p2),
                ClampFactor::Quadratic => (
                    x * x * p0,
                    2.0 * x * p0 + x * x * p1,
                    2.0 * p0 + 4.0 * x * p1 + x * x * p2,
                ),
            };
        }
        d[0].push(v0);
        d[1].push(v1);
        d[2].push(v2);
    }
    Table1d { d }
}

/// `∫ f^(a)_m f^(b)_n` over the interval from a table at Gauss points with weights
/// `weights` (already scaled to the physical interval).
fn gram(table: &Table1d, weights: &[f64], a: usize, b: usize) -> Mat<f64> {
    let n = table.d[0][0].len();
    Mat::from_fn(n, n, |i, j| {
        weights
            .iter()
            .enumerate()
            .map(|(q, w)| w * table.d[a][q][i] * table.d[b][q][j])
            .sum()
    })
}

/// `Σ_k c_k X_k ⊗ Z_k` with index `(m, n) ↦ m·N + n`.
fn kron_sum(terms: &[(f64, &Mat<f64>, &Mat<f64>)]) -> Mat<f64> {
    let (mx, nz) = (terms[0].1.nrows(), terms[0].2.nrows());
    Mat::from_fn(mx * nz, mx * nz, |i, j| {
        let (m, n, mp, np) = (i / nz, i % nz, j / nz, j % nz);
        terms
            .iter()
            .map(|(c, x, z)| c * x[(m, mp)] * z[(n, np)])
            .sum()
    })
}

/// Gauss rule on `[0, length]` (or `[−length/2, length/2]`; only the weights are scaled):
/// reference nodes `t` and physical weights.
fn rule(points: usize, length: f64) -> (Vec<f64>, Vec<f64>) {
    let (t, w) = gauss_legendre(points);
    (t, w.iter().map(|w| 0.5 * length * w).collect())
}

/// The pre-buckling membrane state: Ritz coefficients of `U_x`, `U_z` for unit load
/// `ρgh = 1`, unit membrane stiffness `Eh/(1−ν²) = 1` and `L = 1`.
#[derive(Clone, Debug)]
pub struct MembraneSolution {
    /// Aspect ratio `a = w/L`.
    pub w_over_l: f64,
    /// Poisson's ratio.
    pub nu: f64,
    /// Basis orders.
    pub orders: TensorOrders,
    /// Coefficients of `U_x` (index `m·N + n`).
    pub ux: Vec<f64>,
    /// Coefficients of `U_z`.
    pub uz: Vec<f64>,
}

impl MembraneSolution {
    /// Membrane forces `[n_xx, n_xz, n_zz]` in units of `ρghL` at points `(x, z)`
    /// (`x ∈ [0, 1]`, `z ∈ [−a/2, a/2]`) given as separate x and z coordinate lists; the
    /// result is indexed `[ix · nz + iz]`.
    pub fn forces_on_grid(&self, xs: &[f64], zs: &[f64]) -> Vec<[f64; 3]> {
        let a = self.w_over_l;
        let tx: Vec<f64> = xs.iter().map(|x| 2.0 * x - 1.0).collect();
        let tz: Vec<f64> = zs.iter().map(|z| 2.0 * z / a).collect();
        let fx = tabulate(&tx, self.orders.along_length, 0.5, ClampFactor::Linear);
        let hz = tabulate(&tz, self.orders.across_width, 0.5 * a, ClampFactor::None);
        self.forces_from_tables(&fx, &hz)
    }

    fn forces_from_tables(&self, fx: &Table1d, hz: &Table1d) -> Vec<[f64; 3]> {
        let (mx, nz) = (self.orders.along_length, self.orders.across_width);
        let nu = self.nu;
        let (qx, qz) = (fx.d[0].len(), hz.d[0].len());
        let mut out = Vec::with_capacity(qx * qz);
        // Partial sums over m first: U(x, ·) coefficients in the width basis.
        for ix in 0..qx {
            let mut ux0 = vec![0.0; nz]; // Σ_m cx f_m
            let mut ux1 = vec![0.0; nz]; // Σ_m cx f'_m
            let mut uz0 = vec![0.0; nz];
            let mut uz1 = vec![0.0; nz];
            for m in 0..mx {
                let (f0, f1) = (fx.d[0][ix][m], fx.d[1][ix][m]);
                for n in 0..nz {
                    let i = m * nz + n;
                    ux0[n] += self.ux[i] * f0;
                    ux1[n] += self.ux[i] * f1;
                    uz0[n] += self.uz[i] * f0;
                    uz1[n] += self.uz[i] * f1;
                }
            }
            for iz in 0..qz {
                let (mut exx, mut ezz, mut gam) = (0.0, 0.0, 0.0);
                for n in 0..nz {
                    let (h0, h1) = (hz.d[0][iz][n], hz.d[1][iz][n]);
                    exx += ux1[n] * h0;
                    ezz += uz0[n] * h1;
                    gam += ux0[n] * h1 + uz1[n] * h0;
                }
                out.push([exx + nu * ezz, 0.5 * (1.0 - nu) * gam, ezz + nu * exx]);
            }
        }
        out
    }
}

/// Solves the plane-stress pre-buckling problem by Ritz (see the module docs).
pub fn solve_membrane(
    w_over_l: f64,
    nu: f64,
    orders: TensorOrders,
) -> Result<MembraneSolution, LateralBucklingError> {
    check_positive_aspect_ratio(w_over_l)?;
    check_poisson_ratio(nu)?;
    PlateDiscretization {
        buckling: orders,
        membrane: orders,
    }
    .validate()?;
    let (mx, nz) = (orders.along_length, orders.across_width);
    let a = w_over_l;
    // 1-D Gram matrices, exact (degree ≤ 2·order in each direction).
    let (tx, wx) = rule(mx + 2, 1.0);
    let (tz, wz) = rule(nz + 2, a);
    let fx = tabulate(&tx, mx, 0.5, ClampFactor::Linear);
    let hz = tabulate(&tz, nz, 0.5 * a, ClampFactor::None);
    let (x00, x11, x10, x01) = (
        gram(&fx, &wx, 0, 0),
        gram(&fx, &wx, 1, 1),
        gram(&fx, &wx, 1, 0),
        gram(&fx, &wx, 0, 1),
    );
    let (z00, z11, z10, z01) = (
        gram(&hz, &wz, 0, 0),
        gram(&hz, &wz, 1, 1),
        gram(&hz, &wz, 1, 0),
        gram(&hz, &wz, 0, 1),
    );
    let c = 0.5 * (1.0 - nu);
    let kxx = kron_sum(&[(1.0, &x11, &z00), (c, &x00, &z11)]);
    let kzz = kron_sum(&[(1.0, &x00, &z11), (c, &x11, &z00)]);
    let kxz = kron_sum(&[(nu, &x10, &z01), (c, &x01, &z10)]);
    let n1 = mx * nz;
    let k = Mat::from_fn(2 * n1, 2 * n1, |i, j| match (i < n1, j < n1) {
        (true, true) => kxx[(i, j)],
        (false, false) => kzz[(i - n1, j - n1)],
        (true, false) => kxz[(i, j - n1)],
        (false, true) => kxz[(j, i - n1)],
    });
    // Load: body force −1 along z: F_z = −∫ f_m h_n.
    let fint: Vec<f64> = (0..mx)
        .map(|m| (0..wx.len()).map(|q| wx[q] * fx.d[0][q][m]).sum())
        .collect();
    let hint: Vec<f64> = (0..nz)
        .map(|n| (0..wz.len()).map(|q| wz[q] * hz.d[0][q][n]).sum())
        .collect();
    let mut rhs = Mat::<f64>::zeros(2 * n1, 1);
    for m in 0..mx {
        for n in 0..nz {
            rhs[(n1 + m * nz + n, 0)] = -fint[m] * hint[n];
        }
    }
    let llt = k
        .llt(Side::Lower)
        .map_err(|_| LateralBucklingError::Pencil {
            method: "plate membrane Ritz",
            source: super::generalized_eigen::PencilError::NotPositiveDefinite,
        })?;
    llt.solve_in_place(rhs.as_mut());
    Ok(MembraneSolution {
        w_over_l,
        nu,
        orders,
        ux: (0..n1).map(|i| rhs[(i, 0)]).collect(),
        uz: (0..n1).map(|i| rhs[(n1 + i, 0)]).collect(),
    })
}

/// Critical `Γ_shell = ρhgL³/D` of the clamped Kirchhoff plate under in-plane self-weight,
/// for aspect ratio `w_over_l > 0` and Poisson's ratio `nu ∈ (−1, 0.5)` with the given
/// bases ([`super::master_curve::critical_gamma`] picks converged defaults).
pub fn plate_critical_gamma(
    w_over_l: f64,
    nu: f64,
    disc: &PlateDiscretization,
) -> Result<f64, LateralBucklingError> {
    check_positive_aspect_ratio(w_over_l)?;
    check_poisson_ratio(nu)?;
    disc.validate()?;
    let membrane = solve_membrane(w_over_l, nu, disc.membrane)?;
    buckling_multiplier(w_over_l, nu, disc.buckling, disc.membrane, |xs, zs| {
        membrane.forces_on_grid(xs, zs)
    })
}

/// Smallest positive multiplier `Γ` of a prescribed membrane force field `n(x, z)` at
/// which the clamped plate (`D = L = 1`, width `w_over_l`) buckles out of plane:
/// `K_b c = Γ (−K_g[n]) c`.
///
/// `forces(xs, zs)` returns `[n_xx, n_xz, n_zz]` (tension positive) on the grid `xs × zs`,
/// indexed `[ix · zs.len() + iz]`. `field_orders` bounds the polynomial degree of the field
/// (`< along_length` in x, `< across_width` in z) so that the Gauss rules integrate the
/// geometric stiffness exactly; the self-weight field passes its membrane basis orders.
pub fn buckling_multiplier<F>(
    w_over_l: f64,
    nu: f64,
    buckling: TensorOrders,
    field_orders: TensorOrders,
    forces: F,
) -> Result<f64, LateralBucklingError>
where
    F: Fn(&[f64], &[f64]) -> Vec<[f64; 3]>,
{
    check_positive_aspect_ratio(w_over_l)?;
    check_poisson_ratio(nu)?;
    PlateDiscretization {
        buckling,
        membrane: field_orders,
    }
    .validate()?;
    let a = w_over_l;
    let (mb, nb) = (buckling.along_length, buckling.across_width);
    let (mm, nm) = (field_orders.along_length, field_orders.across_width);

    // Bending stiffness (D = 1): u_xx² + u_zz² + 2ν u_xx u_zz + 2(1−ν) u_xz².
    let (tx, wx) = rule(mb + 3, 1.0);
    let (tz, wz) = rule(nb + 2, a);
    let gx = tabulate(&tx, mb, 0.5, ClampFactor::Quadratic);
    let hz = tabulate(&tz, nb, 0.5 * a, ClampFactor::None);
    let g = |p, q| gram(&gx, &wx, p, q);
    let y = |p, q| gram(&hz, &wz, p, q);
    let (g22, g00, g20, g02, g11) = (g(2, 2), g(0, 0), g(2, 0), g(0, 2), g(1, 1));
    let (y22, y00, y20, y02, y11) = (y(2, 2), y(0, 0), y(2, 0), y(0, 2), y(1, 1));
    let kb = kron_sum(&[
        (1.0, &g22, &y00),
        (1.0, &g00, &y22),
        (nu, &g20, &y02),
        (nu, &g02, &y20),
        (2.0 * (1.0 - nu), &g11, &y11),
    ]);

    // Geometric stiffness: integrand degree ≤ 2(mb+1) + mm along x and ≤ 2nb − 2 + nm
    // across, so these Gauss rules are exact.
    let (tx, wx) = rule(mb + mm / 2 + 2, 1.0);
    let (tz, wz) = rule(nb + nm / 2 + 1, a);
    let gx = tabulate(&tx, mb, 0.5, ClampFactor::Quadratic);
    let hz = tabulate(&tz, nb, 0.5 * a, ClampFactor::None);
    let xs: Vec<f64> = tx.iter().map(|t| 0.5 * (t + 1.0)).collect();
    let zs: Vec<f64> = tz.iter().map(|t| 0.5 * a * t).collect();
    let field = forces(&xs, &zs);
    let (qx, qz) = (tx.len(), tz.len());
    let nq = qx * qz;
    if field.len() != nq {
        return Err(LateralBucklingError::InvalidSize {
            name: "forces(xs, zs).len()",
            value: field.len(),
            min: nq,
            max: nq,
        });
    }
    let nd = mb * nb;
    // Rows q: u_,x of each basis function; rows nq + q: u_,z.
    let grad = Mat::from_fn(2 * nq, nd, |r, i| {
        let (m, n) = (i / nb, i % nb);
        let q = r % nq;
        let (ix, iz) = (q / qz, q % qz);
        if r < nq {
            gx.d[1][ix][m] * hz.d[0][iz][n]
        } else {
            gx.d[0][ix][m] * hz.d[1][iz][n]
        }
    });
    // Weighted −n·∇u (minus sign: G = −K_g).
    let weighted = Mat::from_fn(2 * nq, nd, |r, i| {
        let q = r % nq;
        let (ix, iz) = (q / qz, q % qz);
        let w = wx[ix] * wz[iz];
        let [nxx, nxz, nzz] = field[q];
        let (ux, uz) = (grad[(q, i)], grad[(nq + q, i)]);
        if r < nq {
            -w * (nxx * ux + nxz * uz)
        } else {
            -w * (nxz * ux + nzz * uz)
        }
    });
    let g_minus_kg = grad.transpose() * &weighted;
    let theta = largest_pencil_eigenvalue(&kb, &g_minus_kg).map_err(|source| {
        LateralBucklingError::Pencil {
            method: "plate buckling Ritz",
            source,
        }
    })?;
    Ok(1.0 / theta)
}
