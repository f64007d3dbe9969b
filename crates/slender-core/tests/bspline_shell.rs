//! The B-spline Kirchhoff–Love shell against independent references: every term's gradient
//! and Hessian against central finite differences (error falling like O(ε²)), zero gradient
//! of the flat strip, invariance under rigid motions, the closed-form energy of cylindrical
//! bending, a strip bent into a cylinder by its end clamps, and linear beam theory for small
//! loads; the mixed-integration-point update changes the Hessian only.

use nalgebra::DMatrix;
use nalgebra::{Rotation3, Vector3};
use slender_core::assembly::TermSet;
use slender_core::bspline_shell::groups::{BENDING, INTERNAL, MEMBRANE};
use slender_core::bspline_shell::quadrature::gauss_legendre;
use slender_core::bspline_shell::{
    BsplineLoadPath, BsplineShell, BsplineShellBuilder, BsplineState, ClampMotion, PointLoad,
    StripEnd,
};
use slender_core::rod::Grading;
use slender_core::shell::{Clamp, ShellProperties};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};
use slender_core::testing::{check_model, Rng};

fn properties(poisson: f64) -> ShellProperties {
    ShellProperties {
        length: 1.0,
        width: 0.3,
        thickness: 0.01,
        young: 2.0e5,
        poisson,
        density: 800.0,
    }
}

fn shells() -> Vec<BsplineShell> {
    vec![
        BsplineShellBuilder::new(properties(0.3))
            .elements(3, 2)
            .gravity(Vector3::new(0.3, -9.8, 1.1))
            .point_load(PointLoad {
                u: 0.7,
                v: 0.1,
                force: [0.2, -1.0, 0.5],
            })
            .build()
            .expect("cubic shell"),
        BsplineShellBuilder::new(properties(0.0))
            .degree(2)
            .elements(4, 1)
            .grading(Grading::Uniform)
            .gravity(Vector3::new(0.0, 0.0, -9.8))
            .build()
            .expect("quadratic shell"),
        BsplineShellBuilder::new(properties(0.45))
            .degree(4)
            .elements(2, 1)
            .clamp(StripEnd::End, Clamp::default())
            .build()
            .expect("quartic shell clamped at both ends"),
    ]
}

/// A bent, stretched and twisted state with rotated clamps, so that every term is exercised
/// away from zero.
fn random_state(shell: &BsplineShell, rng: &mut Rng) -> BsplineState {
    let mut s = shell.rest_state();
    for (k, p) in s.control_points.iter_mut().enumerate() {
        let r = shell.patch().rest_points[k];
        let x = r.x;
        *p = Vector3::new(
            x.sin(),
            1.0 - x.cos() + 0.2 * x * r.z,
            r.z * (1.0 + 0.1 * x),
        ) + Vector3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 0.01;
    }
    for end in StripEnd::BOTH {
        if shell.is_clamped(end) {
            let pose = Clamp {
                rotation: Rotation3::from_axis_angle(&Vector3::x_axis(), 0.2 * rng.uniform()),
                translation: Vector3::new(0.0, 0.01 * rng.uniform(), 0.0),
            };
            shell.set_clamp(end, pose, &mut s).expect("clamped end");
        }
    }
    s
}

