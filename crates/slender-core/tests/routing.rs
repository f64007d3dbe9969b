//! Real routing operations that used to fail or mislead (issue 17), each against an
//! independent reference: pushing a clamped–clamped cable past buckling (the elastica by
//! elliptic integrals), twisting a closed ring through Michell's instability, a stiff strip's
//! lateral–torsional buckling by inertia, and the residual's scale in motion-driven scenes.

use nalgebra::Vector3;
use slender_core::scene::spec::UnstablePolicy;
use slender_core::scene::{Scene, Session};

use crate::common;
use common::{clamped_elastica_deflection, elliptic_ke};

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

/// Largest distance (m) between corresponding points of two shapes.
fn worst_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

/// A 1 m PMMA-like cable, d = 4 mm, clamped at both ends (issue 17's case).
const PUSH: &str = r#"
[[rods]]
name = "column"
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 3.0e9, poisson = 0.35, density = 1140.0 }
elements = 40
supports = [ { kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" } ]
"#;

fn push(imperfection: f64) {
    let mut s = Session::new(scene(PUSH)).unwrap();
    let steps = 10;
    for k in 1..=steps {
        let r = s
            .move_support_by(
                0,
                1,
                Vector3::new(0.0, 0.0, imperfection / steps as f64),
                Vector3::new(-0.005, 0.0, 0.0),
            )
            .unwrap();
        assert!(r.converged, "step {k}: {r:?}");
        assert!(r.stable, "step {k}: unstable equilibrium returned: {r:?}");
    }
    let res = s.results(steps, None, 1.0, 1);
    assert!(res.stable && res.converged);
    let rod = &res.rods[0];
    let deflection = rod
        .positions
        .iter()
        .map(|p| (p[1] * p[1] + p[2] * p[2]).sqrt())
        .fold(0.0, f64::max);
    let exact = clamped_elastica_deflection(1.0, 0.05);
    let rel = deflection / exact - 1.0;
    eprintln!("imperfection {imperfection}: deflection {deflection:.6} vs elastica {exact:.6} ({rel:+.2e})");
    assert!(
        rel.abs() < 5e-3,
        "deflection {deflection} vs elastica {exact}"
    );
}

#[test]
fn elliptic_integrals_have_their_known_values() {
    let (k, e) = elliptic_ke(0.0);
    assert!((k - std::f64::consts::FRAC_PI_2).abs() < 1e-14 && (e - k).abs() < 1e-14);
    // K(1/2) = 1.854074677301372, E(1/2) = 1.350643881047675 (Abramowitz & Stegun 17.3).
    let (k, e) = elliptic_ke(0.5);
    assert!((k - 1.854_074_677_301_372).abs() < 1e-13, "{k}");
    assert!((e - 1.350_643_881_047_675).abs() < 1e-13, "{e}");
}

#[test]
fn pushing_a_straight_cable_past_buckling_ends_buckled_and_stable() {
    push(0.0);
}

#[test]
fn pushing_an_imperfect_cable_past_buckling_ends_buckled_and_stable() {
    push(0.01);
}

#[test]
fn keeping_the_unstable_straight_column_says_so() {
    let mut sc = scene(PUSH);
    sc.unstable = UnstablePolicy::Keep;
    let mut s = Session::new(sc).unwrap();
    let r = s
        .move_support_by(0, 1, Vector3::zeros(), Vector3::new(-0.005, 0.0, 0.0))
        .unwrap();
    assert!(r.converged && !r.stable, "{r:?}");
    let res = s.results(1, None, 1.0, 1);
    assert!(!res.stable && res.structures[0].stability.unstable_modes > 0);
    // Snapping it to the stable branch on request.
    let r = s.follow_stable();
    assert!(r.stable && r.followed_unstable_mode, "{r:?}");
}

/// A clamped–clamped cable, 1 m, closed into a ring by moving its end clamp onto its start
/// clamp (32 steps along the circle), then twisted by turning that clamp about the common
/// tangent. A round ring is neutrally stable to rolling through itself (an exact null mode),
/// which must not stop the solve; past Michell's instability the ring buckles out of its plane
/// and the buckled ring is stable.
#[test]
fn a_closed_ring_twists_through_its_instability() {
    let mut s = Session::new(scene(PUSH)).unwrap();
    let l = 1.0;
    let n = 32;
    let end = |phi: f64| {
        if phi == 0.0 {
            Vector3::new(l, 0.0, 0.0)
        } else {
            let r = l / phi;
            Vector3::new(r * phi.sin(), r * (1.0 - phi.cos()), 0.0)
        }
    };
    for k in 1..=n {
        let (a, b) = (
            2.0 * std::f64::consts::PI * (k - 1) as f64 / n as f64,
            2.0 * std::f64::consts::PI * k as f64 / n as f64,
        );
        let r = s
            .move_support_by(0, 1, Vector3::new(0.0, 0.0, b - a), end(b) - end(a))
            .unwrap();
        assert!(r.converged, "closing step {k}: {r:?}");
    }
    let closed = s.results(0, None, 1.0, 1);
    let gap = {
        let p = &closed.rods[0].positions;
        let (a, b) = (p[0], p[p.len() - 1]);
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    assert!(gap < 1e-9, "ring not closed: gap {gap}");
    // Twist: turn the end clamp about the ring's tangent there (+x).
    let out_of_plane = |s: &Session| {
        s.results(0, None, 1.0, 1).rods[0]
            .positions
            .iter()
            .map(|p| p[2].abs())
            .fold(0.0, f64::max)
    };
    let mut buckled_at = None;
    let dphi = 0.5;
    for k in 1..=44 {
        let r = s
            .move_support_by(0, 1, Vector3::new(dphi, 0.0, 0.0), Vector3::zeros())
            .unwrap();
        assert!(
            r.converged,
            "twist step {k} ({} rad): {r:?}",
            k as f64 * dphi
        );
        assert!(
            r.stable,
            "twist step {k}: unstable equilibrium returned: {r:?}"
        );
        if buckled_at.is_none() && out_of_plane(&s) > 1e-2 * l {
            buckled_at = Some(k as f64 * dphi);
        }
    }
    // Past Michell's twist (2π√3·EI/GJ ≈ 14.7 rad for a free ring) the ring has left its plane;
    // every step above converged to a stable equilibrium, through the roll null mode.
    let twist = buckled_at.expect("the ring never left its plane");
    assert!(twist < 14.7, "left its plane only at {twist} rad");
    let last = s.results(0, None, 1.0, 1);
    assert!(last.stable && last.structures[0].stability.null_modes <= 1);
}

/// A stiff strip (issue 17): EA = 1e8 N, EI₁ = 1e6 N m² (vertical), EI₂ = 1 N m² (lateral),
/// GJ = 1 N m², ρA = 1.271 kg/m, 1 m, clamped, its width vertical, under gravity −z. Its
/// lateral–torsional buckling under self-weight is at q L³/√(EI₂ GJ) = 12.8538 (the classical
/// constant, design.md §1.3), i.e. g_c = 12.8538/1.271 m/s²; the inertia must switch within
/// 0.5 % of it, with 1000 elements.
fn stiff_strip(elements: usize, g: f64) -> Scene {
    scene(&format!(
        r#"
gravity = [0.0, 0.0, {}]
unstable = "keep"
[[rods]]
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "stiffness", ea = 1e8, ei1 = 1e6, ei2 = 1.0, gj = 1.0, linear_density = 1.271 }}
elements = {elements}
first_director = [0.0, 0.0, 1.0]
supports = [ {{ kind = "clamp", vertex = "start" }} ]
"#,
        -g
    ))
}

#[test]
fn a_stiff_strip_switches_stability_at_lateral_torsional_buckling() {
    let g_c = 12.8538 / 1.271;
    for elements in [320, 1000] {
        for (f, stable) in [(0.995, true), (1.005, false)] {
            let mut sc = stiff_strip(elements, f * g_c);
            sc.unstable = UnstablePolicy::Keep;
            let s = Session::new(sc).unwrap();
            let r = s.results(0, None, 1.0, 1);
            let st = &r.structures[0];
            assert!(st.report.converged());
            assert_eq!(
                st.stability.stable, stable,
                "{elements} elements, g/g_c = {f}"
            );
            // λ_min has the sign of the inertia (its resolution on this graded matrix is a few
            // hundredths of EI/ρAL⁴; the true values are about ±0.15).
            let l = st.report.lambda_min_normalized.expect("λ_min");
            assert_eq!(l > 0.0, stable, "λ_min/scale = {l}");
            // The residual is measured against the load; when round-off limits it (EA/EI₂ =
            // 1e8), it is still small against the load, and the report says how small.
            assert!(
                st.report.relative_residual < 1e-3,
                "{}",
                st.report.relative_residual
            );
        }
    }
}

/// A clamped–free column (d₁-bending EI = 1 N m², twice as stiff in the other plane so that
/// the buckled plane is not a free symmetry), 1 m along x, its tip pushed by a dead force.
fn column(force: f64) -> String {
    format!(
        r#"
[[rods]]
name = "column"
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "stiffness", ea = 1.0e6, ei1 = 1.0, ei2 = 2.0, gj = 0.77, linear_density = 0.1 }}
elements = 100
supports = [ {{ kind = "clamp", vertex = "start" }} ]
forces = [ {{ vertex = "end", force = [{}, 0.0, 0.0] }} ]
"#,
        -force
    )
}

