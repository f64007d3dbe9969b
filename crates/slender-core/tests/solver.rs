//! The solver against closed forms, and its reporting.

use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, Rod, RodBuilder, RodProperties, SectionStiffness};
use slender_core::solver::{EquilibriumSolver, SolveStatus, SolverParams};

fn props(ei: f64) -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(1e9, ei, 0.8 * ei),
        linear_density: 0.2,
    }
}

/// A straight rod of length `l` along x.
fn straight(l: f64, ei: f64) -> RodBuilder {
    RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: l,
        },
        props(ei),
    )
}

fn solve(
    rod: &Rod,
    params: SolverParams,
) -> slender_core::solver::Solution<slender_core::rod::RodState> {
    let start = rod.rest_state().clone();
    EquilibriumSolver::new(rod, &start, params).solve(rod, &start, 0.0, 1.0)
}

#[test]
fn unloaded_rest_shapes_stop_at_iteration_zero() {
    let curves = [
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 2.0, 0.0],
            length: 1.0,
        },
        RestCurve::Circle {
            start: [0.0; 3],
            tangent: [0.0, 0.0, -1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 0.05,
            length: 2.0 * std::f64::consts::PI * 0.05 * 10.0, // 10 turns
        },
        RestCurve::Helix {
            start: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 0.1,
            pitch: 0.05,
            length: 3.0,
        },
    ];
    for c in curves {
        let rod = RodBuilder::new(c.clone(), props(1.0))
            .elements(200)
            .clamp_start()
            .build()
            .unwrap();
        let sol = solve(&rod, SolverParams::default());
        assert!(sol.report.converged(), "{c:?}");
        assert_eq!(sol.report.iterations, 0, "{c:?}");
        assert!(
            sol.report.residual < 1e-12,
            "{c:?}: {}",
            sol.report.residual
        );
        assert_eq!(sol.report.stable(), Some(true));
    }
}

#[test]
fn small_tip_load_matches_linear_beam_theory() {
    // δ = P L³ / (3 EI): exact for the continuum in the small-load limit; the discrete rod with
    // a half-cell clamp converges to it at second order.
    let (ei, l, p): (f64, f64, f64) = (2.0, 1.5, 1e-4);
    let exact = p * l.powi(3) / (3.0 * ei);
    let mut errors = Vec::new();
    for n in [10, 20, 40] {
        let rod = straight(l, ei)
            .elements(n)
            .clamp_start()
            .point_force(n, Vec3::new(0.0, 0.0, -p))
            .build()
            .unwrap();
        let sol = solve(&rod, SolverParams::default());
        assert!(sol.report.converged());
        let tip = sol.state.positions()[n];
        errors.push((-tip.z / exact - 1.0).abs());
    }
    assert!(errors[2] < 1e-3, "{errors:?}");
    assert!(
        errors[1] / errors[2] > 3.5,
        "second order expected: {errors:?}"
    );
}

#[test]
fn large_tip_load_matches_the_elastica() {
    // Cantilever with a dead end load P ⊥ the rod: for α = P L²/EI = 1 the classical elastica
    // (Bisshopp & Drucker 1945) gives tip deflections v/L = 0.3017, (L − u)/L = 0.0566.
    let (ei, l) = (1.0, 1.0);
    let n = 80;
    let rod = straight(l, ei)
        .elements(n)
        .grading(Grading::Uniform)
        .clamp_start()
        .point_force(n, Vec3::new(0.0, -1.0, 0.0))
        .build()
        .unwrap();
    let sol = solve(&rod, SolverParams::default());
    assert!(sol.report.converged());
    let tip = sol.state.positions()[n];
    assert!((-tip.y - 0.3017).abs() < 1e-3, "v/L = {}", -tip.y);
    assert!(
        (1.0 - tip.x - 0.0566).abs() < 1e-3,
        "(L−u)/L = {}",
        1.0 - tip.x
    );
}

#[test]
fn a_solve_that_cannot_converge_says_so() {
    let rod = straight(1.0, 1.0)
        .elements(20)
        .clamp_start()
        .gravity(Vec3::new(0.0, -5e5, 0.0))
        .build()
        .unwrap();
    // Γ = 10⁵ with one Newton iteration per step (ten on the snap retry) and steps no smaller
    // than 10 % of the load: out of reach.
    let params = SolverParams {
        max_iterations: 1,
        min_load_step: 0.1,
        ..Default::default()
    };
    let sol = solve(&rod, params);
    match &sol.report.status {
        SolveStatus::NotConverged { reason } => assert!(!reason.is_empty()),
        SolveStatus::Converged => panic!("one iteration cannot reach Γ = 1e5"),
    }
    assert!(sol.report.load_reached < 1.0);
    assert!(sol.report.residual > 0.0);
    assert_eq!(
        sol.report.stable(),
        None,
        "no stability claim without convergence"
    );
    assert!(sol.lowest_mode.is_none());
}

