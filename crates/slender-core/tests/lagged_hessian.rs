//! The lagged Hessian of a warm re-solve's first Newton step (`SolverParams::lagged_first_step`):
//! the assembler keeps the rod's bending and twisting Hessian apart or leaves it out, the two
//! parts add up to the whole Hessian, and drags with the lagged first step reach the same
//! equilibria as drags without it.

use slender_core::assembly::{Assembler, TermSet};
use slender_core::geometry::Vec3;
use slender_core::linalg::{AdaptiveMatrix, SymmetricMatrix};
use slender_core::rod::groups::{BENDING, TWISTING};
use slender_core::scene::{Scene, Session};
use slender_core::solver::EquilibriumProblem;

fn cable(supports: &str) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 40
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {supports} ]
"#
    ))
    .unwrap()
}

/// Largest |(A − B) v| over a few fixed vectors, relative to the largest |A v|.
fn relative_difference(a: &AdaptiveMatrix, b: &AdaptiveMatrix) -> f64 {
    let n = a.dim();
    let (mut worst, mut scale) = (0.0_f64, 0.0_f64);
    for k in 0..4 {
        let v: Vec<f64> = (0..n)
            .map(|i| ((i * 7 + k * 13) % 11) as f64 - 5.0)
            .collect();
        let (mut av, mut bv) = (vec![0.0; n], vec![0.0; n]);
        a.mul_vec(&v, &mut av);
        b.mul_vec(&v, &mut bv);
        for i in 0..n {
            worst = worst.max((av[i] - bv[i]).abs());
            scale = scale.max(av[i].abs());
        }
    }
    worst / scale
}

#[test]
fn the_lagged_and_fresh_parts_of_a_rods_hessian_add_up_to_the_whole() {
    let session = Session::new(cable(
        r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }"#,
    ))
    .unwrap();
    let rod = &session.compiled().structures[0];
    let slow = BENDING.set().with(TWISTING.set());
    assert_eq!(rod.lagged_hessian_groups(), slow);
    let n = rod.n_free();
    // A state away from the equilibrium, bent in 3D (the sagged equilibrium pushed sideways
    // and twisted by a smooth field).
    let mut dx = vec![0.0; n];
    for (i, d) in dx.iter_mut().enumerate() {
        *d = 1e-3 * (0.37 * i as f64).sin();
    }
    let mut state = session.state(0).clone();
    rod.displace(session.state(0), &dx, 1.0, &mut state);

    let whole = |s| {
        let (mut g, mut h) = (vec![0.0; n], rod.new_hessian());
        let mut asm = Assembler::new(TermSet::ALL, Some(&mut g[..]), Some(&mut h), None);
        rod.assemble_selected(s, 1.0, &mut asm);
        (g, h)
    };
    let (g, h) = whole(&state);

    // Kept apart: the fresh part plus the kept part is the whole Hessian (to the rounding of
    // a different summation order); the gradient is the whole gradient, bit for bit.
    let (mut g2, mut fresh, mut kept) = (vec![0.0; n], rod.new_hessian(), rod.new_hessian());
    let mut asm = Assembler::new(TermSet::ALL, Some(&mut g2[..]), Some(&mut fresh), None)
        .lagging(slow, Some(&mut kept));
    rod.assemble_selected(&state, 1.0, &mut asm);
    let fresh_only = fresh.clone();
    assert!(fresh.add_same_pattern(&kept));
    assert_eq!(g, g2);
    let d = relative_difference(&h, &fresh);
    assert!(
        d < 1e-13,
        "fresh + kept differs from the whole Hessian by {d:e}"
    );
    // The bending and twisting part is not small: leaving it out is a different matrix.
    let d = relative_difference(&h, &fresh_only);
    assert!(d > 1e-6, "the kept part is only {d:e} of the Hessian");

    // Left out: the same fresh part (bit for bit) without evaluating the lagged one; the
    // hinges then take their gradient-only path, whose rounding differs.
    let (mut g3, mut left) = (vec![0.0; n], rod.new_hessian());
    let mut asm =
        Assembler::new(TermSet::ALL, Some(&mut g3[..]), Some(&mut left), None).lagging(slow, None);
    rod.assemble_selected(&state, 1.0, &mut asm);
    let scale = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for (a, b) in g.iter().zip(&g3) {
        assert!((a - b).abs() <= 1e-13 * scale, "gradient {a} against {b}");
    }
    assert_eq!(relative_difference(&fresh_only, &left), 0.0);
}

/// Drags the end clamp of `scene`'s cable by ±1 cm sideways and up, `k` times, and returns the
/// final positions and the Newton iterations of each drag.
fn drag(scene: Scene, lagged: bool, k: usize) -> (Vec<Vec3>, Vec<usize>) {
    let mut compiled = scene.compile().unwrap();
    assert!(
        compiled.solver.lagged_first_step,
        "scene sessions lag the first step"
    );
    compiled.solver.lagged_first_step = lagged;
    let mut session = Session::from_compiled(scene, compiled);
    let mut its = Vec::new();
    for i in 0..k {
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        let r = session
            .move_support_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.01 * sign, 0.004))
            .unwrap();
        assert!(r.converged, "drag {i}, lagged {lagged}: {r:?}");
        its.push(r.iterations);
    }
    let positions = session.state(0).members[0].positions().to_vec();
    (positions, its)
}

#[test]
fn drags_with_a_lagged_first_step_reach_the_equilibria_of_drags_without() {
    for supports in [
        r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }"#,
        r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }, { kind = "clip", vertex = 10 }, { kind = "clip", vertex = 30 }"#,
    ] {
        let (exact, exact_its) = drag(cable(supports), false, 6);
        let (lagged, lagged_its) = drag(cable(supports), true, 6);
        let worst = exact
            .iter()
            .zip(&lagged)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-9,
            "{supports}: the lagged drags end {worst:e} m away"
        );
        println!(
            "{supports}: {worst:e} m apart; iterations {lagged_its:?} (lagged), {exact_its:?}"
        );
        // The lagged first step is as good as Newton's here: no drag takes more iterations.
        for (a, b) in exact_its.iter().zip(&lagged_its) {
            assert!(
                b <= a,
                "{supports}: iterations {lagged_its:?} against {exact_its:?}"
            );
        }
    }
}