#[test]
fn a_clamped_free_column_at_one_and_a_half_euler_loads_ends_on_the_elastica() {
    // Euler's first case: P_E = π²EI/(4L²). The buckled cantilever is half a pinned–pinned
    // elastica of length 2L: with k = sin(α/2) (α the tip angle), P/P_E = (2K(k)/π)², the tip
    // deflects by 2kL/K(k) across and sits at L(2E(k)/K(k) − 1) along the axis.
    let ratio = 1.5;
    let p_e = std::f64::consts::PI.powi(2) / 4.0;
    let s = Session::new(scene(&column(ratio * p_e))).unwrap();
    let res = s.results(0, None, 1.0, 1);
    assert!(res.converged && res.stable, "{:?}", res.structures);
    assert!(res.structures[0].stability.followed_unstable_mode);
    let tip = *res.rods[0].positions.last().unwrap();
    let (mut lo, mut hi) = (1e-9_f64, 0.999_f64);
    for _ in 0..200 {
        let k = 0.5 * (lo + hi);
        if (2.0 * elliptic_ke(k * k).0 / std::f64::consts::PI).powi(2) < ratio {
            lo = k;
        } else {
            hi = k;
        }
    }
    let k = 0.5 * (lo + hi);
    let (kk, ee) = elliptic_ke(k * k);
    let (across, along) = (2.0 * k / kk, 2.0 * ee / kk - 1.0);
    let sim_across = (tip[1] * tip[1] + tip[2] * tip[2]).sqrt();
    eprintln!(
        "tip ({:.6}, {sim_across:.6}) vs elastica ({along:.6}, {across:.6})",
        tip[0]
    );
    assert!(
        (tip[0] - along).abs() < 1e-3 && (sim_across - across).abs() < 1e-3,
        "tip {tip:?} vs elastica ({along}, {across})"
    );
}