#[test]
fn a_rod_too_stiff_for_double_precision_is_not_reported_as_an_equilibrium() {
    // EA = 1e30 N: the stretching forces' rounding (EA·ε ≈ 1e14 N) drowns the weight (0.98 N).
    // The residual stalls under its round-off floor at ~1e14 N; that floor used to accept it,
    // and a scene solve of this rod reported a stable equilibrium with a clamp force of
    // 1.1e14 N against the weight (measured). Scenes now refuse such a section
    // (tests/scene_precision.rs); the solver, which other callers reach directly, must still
    // not call it an equilibrium. The same cantilever with EA = 1e6 N converges.
    let cantilever = |ea: f64| {
        let props = RodProperties {
            stiffness: SectionStiffness {
                ea,
                ei1: 0.05,
                ei2: 0.05,
                gj: 0.04,
            },
            linear_density: 0.1,
        };
        RodBuilder::new(
            RestCurve::Straight {
                start: [0.0; 3],
                direction: [1.0, 0.0, 0.0],
                length: 1.0,
            },
            props,
        )
        .elements(20)
        .clamp_start()
        .gravity(Vec3::new(0.0, -9.81, 0.0))
        .build()
        .unwrap()
    };
    let sane = solve(&cantilever(1e6), SolverParams::default());
    assert!(
        sane.report.converged() && sane.report.relative_residual <= 1e-6,
        "{:?}",
        sane.report
    );
    let stiff = solve(&cantilever(1e30), SolverParams::default());
    let r = &stiff.report;
    assert!(
        !r.converged(),
        "residual {} N ({} of the loads) reported as an equilibrium",
        r.residual,
        r.relative_residual
    );
    assert_eq!(r.stable(), None);
}

#[test]
fn a_solve_past_its_iteration_budget_stops_and_says_so() {
    // A heavy cantilever (Γ = 100) ramped in load steps of 1/500: about three Newton
    // iterations each, some 1500 in all. With a budget of 200 the solve must stop early, say
    // why and where, and claim no equilibrium at the requested load; with the default budget
    // the same ramp converges, so the budget is what stopped it.
    let rod = straight(1.0, 1.0)
        .elements(20)
        .clamp_start()
        .gravity(Vec3::new(0.0, -500.0, 0.0))
        .build()
        .unwrap();
    let ramp = SolverParams {
        initial_load_step: 2e-3,
        max_load_step: 2e-3,
        ..Default::default()
    };
    let budget = 200;
    let sol = solve(
        &rod,
        SolverParams {
            max_total_iterations: budget,
            ..ramp
        },
    );
    match &sol.report.status {
        SolveStatus::NotConverged { reason } => assert!(
            reason.contains("max_total_iterations") && reason.contains("200"),
            "{reason}"
        ),
        SolveStatus::Converged => panic!("200 iterations cannot take 500 load steps"),
    }
    assert!(
        sol.report.load_reached > 0.0 && sol.report.load_reached < 0.5,
        "{}",
        sol.report.load_reached
    );
    // The budget is checked before each load step: one step's Newton solve (and its snap
    // retry) may finish past it, no more.
    let defaults = SolverParams::default();
    assert!(
        sol.report.iterations >= budget
            && sol.report.iterations < budget + defaults.max_iterations + defaults.snap_iterations,
        "{} iterations",
        sol.report.iterations
    );
    assert_eq!(sol.report.stable(), None);

    let full = solve(&rod, ramp);
    assert!(full.report.converged(), "{:?}", full.report.status);
    assert!(
        full.report.iterations > budget,
        "{} iterations",
        full.report.iterations
    );
}

#[test]
fn an_iteration_budget_below_one_load_step_is_refused() {
    let params = SolverParams {
        max_iterations: 30,
        max_total_iterations: 29,
        ..Default::default()
    };
    let e = params.validate().unwrap_err().to_string();
    assert!(
        e.contains("max_total_iterations") && e.contains(">= max_iterations"),
        "{e}"
    );
}

