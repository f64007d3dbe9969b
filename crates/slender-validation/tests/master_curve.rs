//! The cantilever master curve: limits, reference values, and the two independent methods
//! (multiple shooting and Richardson-extrapolated finite differences) against each other.

use slender_validation::cantilever::master_curve::{
    heavy_elastica, heavy_elastica_finite_difference, heavy_elastica_richardson, master_ratio,
    MasterCurveError, GAMMA_MAX, GAMMA_MIN,
};
use std::f64::consts::FRAC_PI_2;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Half a unit in the last digit of a reference value given with `decimals` decimals.
fn half_unit(decimals: i32) -> f64 {
    0.5 * 10f64.powi(-decimals)
}

#[test]
fn small_gamma_limit_is_the_linear_beam() {
    // Δy/Δx = Γ/8 (1 + O(Γ²)): the O(Γ) relative corrections of Δy and Δx cancel.
    for gamma in [1e-8, 1e-4, 1e-3] {
        let r = master_ratio(gamma).unwrap();
        assert!(
            rel(r, gamma / 8.0) < 1e-6,
            "Γ = {gamma}: {r} vs {}",
            gamma / 8.0
        );
    }
    let e = heavy_elastica(1e-4).unwrap();
    assert!(rel(e.tip_angle, 1e-4 / 6.0) < 1e-6);
    assert!(rel(e.clamp_curvature, 1e-4 / 2.0) < 1e-6);
}

#[test]
fn ratio_matches_independent_reference_values() {
    // (Γ, Δy/Δx, decimals given). Independently computed (second-order FD, n = 4000 and
    // 16000). Tolerance: 2e-6 relative, or half a unit in the last digit given where the
    // rounding of the reference is coarser than that (Γ = 0.1, 1, 3000, 1e4).
    let table = [
        (0.1, 0.0124996f64, 7),
        (1.0, 0.124562, 6),
        (3.0, 0.364621, 6),
        (10.0, 1.066802, 6),
        (30.0, 2.547214, 6),
        (61.3, 4.270745, 6),
        (100.0, 5.888105, 6),
        (300.0, 11.18312, 5),
        (1000.0, 21.33544, 5),
        (3000.0, 37.7196, 4),
        (1e4, 69.709, 3),
    ];
    for (gamma, reference, decimals) in table {
        let r = master_ratio(gamma).unwrap();
        let tol = (2e-6 * reference).max(half_unit(decimals));
        assert!(
            (r - reference).abs() <= tol,
            "Γ = {gamma}: {r} vs {reference} (diff {:e}, tol {tol:e})",
            r - reference
        );
    }
}

#[test]
fn tip_angle_matches_reference_values() {
    for (gamma, reference) in [
        (0.1, 0.016665),
        (1.0, 0.165116),
        (10.0, 1.052643),
        (100.0, 1.564107),
    ] {
        let e = heavy_elastica(gamma).unwrap();
        assert!(
            (e.tip_angle - reference).abs() <= half_unit(6),
            "Γ = {gamma}: {} vs {reference}",
            e.tip_angle
        );
    }
    for gamma in [1e3, 3e3, 1e4, 1e5] {
        let e = heavy_elastica(gamma).unwrap();
        assert!(
            (e.tip_angle - FRAC_PI_2).abs() < 5e-6,
            "Γ = {gamma}: {}",
            e.tip_angle
        );
        assert!(e.tip_angle <= FRAC_PI_2 + 1e-12);
    }
}

#[test]
fn shooting_agrees_with_richardson_extrapolated_finite_differences() {
    let mut worst: f64 = 0.0;
    for gamma in [1e-3, 0.1, 1.0, 10.0, 61.3, 100.0, 1000.0, 1e4] {
        let s = heavy_elastica(gamma).unwrap();
        let f = heavy_elastica_richardson(gamma, 2000).unwrap();
        let d = rel(s.ratio(), f.ratio());
        worst = worst.max(d);
        assert!(
            d < 1e-7,
            "Γ = {gamma}: shooting {} vs FD {} ({d:e})",
            s.ratio(),
            f.ratio()
        );
        assert!(
            rel(s.dx, f.dx) < 1e-7 && rel(s.dy, f.dy) < 1e-7,
            "Γ = {gamma}"
        );
        assert!(rel(s.tip_angle, f.tip_angle) < 1e-7, "Γ = {gamma}");
        assert!(
            rel(s.clamp_curvature, f.clamp_curvature) < 1e-7,
            "Γ = {gamma}"
        );
    }
    println!("max relative difference shooting vs Richardson FD: {worst:e}");
}

#[test]
fn finite_differences_converge_at_second_order() {
    for gamma in [1.0, 100.0, 1e4] {
        let exact = master_ratio(gamma).unwrap();
        let e1 = heavy_elastica_finite_difference(gamma, 500)
            .unwrap()
            .ratio()
            - exact;
        let e2 = heavy_elastica_finite_difference(gamma, 1000)
            .unwrap()
            .ratio()
            - exact;
        let order = (e1 / e2).log2();
        assert!(
            (order - 2.0).abs() < 0.1,
            "Γ = {gamma}: observed order {order}"
        );
        assert!(
            rel(exact + e2, exact) < 1e-5,
            "Γ = {gamma}: FD(1000) error {e2:e}"
        );
    }
}