/// The heavy standing column (Greenhill): clamped at the bottom, free at the top, under its
/// weight q per length, Γ = qL³/EI. With θ the angle from the vertical and S = s/L,
/// θ'' = −Γ(1 − S) sin θ, θ(0) = 0, θ'(1) = 0; shot from the top on α = θ(1) (the first
/// non-zero root), integrating the tip's offset from the clamp. Returns (across, up) / L.
fn heavy_column_tip(gamma: f64) -> (f64, f64) {
    let steps = 4000;
    let h = 1.0 / steps as f64;
    // State from the top down: (θ, θ', ∫sin θ, ∫cos θ) over [S, 1].
    let run = |alpha: f64| {
        let rhs = |s: f64, y: [f64; 4]| {
            [
                y[1],
                -gamma * (1.0 - s) * y[0].sin(),
                y[0].sin(),
                y[0].cos(),
            ]
        };
        let mut y = [alpha, 0.0, 0.0, 0.0];
        let mut s = 1.0;
        for _ in 0..steps {
            let add = |y: [f64; 4], k: [f64; 4], c: f64| [0, 1, 2, 3].map(|i| y[i] + c * k[i]);
            let k1 = rhs(s, y);
            let k2 = rhs(s - 0.5 * h, add(y, k1, -0.5 * h));
            let k3 = rhs(s - 0.5 * h, add(y, k2, -0.5 * h));
            let k4 = rhs(s - h, add(y, k3, -h));
            y = [0, 1, 2, 3].map(|i| y[i] - h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
            s -= h;
        }
        y
    };
    // The first sign change of θ(0) in α, then bisection.
    let mut a = 1e-3;
    let f0 = run(a)[0];
    let mut b = a;
    while b < 3.1 {
        b += 0.01;
        if run(b)[0].signum() != f0.signum() {
            break;
        }
    }
    let (mut lo, mut hi) = (b - 0.01, b);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if run(mid)[0].signum() == f0.signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    a = 0.5 * (lo + hi);
    // Integrated from the top down, the integrals carry the sign of ds < 0; the buckling
    // side is arbitrary.
    let y = run(a);
    (y[2].abs(), -y[3])
}

#[test]
fn a_heavy_column_past_greenhill_ends_buckled_on_the_heavy_elastica() {
    // Greenhill's critical Γ for a standing column is 7.8373; take 1.5 times it.
    let gamma = 1.5 * 7.8373;
    let text = format!(
        r#"
gravity = [0.0, 0.0, {}]
[[rods]]
name = "column"
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [0.0, 0.0, 1.0], length = 1.0 }}
section = {{ shape = "stiffness", ea = 1.0e6, ei1 = 1.0, ei2 = 2.0, gj = 0.77, linear_density = 1.0 }}
first_director = [1.0, 0.0, 0.0]
elements = 100
supports = [ {{ kind = "clamp", vertex = "start" }} ]
"#,
        -gamma
    );
    let s = Session::new(scene(&text)).unwrap();
    let res = s.results(0, None, 1.0, 1);
    assert!(res.converged && res.stable, "{:?}", res.structures);
    assert!(res.structures[0].stability.followed_unstable_mode);
    let tip = *res.rods[0].positions.last().unwrap();
    let (across, up) = heavy_column_tip(gamma);
    let sim_across = (tip[0] * tip[0] + tip[1] * tip[1]).sqrt();
    eprintln!(
        "tip ({sim_across:.6}, {:.6}) vs heavy elastica ({across:.6}, {up:.6})",
        tip[2]
    );
    assert!(
        (sim_across - across).abs() < 1e-3 && (tip[2] - up).abs() < 1e-3,
        "tip {tip:?} vs heavy elastica ({across}, {up})"
    );
}