#[test]
fn stability_margin_matches_the_cantilever_frequency() {
    // Unloaded clamped-free beam: lowest ω² = (1.8751)⁴ EI/(ρA L⁴) = 12.362 EI/(ρA L⁴).
    let rod = straight(1.0, 1.0)
        .elements(100)
        .clamp_start()
        .build()
        .unwrap();
    let sol = solve(&rod, SolverParams::default());
    let lam = sol.report.lambda_min_normalized.unwrap();
    assert!(
        (lam / 1.875_104_f64.powi(4) - 1.0).abs() < 2e-3,
        "λ̂ = {lam}"
    );
}

#[test]
fn greenhill_heavy_column_loses_stability_at_7_837() {
    // A clamped rod standing up under its own weight buckles at ρA g L³/EI = 7.837
    // (Greenhill 1881). Below: stable (no negative pivot); above: the upright state is an
    // unstable equilibrium, which the inertia reports.
    for (gamma, stable) in [(7.6, true), (8.1, false)] {
        let rod = RodBuilder::new(
            RestCurve::Straight {
                start: [0.0; 3],
                direction: [0.0, 0.0, 1.0],
                length: 1.0,
            },
            props(1.0),
        )
        .elements(60)
        .clamp_start()
        .gravity(Vec3::new(0.0, 0.0, -gamma / 0.2))
        .build()
        .unwrap();
        let sol = solve(&rod, SolverParams::default());
        assert!(sol.report.converged(), "Γ = {gamma}");
        assert_eq!(
            sol.report.stable(),
            Some(stable),
            "Γ = {gamma}: {:?}",
            sol.report.inertia
        );
        let lam = sol.report.lambda_min.unwrap();
        assert_eq!(lam > 0.0, stable, "Γ = {gamma}: λ_min = {lam}");
    }
}

#[test]
fn end_moment_rolls_the_rod_into_a_circle() {
    // A constant end moment M bends an inextensible rod into an arc of radius EI/M: the tip of
    // a rod of length L is at (R sin(L/R), R(1 − cos(L/R))). M = π EI/L: a half circle; 2π EI/L:
    // a full circle, the tip back at the clamp (tip rotation 2π: the load angle must unwrap).
    // The discrete curvature 2 tan(φ/2) makes the polygon turn slightly less than the arc:
    // an O(h²) error, so the check is second-order convergence to the closed form.
    let (ei, l) = (1.0_f64, 1.0_f64);
    for turns in [0.5_f64, 1.0] {
        let m = 2.0 * std::f64::consts::PI * turns * ei / l;
        let r = ei / m;
        let exact = Vec3::new(r * (l / r).sin(), r * (1.0 - (l / r).cos()), 0.0);
        let tip_error = |n: usize| {
            let rod = straight(l, ei)
                .elements(n)
                .clamp_start()
                .point_moment(n, Vec3::new(0.0, 0.0, m))
                .build()
                .unwrap();
            let sol = solve(&rod, SolverParams::default());
            assert!(sol.report.converged(), "{:?}", sol.report.status);
            (sol.state.positions()[n] - exact).norm() / l
        };
        let (coarse, fine) = (tip_error(32), tip_error(64));
        assert!(fine < 4e-3, "turns {turns}: tip error {fine}");
        assert!(
            coarse / fine > 3.5,
            "turns {turns}: errors {coarse}, {fine}: not second order"
        );
    }
}

#[test]
fn axial_torque_twists_the_rod_uniformly() {
    // An end torque T about the axis of a straight clamped rod: twist rate T/GJ, end rotation
    // T L/GJ, no bending.
    let (ei, l, n) = (1.0_f64, 2.0_f64, 10);
    let gj = 0.8 * ei;
    let t = 0.3;
    let rod = straight(l, ei)
        .elements(n)
        .clamp_start()
        .point_moment(n, Vec3::new(t, 0.0, 0.0))
        .build()
        .unwrap();
    let sol = solve(&rod, SolverParams::default());
    assert!(sol.report.converged());
    // The last edge's θ is measured from the rest frame; half a cell from the free end.
    let theta = sol.state.thetas()[n - 1];
    let expected = t / gj * (l - 0.5 * l / n as f64);
    assert!(
        (theta / expected - 1.0).abs() < 1e-6,
        "θ = {theta}, expected {expected}"
    );
}