#[test]
fn works_beyond_the_sweep_range() {
    for gamma in [GAMMA_MIN, 1e5, GAMMA_MAX] {
        let e = heavy_elastica(gamma).unwrap();
        assert!(e.ratio().is_finite() && e.ratio() > 0.0, "Γ = {gamma}");
    }
    let s = heavy_elastica(1e5).unwrap();
    let f = heavy_elastica_richardson(1e5, 2000).unwrap();
    assert!(rel(s.ratio(), f.ratio()) < 1e-7);
}

#[test]
fn master_curve_is_increasing() {
    let mut previous = 0.0;
    for i in 0..=40 {
        let gamma = 10f64.powf(-4.0 + 8.0 * i as f64 / 40.0);
        let r = master_ratio(gamma).unwrap();
        assert!(r > previous, "Γ = {gamma}: {r} after {previous}");
        previous = r;
    }
}

#[test]
fn invalid_gamma_is_an_error_not_a_panic() {
    for gamma in [
        f64::NAN,
        0.0,
        -0.0,
        -1.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
    ] {
        let results = [
            heavy_elastica(gamma).map(|e| e.ratio()),
            heavy_elastica_finite_difference(gamma, 100).map(|e| e.ratio()),
            heavy_elastica_richardson(gamma, 100).map(|e| e.ratio()),
            master_ratio(gamma),
        ];
        for r in results {
            match r {
                Err(e @ MasterCurveError::InvalidGamma { .. }) => {
                    assert!(e.to_string().contains("gamma"), "{e}");
                }
                other => panic!("Γ = {gamma}: expected InvalidGamma, got {other:?}"),
            }
        }
    }
}

#[test]
fn invalid_grid_size_is_an_error() {
    for n in [0, 1, usize::MAX] {
        assert!(matches!(
            heavy_elastica_finite_difference(1.0, n),
            Err(MasterCurveError::InvalidGridSize { .. })
        ));
        assert!(matches!(
            heavy_elastica_richardson(1.0, n),
            Err(MasterCurveError::InvalidGridSize { .. })
        ));
    }
    // Coarse grids either solve or report, never panic.
    for gamma in [1e-3, 10.0, 1e4, GAMMA_MAX] {
        for n in [2, 3, 5, 17] {
            let _ = heavy_elastica_finite_difference(gamma, n);
            let _ = heavy_elastica_richardson(gamma, n);
        }
    }
}

#[test]
fn shape_runs_from_the_clamp_to_the_tip() {
    for gamma in [1e-3, 1.0, 61.3, 1e4] {
        let e = heavy_elastica(gamma).unwrap();
        for n in [1, 7, 100] {
            let pts = e.shape(n);
            assert_eq!(pts.len(), n + 1);
            assert_eq!(pts[0], [0.0, 0.0]);
            let tip = pts[n];
            assert!(
                (tip[0] - e.dx).abs() < 1e-9,
                "Γ = {gamma}: {tip:?} vs {}",
                e.dx
            );
            assert!(
                (tip[1] + e.dy).abs() < 1e-9,
                "Γ = {gamma}: {tip:?} vs {}",
                e.dy
            );
            for w in pts.windows(2) {
                // Equal arc-length stations: chords at most 1/n; the rod only goes down.
                let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                assert!(chord <= 1.0 / n as f64 + 1e-12);
                assert!(w[1][1] < w[0][1]);
                assert!(w[1][0] >= w[0][0] - 1e-12, "{:?}", w);
            }
        }
        assert_eq!(e.shape(0), vec![[0.0, 0.0]]);
    }
}

#[test]
fn finite_difference_shape_ends_at_the_tip() {
    for e in [
        heavy_elastica_finite_difference(100.0, 400).unwrap(),
        heavy_elastica_richardson(100.0, 400).unwrap(),
    ] {
        let pts = e.shape(50);
        assert_eq!(pts[0], [0.0, 0.0]);
        assert!((pts[50][0] - e.dx).abs() < 1e-12 && (pts[50][1] + e.dy).abs() < 1e-12);
    }
    // The shapes of both methods agree to the interpolation error.
    let s = heavy_elastica(100.0).unwrap().shape(20);
    let f = heavy_elastica_finite_difference(100.0, 4000)
        .unwrap()
        .shape(20);
    for (a, b) in s.iter().zip(&f) {
        assert!(
            (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5,
            "{a:?} vs {b:?}"
        );
    }
}

/// Not a test: `cargo test -p slender-validation --release --test integration -- --exact
/// master_curve::timing --ignored --nocapture` prints the cost of one master-curve point.
#[test]
#[ignore]
fn timing() {
    for gamma in [1.0, 100.0, 1e4, 1e5] {
        let reps = 50;
        let t = std::time::Instant::now();
        for _ in 0..reps {
            std::hint::black_box(heavy_elastica(std::hint::black_box(gamma)).unwrap());
        }
        println!(
            "heavy_elastica(Γ = {gamma:e}): {:?} per call",
            t.elapsed() / reps
        );
    }
}
