//! The bend–twist master curve (design.md §1.2): self-tests of the linearization against
//! classical buckling loads, limits, the structure of the planar branch, the threshold `Y*`,
//! continuity, convergence of the numerics, bad input, and the cross-check against the
//! discrete rod model (DER, slender-core).
//!
//! Run with `cargo test -p slender-validation --release --test integration bend_twist_master_curve::`
//! (add `-- --nocapture` for the tables).

use slender_core::geometry::Vec3;
use slender_core::rod::{
    Grading, RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness,
};
use slender_core::solver::{EquilibriumSolver, Solution, SolverParams};
use slender_validation::bend_twist::master_curve::{
    critical_boundaries, critical_boundaries_with, general_free_end_moments, planar_branch,
    planar_equilibrium, planar_stable, stability_function, threshold_y, tongue_tip, BendTwistError,
    EventKind, GeneralBase, Settings, GAMMA_MAX, Y_MAX, Y_MIN,
};
use std::f64::consts::PI;
use std::time::Instant;

/// Ω_rod: GJ/EI = 0.77.
const C: f64 = 0.77;

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// Root of `f` on `[lo, hi]` by bisection (`f(lo)`, `f(hi)` of opposite signs).
fn bisect(mut f: impl FnMut(f64) -> f64, mut lo: f64, mut hi: f64, rel_tol: f64) -> f64 {
    let mut f_lo = f(lo);
    assert!(
        f_lo.signum() != f(hi).signum(),
        "no sign change on [{lo}, {hi}]"
    );
    while hi - lo > rel_tol * hi.abs() {
        let mid = 0.5 * (lo + hi);
        let fm = f(mid);
        if fm.signum() == f_lo.signum() {
            lo = mid;
            f_lo = fm;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

// ---------------------------------------------------------------------------------------
// The linearization against classical results
// ---------------------------------------------------------------------------------------

/// Greenhill's heavy column: an upright column clamped at its foot buckles under its own
/// weight at ρgAL³/EI = 7.8373 (= (3/2 · j)², j = 1.86635 the first zero of J_{−1/3}). Here
/// the rod points down from the clamp and gravity is reversed (Γ < 0), which is the same
/// problem. Both planes (the x column is out-of-plane, the y column in-plane) buckle there,
/// whatever the torsion ratio.
#[test]
fn general_linearization_reproduces_greenhill() {
    const GREENHILL: f64 = 7.837_347;
    for c in [0.5, 0.77, 1.0] {
        for (column, component) in [(0, 0), (1, 1)] {
            let entry = |g: f64| {
                general_free_end_moments(&GeneralBase {
                    theta0: 0.0,
                    clamp_moment: 0.0,
                    natural_curvature: 0.0,
                    gamma: -g,
                    stiffness: [1.0, 1.0, c],
                })
                .unwrap()[column][component]
            };
            let g = bisect(entry, 6.0, 9.0, 1e-12);
            assert!(rel(g, GREENHILL) < 1e-6, "c = {c}, column {column}: {g}");
        }
    }
}

/// Lateral–torsional buckling of a cantilever under its distributed weight at the centroid
/// (Timoshenko & Gere; design.md §1.3): λ = qL³/√(B·GJ) = 12.8538, with the in-plane
/// bending frozen (K₁ = ∞), a horizontal clamp (θ = π/2) and the in-plane moment
/// m_y = Γ(1 − S)²/2 from the base-state equations.
#[test]
fn general_linearization_reproduces_lateral_torsional_buckling() {
    const LAMBDA_C: f64 = 12.8538;
    for gj in [0.3, 1.0, 4.0] {
        let det = |g: f64| {
            // Out-of-plane block (x, z): δm_z is conserved, so its determinant is the x entry.
            general_free_end_moments(&GeneralBase {
                theta0: PI / 2.0,
                clamp_moment: 0.5 * g,
                natural_curvature: 0.0,
                gamma: g,
                stiffness: [f64::INFINITY, 1.0, gj],
            })
            .unwrap()[0][0]
        };
        let g = bisect(det, 8.0 * gj.sqrt(), 16.0 * gj.sqrt(), 1e-12);
        let lambda = g / gj.sqrt();
        assert!(rel(lambda, LAMBDA_C) < 1e-5, "GJ = {gj}: λ = {lambda}");
    }
}

/// The reduced 3-D out-of-plane system of the master curve against the general 6-D
/// linearization about the same planar equilibrium (isotropic, c = 0.77): the in-plane and
/// out-of-plane parts decouple, the signs agree, and the out-of-plane critical X is the
/// same (Y = 1.5, Γ ≈ 27 at X_c1, where the general system needs no rescaling).
#[test]
fn reduced_system_matches_the_general_linearization() {
    let y = 1.5;
    let general = |x: f64| {
        let eq = planar_equilibrium(x, y, C).unwrap();
        let m = general_free_end_moments(&GeneralBase {
            theta0: 0.0,
            clamp_moment: eq.clamp_moment,
            natural_curvature: 2.0 * PI * y,
            gamma: eq.gamma,
            stiffness: [1.0, 1.0, C],
        })
        .unwrap();
        (m, eq.stability_function)
    };
    let xc1 = critical_boundaries(y, C).unwrap().lower.unwrap();
    for x in [0.2, 0.3, 0.98 * xc1, 1.02 * xc1, 0.4] {
        let (m, f) = general(x);
        // Decoupling: the y column has no x, z components and the x, z columns no y one.
        let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(m[0][1].abs() < 1e-9 * scale && m[2][1].abs() < 1e-9 * scale);
        assert!(m[1][0].abs() < 1e-9 * scale && m[1][2].abs() < 1e-9 * scale);
        // δm_z is conserved: the z column keeps δm_z = 1, the x column δm_z = 0.
        assert!((m[2][2] - 1.0).abs() < 1e-9 && m[0][2].abs() < 1e-9 * scale);
        assert_eq!(m[0][0] > 0.0, f > 0.0, "X = {x}: {} vs f̂ = {f}", m[0][0]);
    }
    let x_general = bisect(|x| general(x).0[0][0], 0.98 * xc1, 1.02 * xc1, 1e-10);
    assert!(
        rel(x_general, xc1) < 1e-7,
        "general {x_general} vs reduced {xc1}"
    );
}

// ---------------------------------------------------------------------------------------
// Limits and sign conventions
// ---------------------------------------------------------------------------------------

/// Γ → 0: the stress-free coil θ = 2πY·S (clamp curvature and tip angle 2πY). Γ → ∞: the rod
/// hangs straight with a linear tip layer θ ≈ A·Ai((1 − S)Γ^{1/3}), tip angle
/// Ai(0)/|Ai'(0)|/X = 1.3717/X.
#[test]
fn planar_equilibrium_limits() {
    for y in [0.5, 1.0, 3.0] {
        let eq = planar_equilibrium(1e-3, y, C).unwrap();
        let k = 2.0 * PI * y;
        assert!(rel(eq.clamp_curvature, k) < 1e-4, "{eq:?}");
        assert!(rel(eq.tip_angle, k) < 1e-4, "{eq:?}");
        assert!(eq.stability_function > 0.0 && eq.index == (0, 0));
    }
    for (x, y) in [(20.0, 1.0), (10.0, 3.0)] {
        let eq = planar_equilibrium(x, y, C).unwrap();
        let airy = 0.355_028_053_887_817_2 / 0.258_819_403_792_806_8;
        assert!(rel(eq.tip_angle * x, airy) < 2e-3, "{eq:?}");
        // The straight part carries the moment 2πY that keeps it straight.
        assert!(rel(eq.clamp_moment, 2.0 * PI * y) < 1e-12);
        assert!(eq.ln_clamp_curvature < -100.0 && eq.index == (0, 0));
    }
}

/// Below Y* (less than about one turn) the planar equilibrium is stable for every X.
#[test]
fn small_y_is_always_planar() {
    for y in [Y_MIN, 0.1, 0.3, 0.5, 0.75, 0.9] {
        let b = critical_boundaries(y, C).unwrap();
        assert_eq!((b.lower, b.upper), (None, None), "Y = {y}");
        for x in [1e-3, 0.1, 0.3, 0.45, 0.6, 1.0, 10.0, 1e3] {
            assert!(planar_stable(x, y, C).unwrap(), "X = {x}, Y = {y}");
        }
    }
}

/// X → 0 (stress-free coil) and X → ∞ (hanging rod) are stable; just inside the window the
/// planar state is unstable with one out-of-plane mode and f̂ < 0.
#[test]
fn small_and_large_x_are_stable() {
    for y in [1.0, 2.0, 5.0, 10.0] {
        let b = critical_boundaries(y, C).unwrap();
        let (lo, hi) = (b.lower.unwrap(), b.upper.unwrap());
        for x in [1e-4, 1e-2, 0.9 * lo, 1.1 * hi, 2.0, 100.0, 1e6] {
            assert!(planar_stable(x, y, C).unwrap(), "X = {x}, Y = {y}");
        }
        for x in [1.001 * lo, 0.5 * (lo + hi), 0.999 * hi] {
            assert!(!planar_stable(x, y, C).unwrap(), "X = {x}, Y = {y}");
        }
        assert!(stability_function(1e-3, y, C).unwrap() > 0.0);
        let eq = planar_equilibrium(1.001 * lo, y, C).unwrap();
        assert!(eq.stability_function < 0.0 && eq.index == (0, 1), "{eq:?}");
    }
}

// ---------------------------------------------------------------------------------------
// The boundaries
// ---------------------------------------------------------------------------------------

/// The table of the report, with timings; X_c1 < X_c2 wherever both exist, and both exist
/// exactly above Y*.
#[test]
fn boundaries_table() {
    let y_star = threshold_y(C).unwrap();
    println!("Y* = {y_star:.8} (c = {C})");
    println!("    Y      X_c1          X_c2        first call");
    for y in [0.1, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0] {
        let t0 = Instant::now();
        let b = critical_boundaries_with(y, C, &Settings::default()).unwrap();
        let elapsed = t0.elapsed();
        println!(
            "{y:6.2}  {:>12}  {:>12}  {elapsed:>10.1?}",
            b.lower.map_or("-".into(), |v| format!("{v:.8}")),
            b.upper.map_or("-".into(), |v| format!("{v:.8}")),
        );
        assert_eq!(b.lower.is_some(), y > y_star, "Y = {y}");
        assert_eq!(b.lower.is_some(), b.upper.is_some());
        if let (Some(l), Some(u)) = (b.lower, b.upper) {
            assert!(l < u, "Y = {y}: {l} >= {u}");
        }
    }
    // Memoized: a repeated call is a lookup.
    critical_boundaries(10.0, C).unwrap();
    let t0 = Instant::now();
    for _ in 0..1000 {
        planar_stable(0.3, 10.0, C).unwrap();
    }
    println!("memoized planar_stable: {:?} per call", t0.elapsed() / 1000);
}

/// Y* lies a little below one turn for ν = 0.3 (design.md), and the window closes there:
/// none just below, a narrow one around the tip X* just above.
#[test]
fn threshold_is_the_tip_of_the_tongue() {
    let (y_star, x_star) = tongue_tip(C).unwrap();
    assert!(y_star > 0.5 && y_star < 1.0, "Y* = {y_star}");
    let below = critical_boundaries(y_star * (1.0 - 1e-4), C).unwrap();
    assert_eq!((below.lower, below.upper), (None, None));
    let above = critical_boundaries(y_star * (1.0 + 1e-4), C).unwrap();
    let (l, u) = (above.lower.unwrap(), above.upper.unwrap());
    assert!(l < x_star && x_star < u && rel(l, x_star) < 0.02 && rel(u, x_star) < 0.02);
    // Cheaper twisting destabilizes: Y* increases with c.
    assert!(threshold_y(0.5).unwrap() < y_star && y_star < threshold_y(1.0).unwrap());
}

/// On a fine grid in Y above Y*, X_c1 decreases and X_c2 increases (to its large-Y limit,
/// which it reaches to 1e-8 by Y ≈ 3: the unstable mode lives in the tip curl), without
/// jumps: neighbours (ΔY/Y ≈ 5 %) differ by less than 6 % in X. Near the tip the window
/// opens like a square root, (X_c2 − X_c1)² ∝ Y − Y*.
#[test]
fn boundaries_are_continuous_in_y() {
    let (y_star, x_star) = tongue_tip(C).unwrap();
    let ys: Vec<f64> = (0..40)
        .map(|k| 1.1 * y_star * (10.0 / (1.1 * y_star)).powf(k as f64 / 39.0))
        .collect();
    let b: Vec<(f64, f64)> = ys
        .iter()
        .map(|&y| {
            let b = critical_boundaries(y, C).unwrap();
            (b.lower.unwrap(), b.upper.unwrap())
        })
        .collect();
    for w in b.windows(2) {
        let ((l0, u0), (l1, u1)) = (w[0], w[1]);
        assert!(l1 < l0 && rel(l1, l0) < 0.06, "{w:?}");
        assert!(u1 > u0 - 1e-8 && rel(u1, u0) < 0.06, "{w:?}");
    }
    let limit = b.last().unwrap().1;
    for (y, (_, u)) in ys.iter().zip(&b) {
        if *y > 3.0 {
            assert!(rel(*u, limit) < 1e-8, "Y = {y}: {u} vs {limit}");
        }
    }
    // Square-root opening at the tip, centred on X*.
    let ratio: Vec<f64> = [1e-5, 1e-4, 1e-3]
        .iter()
        .map(|&d| {
            let b = critical_boundaries(y_star * (1.0 + d), C).unwrap();
            let (l, u) = (b.lower.unwrap(), b.upper.unwrap());
            assert!(rel(0.5 * (l + u), x_star) < 0.02 * d.sqrt().max(1e-3));
            (u - l).powi(2) / (y_star * d)
        })
        .collect();
    assert!(
        rel(ratio[0], ratio[1]) < 0.05 && rel(ratio[1], ratio[2]) < 0.05,
        "{ratio:?}"
    );
}

/// Halving the integration tolerance moves the boundaries by < 1e-6 relative (observed
/// ~1e-10).
#[test]
fn numerics_converge_when_the_tolerance_is_halved() {
    for y in [1.0, 3.0, 10.0] {
        let a = critical_boundaries_with(y, C, &Settings { rtol: 1e-10 }).unwrap();
        let b = critical_boundaries_with(y, C, &Settings { rtol: 5e-11 }).unwrap();
        for (p, q) in [(a.lower, b.lower), (a.upper, b.upper)] {
            let (p, q) = (p.unwrap(), q.unwrap());
            assert!(rel(p, q) < 1e-6, "Y = {y}: {p} vs {q}");
        }
    }
}

/// A full trace of the planar branch with its Morse index (which the trace checks against
/// the signs of f̂ and of the in-plane derivative at every point): the index rises from 0 at
/// X_c1 and returns to 0 at X_c2, every in-plane fold and every other change lies inside the
/// window, and nothing happens above it (traced beyond the start of the walk down, X = 1.2).
#[test]
fn the_branch_has_one_unstable_window() {
    for (y, c) in [(1.5, C), (3.0, C), (2.0, 0.5)] {
        let b = critical_boundaries(y, c).unwrap();
        let (lo, hi) = (b.lower.unwrap(), b.upper.unwrap());
        let branch = planar_branch(y, c, 1.5, &Settings::default()).unwrap();
        assert_eq!(branch.stable_stretches(), 2, "{branch:?}");
        assert_eq!(branch.final_index, (0, 0));
        let first = branch.events.first().unwrap();
        let last = branch.events.last().unwrap();
        assert_eq!(first.kind, EventKind::OutOfPlane);
        assert_eq!(last.kind, EventKind::OutOfPlane);
        assert_eq!((first.index_before, first.index_after), ((0, 0), (0, 1)));
        assert_eq!((last.index_before, last.index_after), ((0, 1), (0, 0)));
        // Events located at the walking tolerance (1e-8).
        assert!(
            rel(first.x, lo) < 1e-6 && rel(last.x, hi) < 1e-6,
            "{branch:?}"
        );
        for e in &branch.events {
            assert!(
                e.x >= lo * (1.0 - 1e-6) && e.x <= hi * (1.0 + 1e-6),
                "{e:?}"
            );
        }
        let folds = branch
            .events
            .iter()
            .filter(|e| e.kind == EventKind::InPlaneFold)
            .count();
        println!(
            "Y = {y}, c = {c}: {} events ({folds} in-plane folds), max index {:?}",
            branch.events.len(),
            branch
                .events
                .iter()
                .map(|e| e.index_after.0 + e.index_after.1)
                .max()
        );
    }
}

#[test]
fn invalid_input_is_rejected_with_the_field_name() {
    let name = |r: Result<f64, BendTwistError>| match r {
        Err(BendTwistError::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid-parameter error, got {other:?}"),
    };
    assert_eq!(name(stability_function(f64::NAN, 1.0, C)), "x");
    assert_eq!(name(stability_function(-1.0, 1.0, C)), "x");
    assert_eq!(name(stability_function(1e9, 1.0, C)), "x");
    assert_eq!(name(stability_function(0.3, 0.0, C)), "y");
    assert_eq!(name(stability_function(0.3, Y_MAX * 2.0, C)), "y");
    assert_eq!(name(stability_function(0.3, f64::INFINITY, C)), "y");
    assert_eq!(name(stability_function(0.3, 1.0, 0.0)), "c");
    assert_eq!(name(stability_function(0.3, 1.0, 2.0)), "c");
    assert_eq!(name(threshold_y(f64::NAN)), "c");
    assert_eq!(name(planar_stable(0.0, 1.0, C).map(f64::from)), "x");
    assert_eq!(name(planar_stable(0.3, -1.0, C).map(f64::from)), "y");
    for r in [
        critical_boundaries(f64::NAN, C),
        critical_boundaries(1.0, 1.5),
        critical_boundaries_with(1.0, C, &Settings { rtol: 0.0 }),
    ] {
        assert!(
            matches!(r, Err(BendTwistError::InvalidParameter { .. })),
            "{r:?}"
        );
    }
    let msg = stability_function(0.3, 1.0, 2.0).unwrap_err().to_string();
    assert!(msg.contains("c = 2") && msg.contains("[0.5, 1]"), "{msg}");
    // Large X is fine for the classification, limited by Γ for the stability function.
    assert!(planar_stable(1e12, 1.0, C).unwrap());
    let x_max = GAMMA_MAX.cbrt() / (2.0 * PI);
    assert!(stability_function(0.9 * x_max, 1.0, C).is_ok());
    let bad = general_free_end_moments(&GeneralBase {
        theta0: 0.0,
        clamp_moment: 0.0,
        natural_curvature: 0.0,
        gamma: 1.0,
        stiffness: [1.0, 0.0, 1.0],
    });
    assert!(matches!(
        bad,
        Err(BendTwistError::InvalidParameter {
            name: "stiffness[1]",
            ..
        })
    ));
}

// ---------------------------------------------------------------------------------------
// Cross-check with the discrete rod model
// ---------------------------------------------------------------------------------------

/// Ω_rod section with ρA = 1, EI = 1, L = 1, so that gravity g = Γ.
fn omega_rod() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(1.6e7, 1.0, C),
        linear_density: 1.0,
    }
}

/// The benchmark rod: a circle of radius R = L/(2πY) in the xz plane, clamped at the top
/// with its tangent along gravity, m₁ in the plane of the coil, `n` uniform elements.
fn coil(y: f64, gamma: f64, n: usize) -> Rod {
    RodBuilder::new(
        RestCurve::Circle {
            start: [0.0; 3],
            tangent: [0.0, 0.0, -1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 1.0 / (2.0 * PI * y),
            length: 1.0,
        },
        omega_rod(),
    )
    .elements(n)
    .grading(Grading::Uniform)
    .first_director(Vec3::x())
    .clamp_start()
    .gravity(Vec3::new(0.0, 0.0, -gamma))
    .build()
    .unwrap()
}

/// The rest state of a straight rod hanging from the same clamp (same clamp frame and m₁),
/// used as the start of Newton for the hanging branch.
fn hanging_start(n: usize) -> RodState {
    RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [0.0, 0.0, -1.0],
            length: 1.0,
        },
        omega_rod(),
    )
    .elements(n)
    .grading(Grading::Uniform)
    .first_director(Vec3::x())
    .clamp_start()
    .build()
    .unwrap()
    .rest_state()
    .clone()
}

/// Whether a converged discrete equilibrium is planar and unstable out of plane. Panics if
/// it did not converge, is not planar, or is not on the master curve's branch (tip angle
/// `ode_tip` within 0.1 rad): the cross-check is only meaningful on the same planar branch.
fn unstable_out_of_plane(sol: &Solution<RodState>, ode_tip: f64, what: &str) -> bool {
    assert!(sol.report.converged(), "{what}: {:?}", sol.report.status);
    let p = sol.state.positions();
    let max_y = p.iter().fold(0.0f64, |m, p| m.max(p.y.abs()));
    assert!(max_y < 1e-9, "{what}: not planar (max |y| = {max_y:e})");
    let e = p[p.len() - 1] - p[p.len() - 2];
    let tip = e.x.atan2(-e.z);
    let gap = (tip - ode_tip + PI).rem_euclid(2.0 * PI) - PI;
    assert!(
        gap.abs() < 0.1,
        "{what}: tip angle {tip} vs {ode_tip} (mod 2π)"
    );
    let negative = sol.report.inertia.expect("inertia").negative;
    if negative == 0 {
        return false;
    }
    // Free DOFs [θ⁰, x₁(3), θ¹, x₂(3), …]: about a planar state an out-of-plane mode moves
    // along y (and twists), an in-plane one only along x, z. Only the lowest mode is known;
    // near X_c1 and X_c2 no in-plane mode is unstable (the folds lie inside the window),
    // which this checks.
    let mode = &sol.lowest_mode.as_ref().expect("lowest mode").shape;
    let (mut along_y, mut in_plane) = (0.0, 0.0);
    for (i, v) in mode.iter().enumerate() {
        match i % 4 {
            2 => along_y += v * v,
            1 | 3 => in_plane += v * v,
            _ => {}
        }
    }
    assert!(
        along_y > 1e6 * in_plane,
        "{what}: the unstable mode is not out-of-plane ({negative} negative)"
    );
    true
}

/// Tip angle of the master curve's planar state at `(x, y)`.
fn ode_tip(x: f64, y: f64) -> f64 {
    planar_equilibrium(x, y, C).unwrap().tip_angle
}

/// Critical X of the discrete model by bisection on the out-of-plane instability, bracketed
/// by ±6 % around the master curve, to 2e-5 relative.
fn discrete_bisection(x_ode: f64, mut unstable: impl FnMut(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (0.94 * x_ode, 1.06 * x_ode);
    let u_lo = unstable(lo);
    assert_ne!(
        u_lo,
        unstable(hi),
        "no change of stability within ±6 % of {x_ode}"
    );
    while hi / lo - 1.0 > 2e-5 {
        let mid = (lo * hi).sqrt();
        if unstable(mid) == u_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo * hi).sqrt()
}

/// The acceptance test of the benchmark: the ODE master curve and the discrete inertia
/// bisection agree within 1 % in X at no fewer than five values of Y across [0.1, 10].
///
/// Slow-ish (~10–20 s in release: DER with n = 100·Y elements, up to 1000, ~100 planar
/// solves). Both boundaries are checked at six values of Y in [1, 10], and the absence of
/// any instability at Y = 0.1 and 0.5 (below Y*).
///
/// * Lower boundary X_c1: gravity is ramped from 0 (the stress-free coil), which follows the
///   coil branch; below the first fold it is the only planar branch.
/// * Upper boundary X_c2: ramping up from the coil would cross the window, where the planar
///   branch folds (snaps) and Newton drifts off the symmetric states. Instead the rod is
///   "pre-hung": Newton starts from a straight rod hanging from the same clamp, at X = 0.8
///   (above every X_c2 for c = 0.77, and low enough that the clamp strain Γ/EA stays < 1 %),
///   which lands on the stable hanging branch; each probe then ramps gravity down from
///   there, through stable hanging states only.
#[test]
fn discrete_rod_agrees_with_the_master_curve() {
    let t0 = Instant::now();
    let mut compared = Vec::new();
    println!("   Y  boundary   X (ODE)     X (DER)    rel. diff   n");
    for y in [1.0f64, 1.5, 2.0, 3.0, 5.0, 10.0] {
        let n = ((100.0 * y).round() as usize).max(50);
        let b = critical_boundaries(y, C).unwrap();
        let gamma = |x: f64| (2.0 * PI * x * y).powi(3);

        let x1 = b.lower.unwrap();
        let d1 = discrete_bisection(x1, |x| {
            let rod = coil(y, gamma(x), n);
            let start = rod.rest_state().clone();
            let mut solver = EquilibriumSolver::new(&rod, &start, SolverParams::default());
            let sol = solver.solve(&rod, &start, 0.0, 1.0);
            unstable_out_of_plane(&sol, ode_tip(x, y), &format!("coil, Y = {y}, X = {x}"))
        });

        let x2 = b.upper.unwrap();
        let x_ref: f64 = 0.8;
        let rod = coil(y, gamma(x_ref), n);
        let start = hanging_start(n);
        let mut solver = EquilibriumSolver::new(&rod, &start, SolverParams::default());
        let top = solver.solve(&rod, &start, 1.0, 1.0);
        assert!(!unstable_out_of_plane(
            &top,
            ode_tip(x_ref, y),
            "hanging start"
        ));
        let d2 = discrete_bisection(x2, |x| {
            let sol = solver.solve(&rod, &top.state, 1.0, (x / x_ref).powi(3));
            unstable_out_of_plane(&sol, ode_tip(x, y), &format!("hanging, Y = {y}, X = {x}"))
        });
        for (name, ode, der) in [("X_c1", x1, d1), ("X_c2", x2, d2)] {
            println!(
                "{y:5.1}  {name}    {ode:.6}    {der:.6}    {:+.3} %   {n}",
                100.0 * (der / ode - 1.0)
            );
            compared.push((y, name, rel(der, ode)));
        }
    }
    // Below Y*: no instability anywhere on the coil branch, in either model.
    for y in [0.1, 0.5] {
        let n = 50;
        for x in [0.2, 0.45, 0.7, 1.0] {
            let rod = coil(y, (2.0 * PI * x * y).powi(3), n);
            let start = rod.rest_state().clone();
            let mut solver = EquilibriumSolver::new(&rod, &start, SolverParams::default());
            let sol = solver.solve(&rod, &start, 0.0, 1.0);
            let what = format!("Y = {y}, X = {x}");
            assert!(!unstable_out_of_plane(&sol, ode_tip(x, y), &what));
            assert_eq!(sol.report.inertia.unwrap().negative, 0);
            assert!(planar_stable(x, y, C).unwrap());
        }
    }
    println!("(discrete cross-check: {:?})", t0.elapsed());
    let worst = compared.iter().fold(0.0f64, |m, c| m.max(c.2));
    let distinct_y = {
        let mut ys: Vec<f64> = compared.iter().map(|c| c.0).collect();
        ys.dedup();
        ys.len()
    };
    assert!(distinct_y >= 5);
    assert!(
        worst < 0.01,
        "largest relative difference {worst}: {compared:?}"
    );
}