#[test]
fn a_non_finite_load_range_is_refused_not_stepped_forever() {
    let rod = straight(1.0, 1.0)
        .clamp_start()
        .gravity(Vec3::new(0.0, -1.0, 0.0))
        .build()
        .unwrap();
    let rest = rod.rest_state().clone();
    let mut solver = EquilibriumSolver::new(&rod, &rest, SolverParams::default());
    for to in [f64::NAN, f64::INFINITY] {
        let r = solver.solve(&rod, &rest, 0.0, to);
        assert!(!r.report.converged(), "{to}: {:?}", r.report);
        assert!(
            format!("{:?}", r.report.status).contains("not finite"),
            "{:?}",
            r.report.status
        );
    }
}

/// E(x) = √(1 + x²) − f·x, one DOF: convex (E″ = (1 + x²)^(−3/2) > 0), but far from the
/// equilibrium x = f/√(1 − f²) the full Newton step overshoots to a higher energy and the line
/// search must cut it.
struct Hyperbola {
    force: f64,
}

impl slender_core::solver::MassMetric for Hyperbola {
    fn inertia_metric(&self, _: usize) -> f64 {
        1.0
    }
    fn eigenvalue_scale(&self) -> f64 {
        1.0
    }
}

impl slender_core::solver::EquilibriumProblem for Hyperbola {
    type State = f64;
    type Hessian = slender_core::linalg::SymmetricBandMatrix;
    fn n_free(&self) -> usize {
        1
    }
    fn new_hessian(&self) -> Self::Hessian {
        slender_core::linalg::SymmetricBandMatrix::new(1, 0)
    }
    fn term_groups(&self) -> &[slender_core::assembly::TermGroup] {
        &[]
    }
    fn assemble_selected<M: slender_core::linalg::SymmetricMatrix>(
        &self,
        x: &f64,
        load: f64,
        asm: &mut slender_core::assembly::Assembler<'_, M>,
    ) {
        let s = (1.0 + x * x).sqrt();
        let g = nalgebra::SVector::<f64, 1>::new(x / s);
        let h = nalgebra::SMatrix::<f64, 1, 1>::new(1.0 / (s * s * s));
        asm.local(&[0], s, s, &g, &h);
        let f = load * self.force;
        asm.load(f * x, f.abs());
        asm.generalized_force(0, f);
    }
    fn merit_is_energy(&self) -> bool {
        true
    }
    fn difference(&self, a: &f64, b: &f64, out: &mut [f64]) {
        out[0] = a - b;
    }
    fn displace(&self, x: &f64, dx: &[f64], alpha: f64, out: &mut f64) {
        *out = x + alpha * dx[0];
    }
    fn max_step(&self, _: &f64, _: &[f64]) -> f64 {
        1.0
    }
    fn force_length(&self, _: usize) -> f64 {
        1.0
    }
    fn dof_magnitude(&self, _: &f64, _: usize) -> f64 {
        1.0
    }
}

#[test]
fn a_deferred_energy_test_undoes_a_rejected_full_step_and_backtracks_as_before() {
    use slender_core::solver::{newton, NewtonWorkspace, SolverParams};
    let problem = Hyperbola { force: 0.5 };
    let exact = 0.5 / 0.75_f64.sqrt();
    let run = |start: f64, deferred: bool| {
        let params = SolverParams {
            deferred_energy_check: deferred,
            ..SolverParams::default()
        };
        let mut x = start;
        let mut ws = NewtonWorkspace::new(&problem, &x);
        let out = newton(&problem, &mut x, 1.0, &params, &mut ws);
        assert!(out.converged, "start {start}, deferred {deferred}: {out:?}");
        assert!((x - exact).abs() < 1e-8, "start {start}: x = {x}");
        (x, out.iterations)
    };
    // From x = 3 the full step lands at x ≈ −11 (energy 16.8 against 1.66) and the line search
    // accepts α = 1/4. Deferred, the step is taken, judged by the next measure, undone and
    // backtracked from α = 1/2 to the same point: the same iterates one measure later.
    let (plain, plain_its) = run(3.0, false);
    let (deferred, deferred_its) = run(3.0, true);
    assert_eq!(plain.to_bits(), deferred.to_bits());
    assert_eq!(deferred_its, plain_its + 1);
    // Near the equilibrium every full step passes: the same iterates, no extra measure.
    let (plain, plain_its) = run(0.7, false);
    let (deferred, deferred_its) = run(0.7, true);
    assert_eq!(plain.to_bits(), deferred.to_bits());
    assert_eq!(deferred_its, plain_its);
}