#[test]
fn a_clip_added_in_a_session_and_saved_round_trips_to_the_same_equilibrium() {
    // A sagging cable, its end pinned and dragged, then clipped mid-span where it hangs: the
    // saved scene (the clip moved rigidly from its rest pose, the pin's drag as motion) must
    // re-solve to the session's equilibrium.
    use slender_core::scene::spec::{SupportKind, SupportSpec};
    let text = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.6 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e8, poisson = 0.4, density = 1400.0 }
elements = 24
supports = [ { kind = "clamp", vertex = "start" }, { kind = "pin", vertex = "end" } ]
"#;
    let mut s = Session::new(scene(text)).unwrap();
    let r = s
        .move_support_by(0, 1, Vector3::zeros(), Vector3::new(-0.05, 0.04, 0.06))
        .unwrap();
    assert!(r.converged);
    let r = s
        .add_support(
            0,
            SupportSpec {
                kind: SupportKind::Clip,
                vertex: None,
                at: Some(0.31),
                axis: None,
            },
        )
        .unwrap();
    assert!(r.converged, "{r:?}");
    let here = s.results(0, None, 1.0, 1).rods[0].positions.clone();
    let saved = s.saved();
    let mut again = Session::new(saved).unwrap();
    for k in 1..=again.motion_steps() {
        assert!(again.run_motion_step(k).converged);
    }
    let there = again.results(0, None, 1.0, 1).rods[0].positions.clone();
    assert_eq!(here.len(), there.len());
    let worst = worst_distance(&here, &there);
    assert!(worst < 1e-9 * 0.6, "saved scene differs by {worst:e} m");
}