#[test]
fn every_term_passes_the_derivative_checker() {
    // Membrane, bending, gravity and point loads (linear: no Hessian) and their sum against
    // finite differences; rigid motions (the clamps move with the state); the flat unloaded
    // strip, for degrees 2, 3 and 4.
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (k, shell) in shells().into_iter().enumerate() {
        let states: Vec<BsplineState> = (0..3).map(|_| random_state(&shell, &mut rng)).collect();
        check_model(
            &shell,
            &states,
            1.0,
            &mut rng,
            |_| 1.0,
            1.0,
            &format!("shell {k}"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn flat_strip_has_no_internal_force_in_any_pose() {
    // The rest state placed by a rotated, translated clamp is still stress free.
    let pose = Clamp {
        rotation: Rotation3::new(Vector3::new(0.3, 1.0, -0.2) * 0.9),
        translation: Vector3::new(0.5, -1.0, 2.0),
    };
    let shell = BsplineShellBuilder::new(properties(0.3))
        .elements(4, 2)
        .clamp(StripEnd::Start, pose)
        .build()
        .unwrap();
    let s = shell.rest_state();
    let n = shell.n_free();
    let mut g = vec![0.0; n];
    let mut h = shell.sparse_hessian();
    let info = shell.assemble_terms(&s, 1.0, INTERNAL, Some(&mut g), Some(&mut h), None);
    assert!(info.energy.abs() < 1e-20, "energy {}", info.energy);
    assert!(g.iter().all(|x| x.abs() < 1e-12), "{g:?}");
}

/// The point of the cylinder of curvature κ about z through the rest line y = 0 above rest
/// point (x, ·, z): (sin κx/κ, (1 − cos κx)/κ, z).
fn on_cylinder(kappa: f64, x: f64, z: f64) -> Vector3<f64> {
    Vector3::new(
        (kappa * x).sin() / kappa,
        (1.0 - (kappa * x).cos()) / kappa,
        z,
    )
}

/// Control points whose surface interpolates the cylinder at the Greville abscissae along the
/// length (collocation: the spline then approximates the cylinder to O(h^(p+1))).
fn interpolate_cylinder(shell: &BsplineShell, kappa: f64) -> BsplineState {
    let knots = &shell.patch().knots_u;
    let g = knots.greville();
    let n = g.len();
    let mut a = DMatrix::zeros(n, n);
    for (i, &x) in g.iter().enumerate() {
        let e = knots.element_of(x);
        let b = knots.evaluate(e, x);
        for k in 0..=knots.degree() {
            a[(i, knots.first_function(e) + k)] = b[k][0];
        }
    }
    let lu = a.lu();
    let mut s = shell.rest_state();
    for c in 0..2 {
        let rhs = DMatrix::from_fn(n, 1, |i, _| on_cylinder(kappa, g[i], 0.0)[c]);
        let sol = lu
            .solve(&rhs)
            .expect("Schoenberg–Whitney: the collocation matrix is regular");
        for (k, x) in s.control_points.iter_mut().enumerate() {
            x[c] = sol[shell.patch().row(k)];
        }
    }
    s
}

#[test]
fn cylindrical_bending_energy_matches_closed_form() {
    // A surface interpolating a cylinder: the bending energy is ½·D·w·L·κ² (ν ≠ 0 exercises
    // the λ(tr N)² coupling). Graded knots included.
    for (poisson, kappa, degree, grading) in [
        (0.3, 1.0, 3, Grading::Uniform),
        (0.0, 2.0, 2, Grading::Uniform),
        (0.45, 0.5, 4, Grading::Power { exponent: 2.0 }),
    ] {
        let p = properties(poisson);
        let shell = BsplineShellBuilder::new(p)
            .degree(degree)
            .elements(16, 2)
            .grading(grading)
            .build()
            .unwrap();
        let s = interpolate_cylinder(&shell, kappa);
        let bending = shell.energy_terms(&s, 0.0, BENDING.set());
        let expected = 0.5 * p.bending_stiffness() * p.width * p.length * kappa * kappa;
        let rel = (bending - expected) / expected;
        assert!(
            rel.abs() < 5e-3,
            "ν = {poisson}, κ = {kappa}, p = {degree}: {bending} vs {expected} ({rel:+.2e})"
        );
    }
}

#[test]
fn end_clamps_bend_the_strip_into_a_cylinder() {
    // Both ends clamped; the end clamp turns by θ about z and moves to the end of the circular
    // arc of curvature κ = θ/L. With ν = 0 the exact solution is that arc (pure bending by the
    // end moment M = D·w·κ, no membrane strain): energy ½·D·w·L·κ², every centre-line point at
    // distance R = 1/κ from the centre. Solved from the flat strip along the clamp's motion.
    let p = ShellProperties {
        length: 1.0,
        width: 0.2,
        thickness: 0.005,
        young: 1.0e9,
        poisson: 0.0,
        density: 1000.0,
    };
    // (Quadratic splines lock here: +5.6 % at 12 elements; the default degree is 3.)
    for (degree, n) in [(3, 8), (4, 8)] {
        let theta = 1.2;
        let kappa = theta / p.length;
        let arc_end = Vector3::new((theta).sin() / kappa, (1.0 - theta.cos()) / kappa, 0.0);
        let mut shell = BsplineShellBuilder::new(p)
            .degree(degree)
            .elements(n, 2)
            .grading(Grading::Uniform)
            .clamp(StripEnd::End, Clamp::default())
            .build()
            .unwrap();
        shell
            .set_load_path(BsplineLoadPath::clamp_motion(vec![ClampMotion {
                end: StripEnd::End,
                pivot: [p.length, 0.0, 0.0],
                rotation: [0.0, 0.0, theta],
                translation: (arc_end - Vector3::new(p.length, 0.0, 0.0)).into(),
            }]))
            .unwrap();
        let start = shell.rest_state();
        let mut solver = EquilibriumSolver::new(&shell, &start, SolverParams::default());
        let sol = solver.solve(&shell, &start, 0.0, 1.0);
        assert!(sol.report.converged(), "p = {degree}: {:?}", sol.report);
        assert_eq!(sol.report.stable(), Some(true));
        let e = shell.energy_terms(&sol.state, 1.0, INTERNAL);
        let expected = 0.5 * p.bending_stiffness() * p.width * p.length * kappa * kappa;
        let rel = (e - expected) / expected;
        assert!(
            rel.abs() < 5e-3,
            "p = {degree}: energy {e} vs {expected} ({rel:+.2e})"
        );
        let centre = Vector3::new(0.0, 1.0 / kappa, 0.0);
        for k in 0..=20 {
            let u = p.length * k as f64 / 20.0;
            for v in [-0.1, 0.0, 0.1] {
                let x = shell.point(&sol.state, u, v);
                let r = ((x - centre).xy()).norm();
                assert!(
                    (r * kappa - 1.0).abs() < 5e-3,
                    "p = {degree}: radius at u = {u}, v = {v}: {r} vs {}",
                    1.0 / kappa
                );
                assert!(
                    (x.z - v).abs() < 1e-6,
                    "the width stays straight: z = {}",
                    x.z
                );
            }
        }
    }
}

fn beam(poisson: f64) -> ShellProperties {
    ShellProperties {
        length: 1.0,
        width: 0.1,
        thickness: 1e-3,
        young: 1.0e9,
        poisson,
        density: 1000.0,
    }
}

#[test]
fn small_loads_follow_linear_beam_theory() {
    // ν = 0, so D·w = EI and the plate is a beam. A uniform line load F/w across the free end
    // (as consistent point loads at the Gauss points of the width): tip deflection F L³/(3EI);
    // self-weight q = ρ h w g: q L⁴/(8EI). Cubic B-splines represent both cubic/quartic
    // deflections closely; the loads are small enough for the nonlinearity to be < 1e-5.
    let p = beam(0.0);
    let ei = p.bending_stiffness() * p.width;
    let force = 1e-4 * ei / p.length.powi(2);
    let (xg, wg) = gauss_legendre(4);
    let mut b = BsplineShellBuilder::new(p)
        .elements(8, 1)
        .grading(Grading::Uniform);
    for (x, w) in xg.iter().zip(&wg) {
        b = b.point_load(PointLoad {
            u: p.length,
            v: 0.5 * p.width * x,
            force: [0.0, -force * 0.5 * w, 0.0],
        });
    }
    let shell = b.build().unwrap();
    let start = shell.rest_state();
    let mut solver = EquilibriumSolver::new(&shell, &start, SolverParams::default());
    let sol = solver.solve(&shell, &start, 0.0, 1.0);
    assert!(sol.report.converged());
    let tip = -shell.point(&sol.state, p.length, 0.0).y;
    let expected = force * p.length.powi(3) / (3.0 * ei);
    assert!(
        (tip / expected - 1.0).abs() < 1e-4,
        "point load: {tip} vs {expected}"
    );

    let gamma = 1e-3;
    let g = p.gravity_for_gamma(gamma);
    let shell = BsplineShellBuilder::new(p)
        .elements(8, 1)
        .gravity(Vector3::new(0.0, -g, 0.0))
        .build()
        .unwrap();
    let mut solver = EquilibriumSolver::new(&shell, &start, SolverParams::default());
    let sol = solver.solve(&shell, &shell.rest_state(), 0.0, 1.0);
    assert!(sol.report.converged());
    let tip = -shell.point(&sol.state, p.length, 0.0).y;
    assert!(
        (tip / (gamma / 8.0) - 1.0).abs() < 1e-4,
        "self-weight: {tip} vs {}",
        gamma / 8.0
    );
}

#[test]
fn the_newton_memory_changes_the_hessian_only() {
    // A state produced by a step carries the step's second-order strain: energy and gradient
    // are those of the positions alone, the merit leaves out the remainder's membrane energy,
    // and the Hessian differs only by the membrane's geometric stiffness (Σ ΔS ∂²a).
    let shell = &shells()[0];
    let mut rng = Rng(7);
    let base = random_state(shell, &mut rng);
    let n = shell.n_free();
    let dx: Vec<f64> = (0..n).map(|_| 0.05 * rng.uniform()).collect();
    let mut stepped = base.clone();
    shell.displace(&base, &dx, 1.0, &mut stepped);
    assert!(!stepped.membrane_remainder.is_empty());
    let mut fresh = stepped.clone();
    fresh.membrane_remainder.clear();
    let (mut g1, mut g2) = (vec![0.0; n], vec![0.0; n]);
    let (mut h1, mut h2) = (shell.sparse_hessian(), shell.sparse_hessian());
    let e1 = shell.assemble_terms(
        &stepped,
        1.0,
        TermSet::ALL,
        Some(&mut g1),
        Some(&mut h1),
        None,
    );
    let e2 = shell.assemble_terms(
        &fresh,
        1.0,
        TermSet::ALL,
        Some(&mut g2),
        Some(&mut h2),
        None,
    );
    assert_eq!(e1.energy, e2.energy);
    assert_eq!(g1, g2);
    let merit = shell.merit(&stepped, 1.0);
    assert!(merit < e1.energy);
    assert_eq!(shell.merit(&fresh, 1.0), e2.energy);
    let mut differs = false;
    for i in 0..n {
        for j in 0..n {
            differs |= h1.get(i, j) != h2.get(i, j);
        }
    }
    assert!(differs, "the remainder must enter the geometric stiffness");
    // Without bending and with a zero remainder the membrane Hessian is exact (checked above
    // by the derivative checker); with the remainder only entries coupling the same
    // coordinate of two control points change (the geometric term is a multiple of I₃).
    let mut hm1 = shell.sparse_hessian();
    let mut hm2 = shell.sparse_hessian();
    shell.assemble_terms(&stepped, 1.0, MEMBRANE.set(), None, Some(&mut hm1), None);
    shell.assemble_terms(&fresh, 1.0, MEMBRANE.set(), None, Some(&mut hm2), None);
    for i in 0..n {
        for j in 0..n {
            let (ci, cj) = (i % 3, j % 3);
            if ci != cj {
                assert_eq!(hm1.get(i, j), hm2.get(i, j), "({i}, {j})");
            }
        }
    }
}

#[test]
fn a_turning_clamp_carries_a_cantilever_rigidly() {
    // Without loads, turning the only clamp turns the strip rigidly: the first guess of the
    // load path is already the equilibrium.
    let mut shell = BsplineShellBuilder::new(beam(0.3))
        .elements(6, 2)
        .build()
        .unwrap();
    shell
        .set_load_path(BsplineLoadPath::clamp_motion(vec![ClampMotion::about_x(
            StripEnd::Start,
            0.7,
        )]))
        .unwrap();
    let start = shell.rest_state();
    let mut solver = EquilibriumSolver::new(&shell, &start, SolverParams::default());
    let sol = solver.solve(&shell, &start, 0.0, 1.0);
    assert!(sol.report.converged());
    assert!(sol.report.iterations <= 2, "{}", sol.report.iterations);
    let rot = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.7);
    for (k, x) in sol.state.control_points.iter().enumerate() {
        assert!((x - rot * shell.patch().rest_points[k]).norm() < 1e-12);
    }
    // Moving a free end is refused.
    assert!(shell
        .set_load_path(BsplineLoadPath::clamp_motion(vec![ClampMotion::about_x(
            StripEnd::End,
            0.1
        )]))
        .is_err());
}

#[test]
fn the_membrane_rule_leaves_no_zero_energy_mode() {
    // The Greville rule samples the membrane at fewer points than Gauss: the unloaded flat
    // strip's Hessian must still be positive definite (no in-plane mechanism), for every
    // degree, one or several elements across, one clamp or two.
    for (degree, n_length, n_width, both) in [
        (2, 1, 1, false),
        (2, 8, 1, false),
        (3, 1, 1, false),
        (3, 8, 1, false),
        (3, 8, 8, false),
        (3, 5, 3, true),
        (4, 8, 2, false),
        (4, 2, 2, true),
    ] {
        let mut b = BsplineShellBuilder::new(beam(0.3))
            .degree(degree)
            .elements(n_length, n_width);
        if both {
            b = b.clamp(StripEnd::End, Clamp::default());
        }
        let shell = b.build().unwrap();
        let rest = shell.rest_state();
        let mut solver = EquilibriumSolver::new(&shell, &rest, SolverParams::default());
        let sol = solver.solve(&shell, &rest, 0.0, 0.0);
        let inertia = sol.report.inertia.expect("factored");
        assert!(
            inertia.negative == 0 && inertia.zero == 0,
            "p = {degree}, {n_length} × {n_width}, both clamped {both}: {inertia:?}"
        );
        assert!(sol.report.lambda_min.unwrap() > 0.0);
    }
}

#[test]
fn strongly_bent_strips_on_graded_meshes_are_stable() {
    // Regression for the membrane rule: with Greville points across the width too, a strongly
    // bent strip on the boundary-layer mesh (elements 30 times longer across than along near
    // the clamp) showed in-plane mechanisms turned unstable by the membrane stress (negative
    // eigenvalues of order −10⁶ D/(ρhL⁴)). A hanging cantilever is stable.
    let p = ShellProperties {
        length: 0.1,
        width: 0.01,
        thickness: 0.2e-3,
        young: 10530e6,
        poisson: 0.35,
        density: 1000.0,
    };
    for (n_length, n_width, gamma) in [(30, 3, 522.0), (30, 1, 522.0), (8, 1, 3070.0)] {
        let shell = BsplineShellBuilder::new(p)
            .elements(n_length, n_width)
            .grading(Grading::BoundaryLayer { gamma })
            .gravity(Vector3::new(0.0, -p.gravity_for_gamma(gamma), 0.0))
            .build()
            .unwrap();
        let start = shell.rest_state();
        let mut solver = EquilibriumSolver::new(&shell, &start, SolverParams::default());
        let sol = solver.solve(&shell, &start, 0.0, 1.0);
        assert!(sol.report.converged(), "{:?}", sol.report.status);
        assert_eq!(
            sol.report.inertia.map(|i| i.negative),
            Some(0),
            "{n_length} × {n_width}, Γ = {gamma}: λ_min = {:?}",
            sol.report.lambda_min_normalized
        );
        assert!(sol.report.iterations <= 60, "{}", sol.report.iterations);
    }
}