/// A drag that does not converge leaves the support and the equilibrium where they were; the
/// edit's report has the failed solve's figures, and the structure's report stays that of the
/// equilibrium it shows.
#[test]
fn a_drag_that_fails_keeps_the_last_equilibrium_and_its_report() {
    let text = format!("{PUSH}\n[solver]\nmax_iterations = 1\nmin_load_step = 0.25\n");
    let mut s = Session::new(scene(&text)).unwrap();
    assert!(s.report(0).converged());
    let before_state = s.state(0).clone();
    let before_residual = s.report(0).relative_residual;
    let before_pose = s.pose(0, 1).unwrap();
    let r = s
        .move_support_by(0, 1, Vector3::zeros(), Vector3::new(0.0, 0.2, 0.0))
        .unwrap();
    assert!(!r.converged, "{r:?}");
    assert!(r.reason.is_some());
    // The failed solve's residual is in the edit's report, far above the kept equilibrium's.
    assert!(
        r.relative_residual > 1e3 * before_residual.max(1e-15),
        "{} vs {before_residual}",
        r.relative_residual
    );
    assert_eq!(s.state(0), &before_state);
    assert_eq!(s.pose(0, 1).unwrap(), before_pose);
    let kept = s.report(0);
    assert!(
        !kept.converged(),
        "the structure's report says the edit failed"
    );
    assert_eq!(kept.relative_residual, before_residual);
}

/// Interactive drags end where a cold solve ends: a sagging cable clamped at both ends, its
/// end clamp dragged by centimetre steps back and forth (each warm re-solve starts from the
/// last equilibrium, corrected by chord steps with the last factorization, and finishes with
/// chord final checks), must reach the equilibrium that the saved scene reaches from rest.
#[test]
fn warm_centimetre_drags_end_where_a_cold_solve_of_the_saved_scene_ends() {
    let text = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.006 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
elements = 50
supports = [ { kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" } ]
"#;
    let mut s = Session::new(scene(text)).unwrap();
    let steps = [
        [0.0, 0.01, 0.0],
        [0.0, 0.01, 0.0],
        [0.0, -0.01, 0.0],
        [-0.01, 0.0, 0.01],
        [0.0, 0.01, 0.0],
        [-0.01, 0.0, -0.01],
    ];
    for d in steps {
        let r = s
            .move_support_by(0, 1, Vector3::zeros(), Vector3::from(d))
            .unwrap();
        assert!(r.converged, "{r:?}");
        assert!(r.relative_residual < 1e-6, "{r:?}");
    }
    let here = s.results(0, None, 1.0, 1).rods[0].positions.clone();
    let mut cold = Session::new(s.saved()).unwrap();
    for k in 1..=cold.motion_steps() {
        assert!(cold.run_motion_step(k).converged);
    }
    let there = cold.results(0, None, 1.0, 1).rods[0].positions.clone();
    let worst = worst_distance(&here, &there);
    assert!(
        worst < 1e-9,
        "warm drags and the cold solve differ by {worst:e} m"
    );
}
