//! Implicit dynamics against closed forms: cantilever frequencies (Euler–Bernoulli), energy
//! conservation and dissipation, the schemes' orders of convergence, free fall, bad input.
//!
//! Run: `cargo test -p slender-core --release --test integration dynamics:: -- --skip framed --nocapture` (prints the
//! measured figures).

use nalgebra::{DMatrix, SymmetricEigen};
use slender_core::cosserat::CosseratBuilder;
use slender_core::dynamics::{DynamicsParams, LumpedMass, Scheme, TimeStepper};
use slender_core::framed::ShearStiffness;
use slender_core::geometry::Vec3;
use slender_core::rod::{RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness};
use slender_core::solver::EquilibriumProblem;
use slender_core::structure::{JointEnd, Member, Structure, StructureBuilder};
use slender_core::ModelError;

/// Section of the README's example cable: EA (N), EI, GJ (N m²), ρA (kg/m).
const EA: f64 = 9.21e5;
const EI: f64 = 4.5e-2;
const GJ: f64 = 3.75e-2;
const RHO_A: f64 = 0.281;
const LENGTH: f64 = 1.0;
const G: f64 = 9.81;

fn props() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(EA, EI, GJ),
        linear_density: RHO_A,
    }
}

fn straight(n: usize) -> RodBuilder {
    RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: LENGTH,
        },
        props(),
    )
    .elements(n)
}

fn cantilever(n: usize, gravity: bool) -> Rod {
    let b = straight(n).clamp_start();
    let b = if gravity {
        b.gravity(Vec3::new(0.0, -G, 0.0))
    } else {
        b
    };
    b.build().expect("valid rod")
}

/// Roots of 1 + cos β cosh β = 0 (the clamped–free Euler–Bernoulli beam) by bisection near
/// the tabulated β₁ = 1.8751, β₂ = 4.6941, β₃ = 7.8548.
fn euler_bernoulli_betas() -> [f64; 3] {
    let f = |b: f64| 1.0 + b.cos() * b.cosh();
    [1.8751, 4.6941, 7.8548].map(|guess| {
        let (mut lo, mut hi) = (guess - 0.1, guess + 0.1);
        assert!(f(lo) * f(hi) < 0.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if f(lo) * f(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    })
}

/// ω_k = β_k² √(EI/(ρA L⁴)) (rad/s).
fn euler_bernoulli_omegas() -> [f64; 3] {
    euler_bernoulli_betas().map(|b| b * b * (EI / (RHO_A * LENGTH.powi(4))).sqrt())
}

fn tip(rod: &Rod, s: &RodState) -> Vec3 {
    s.positions()[rod.n_edges()]
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b) / b
}

#[test]
fn lumped_mass_is_voronoi_vertex_mass_and_polar_twist_inertia() {
    let rod = cantilever(50, false);
    let mass = LumpedMass::of(&rod).unwrap();
    let (mut coord, mut twist) = (0.0, 0.0);
    for (i, &m) in mass.diagonal().iter().enumerate() {
        if rod.dofs().is_angle(i) {
            twist += m;
        } else {
            coord += m;
        }
    }
    // The clamped vertex holds half of the first edge's mass; the free ones the rest, per
    // coordinate.
    let h = LENGTH / 50.0;
    assert!((coord / 3.0 - RHO_A * (LENGTH - 0.5 * h)).abs() < 1e-12);
    // ρJ L with J = I₁ + I₂ = (EI₁ + EI₂)/E and ρ = ρA/A: ρA (EI₁ + EI₂)/EA per length.
    assert!((twist - RHO_A * 2.0 * EI / EA * LENGTH).abs() < 1e-15);
}

/// The dense generalized eigenproblem K v = ω² M v at the straight state: transverse
/// (bending) frequencies, ascending, one per degenerate pair (rad/s).
fn bending_frequencies(rod: &Rod) -> Vec<f64> {
    let n = rod.n_free();
    let s = rod.rest_state().clone();
    let mut hess = rod.new_hessian();
    let (mut g, mut a) = (vec![0.0; n], vec![0.0; n]);
    rod.assemble(&s, 1.0, &mut g, &mut hess, &mut a);
    let mass = LumpedMass::of(rod).unwrap();
    let inv_sqrt: Vec<f64> = mass.diagonal().iter().map(|m| 1.0 / m.sqrt()).collect();
    let mut k = DMatrix::<f64>::zeros(n, n);
    let (mut e, mut col) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..n {
        e.fill(0.0);
        e[j] = 1.0;
        hess.mul_vec(&e, &mut col);
        for i in 0..n {
            k[(i, j)] = inv_sqrt[i] * col[i] * inv_sqrt[j];
        }
    }
    let eig = SymmetricEigen::new(k);
    let mut bending: Vec<f64> = (0..n)
        .filter(|&m| {
            let u = eig.eigenvectors.column(m);
            let transverse: f64 = (0..n)
                .filter(|&i| matches!(rod.dofs().full_index(i) % 4, 1 | 2))
                .map(|i| u[i] * u[i])
                .sum();
            transverse > 0.9
        })
        .map(|m| eig.eigenvalues[m].max(0.0).sqrt())
        .collect();
    bending.sort_by(f64::total_cmp);
    // Isotropic section: the y and z modes come in pairs.
    for p in bending.chunks(2).take(3) {
        assert!(
            (p[0] - p[1]).abs() <= 1e-6 * p[0],
            "pair {p:?} not degenerate"
        );
    }
    bending.iter().step_by(2).take(3).cloned().collect()
}

#[test]
fn cantilever_frequencies_match_euler_bernoulli() {
    let rod = cantilever(50, false);
    let measured = bending_frequencies(&rod);
    let exact = euler_bernoulli_omegas();
    for k in 0..3 {
        let err = relative(measured[k], exact[k]);
        println!(
            "mode {}: omega = {:.6} rad/s, Euler-Bernoulli {:.6} rad/s, relative error {:+.3e}",
            k + 1,
            measured[k],
            exact[k],
            err
        );
        assert!(err.abs() <= 5e-3, "mode {} off by {err:.3e}", k + 1);
    }
}

/// The clamped–free Euler–Bernoulli first mode shape φ(s), φ(L) = 1 normalized by the caller.
fn first_mode_shape(s: f64) -> f64 {
    let b = euler_bernoulli_betas()[0] / LENGTH;
    let bl = b * LENGTH;
    let sigma = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
    let x = b * s;
    x.cosh() - x.cos() - sigma * (x.sinh() - x.sin())
}

/// The rest state with every free vertex moved by `amplitude·φ(s)/φ(L)` along y.
fn mode_one_deflection(rod: &Rod, amplitude: f64) -> RodState {
    let n = rod.n_edges();
    let mut dx = vec![0.0; rod.n_free()];
    for v in 0..=n {
        let i = rod.dofs().vertex(v, 1);
        if i != usize::MAX {
            let s = LENGTH * v as f64 / n as f64;
            dx[i] = amplitude * first_mode_shape(s) / first_mode_shape(LENGTH);
        }
    }
    let mut out = rod.rest_state().clone();
    // The retraction walks the edges from the clamp, so the deflection does not stretch them.
    rod.retract(rod.rest_state(), &dx, 1.0, &mut out);
    out
}

/// Zero crossings (s) of a sampled signal, by linear interpolation.
fn zero_crossings(t: &[f64], y: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 1..y.len() {
        if y[k - 1] != 0.0 && y[k - 1].signum() != y[k].signum() {
            out.push(t[k - 1] + (t[k] - t[k - 1]) * y[k - 1] / (y[k - 1] - y[k]));
        }
    }
    out
}

#[test]
fn cantilever_first_frequency_from_a_time_history() {
    let rod = cantilever(50, false);
    let exact = euler_bernoulli_omegas()[0];
    let period = 2.0 * std::f64::consts::PI / exact;
    let dt = period / 400.0;
    let start = mode_one_deflection(&rod, 1e-4 * LENGTH);
    let params = DynamicsParams::new(dt).with_scheme(Scheme::ImplicitMidpoint);
    let mut stepper = TimeStepper::at_rest(&rod, start, params).unwrap();
    let (mut t, mut y) = (vec![0.0], vec![tip(&rod, stepper.state()).y]);
    for _ in 0..(4 * 400 + 50) {
        let r = stepper.step();
        assert!(r.converged, "{r:?}");
        t.push(stepper.time());
        y.push(tip(&rod, stepper.state()).y);
    }
    let crossings = zero_crossings(&t, &y);
    assert!(crossings.len() >= 8, "{} crossings", crossings.len());
    // Least-squares slope of the crossing times against their index: half the period.
    let m = crossings.len() as f64;
    let k_mean = (m - 1.0) / 2.0;
    let t_mean = crossings.iter().sum::<f64>() / m;
    let (mut num, mut den) = (0.0, 0.0);
    for (k, &tc) in crossings.iter().enumerate() {
        num += (k as f64 - k_mean) * (tc - t_mean);
        den += (k as f64 - k_mean).powi(2);
    }
    let omega = std::f64::consts::PI / (num / den);
    let err = relative(omega, exact);
    println!(
        "time history (implicit midpoint, h = T/400, {} crossings): omega_1 = {omega:.6} rad/s, \
         Euler-Bernoulli {exact:.6}, relative error {err:+.3e}",
        crossings.len()
    );
    assert!(err.abs() <= 5e-3, "omega_1 off by {err:.3e}");
}

/// A cantilever held horizontal under gravity and released: (max relative energy change,
/// largest kinetic energy) over `steps` steps of `dt`.
fn release_under_gravity(scheme: Scheme, dt: f64, steps: usize) -> (Vec<f64>, f64) {
    let rod = cantilever(20, true);
    let mut params = DynamicsParams::new(dt).with_scheme(scheme);
    params.solver.force_tolerance = 1e-13;
    params.solver.energy_tolerance = 1e-20;
    let mut stepper = TimeStepper::at_rest(&rod, rod.rest_state().clone(), params).unwrap();
    let mut totals = vec![stepper.energy().total()];
    let mut kinetic: f64 = 0.0;
    for _ in 0..steps {
        let r = stepper.step();
        assert!(r.converged, "{r:?}");
        let e = stepper.energy();
        totals.push(e.total());
        kinetic = kinetic.max(e.kinetic);
    }
    (totals, kinetic)
}

/// max |E − E₀| over the run, relative to the largest kinetic energy (E₀ = 0 here: the
/// straight rod at rest is the zero of both elastic and gravity energy).
fn energy_drift(totals: &[f64], kinetic: f64) -> f64 {
    totals
        .iter()
        .map(|e| (e - totals[0]).abs())
        .fold(0.0, f64::max)
        / kinetic
}

#[test]
fn energy_conserving_scheme_conserves_energy_of_a_released_cantilever() {
    // Γ = ρAgL³/EI ≈ 61: the tip falls by about half the length and swings back.
    let (totals, kinetic) = release_under_gravity(Scheme::EnergyConserving, 2e-3, 1000);
    let drift = energy_drift(&totals, kinetic);
    println!(
        "energy-conserving (3-point average), 1000 steps of 2 ms: max |E - E0| / max kinetic \
         = {drift:.3e} (max kinetic {kinetic:.4e} J)"
    );
    // The swing is large: at least a tenth of the energy a rigid fall by L/2 would release.
    assert!(kinetic > 0.1 * RHO_A * LENGTH * G * 0.5 * LENGTH);
    assert!(drift <= 1e-6, "energy drift {drift:.3e}");
}

#[test]
fn implicit_midpoint_drifts_where_the_energy_conserving_scheme_does_not() {
    // Measured, to show why the energy-conserving scheme exists: the midpoint rule is exact
    // for quadratic energies only, and on this large swing (the tip passes behind the clamp)
    // the stiff, unresolved stretching (ωh ≈ 10²) pumps energy into the motion.
    let (totals, kinetic) = release_under_gravity(Scheme::ImplicitMidpoint, 2e-3, 1000);
    let midpoint = energy_drift(&totals, kinetic);
    let (totals, kinetic) = release_under_gravity(Scheme::EnergyConserving, 2e-3, 1000);
    let conserving = energy_drift(&totals, kinetic);
    println!(
        "same swing, max |E - E0| / max kinetic: implicit midpoint {midpoint:.3e}, \
         energy-conserving {conserving:.3e}"
    );
    assert!(midpoint.is_finite());
    assert!(conserving * 1e3 < midpoint);
}

#[test]
fn implicit_midpoint_conserves_energy_of_small_vibrations() {
    // Small amplitude: the energy is quadratic to within the amplitude, and the midpoint
    // rule (the trapezoidal rule of the linearized system) conserves it.
    let rod = cantilever(50, false);
    let start = mode_one_deflection(&rod, 1e-4 * LENGTH);
    let mut params = DynamicsParams::new(1e-2).with_scheme(Scheme::ImplicitMidpoint);
    params.solver.force_tolerance = 1e-13;
    params.solver.energy_tolerance = 1e-24;
    let mut stepper = TimeStepper::at_rest(&rod, start, params).unwrap();
    let e0 = stepper.energy().total();
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        assert!(stepper.step().converged);
        worst = worst.max((stepper.energy().total() - e0).abs() / e0);
    }
    println!(
        "implicit midpoint, small vibration, 1000 steps of 10 ms: max |E - E0| / E0 = {worst:.3e}"
    );
    assert!(worst <= 1e-6, "energy drift {worst:.3e}");
}

#[test]
fn backward_euler_dissipates_energy() {
    let (totals, kinetic) = release_under_gravity(Scheme::BackwardEuler, 2e-3, 1000);
    let lost = (totals[0] - totals[totals.len() - 1]) / kinetic;
    let rises = totals
        .windows(2)
        .filter(|w| w[1] > w[0] + 1e-9 * kinetic)
        .count();
    println!("backward Euler, 1000 steps of 2 ms: energy lost = {lost:.3e} of max kinetic, {rises} steps gained energy");
    assert!(lost > 1e-2, "backward Euler lost only {lost:.3e}");
    assert_eq!(rises, 0, "backward Euler should never gain energy here");
}

/// Tip position (m) at `t_end` of a cantilever (no gravity) set swinging from straight by
/// an initial velocity in the shape of the first mode, tip speed `tip_speed` (m/s), with
/// step `dt`.
///
/// A smooth start: releasing a straight cantilever under gravity jolts the clamp's stiffest
/// modes (amplitude ~ g/ω_max² ≈ 10⁻⁶ m), which no step here resolves (ω_max h ≫ 1) and
/// which the schemes treat differently (backward Euler damps them, the others keep them at
/// an aliased frequency): a dt-independent error that would hide the orders.
fn swing_tip_at(scheme: Scheme, dt: f64, t_end: f64, tip_speed: f64) -> Vec3 {
    let rod = cantilever(20, false);
    let n = rod.n_edges();
    let mut velocity = vec![0.0; rod.n_free()];
    for v in 1..=n {
        let s = LENGTH * v as f64 / n as f64;
        velocity[rod.dofs().vertex(v, 1)] =
            tip_speed * first_mode_shape(s) / first_mode_shape(LENGTH);
    }
    let params = DynamicsParams::new(dt).with_scheme(scheme);
    let mut stepper = TimeStepper::new(&rod, rod.rest_state().clone(), velocity, params).unwrap();
    let steps = (t_end / dt).round() as usize;
    assert!((steps as f64 * dt - t_end).abs() < 1e-9);
    for _ in 0..steps {
        let r = stepper.step();
        assert!(r.converged, "{scheme:?}, dt = {dt}: {r:?}");
    }
    tip(&rod, stepper.state())
}

/// Observed orders log(e₁/e₂)/log(h₁/h₂) of the tip error at t_end for three steps.
fn observed_orders(scheme: Scheme, dts: [f64; 3], reference: Vec3, t_end: f64, v: f64) -> [f64; 2] {
    let errors = dts.map(|dt| (swing_tip_at(scheme, dt, t_end, v) - reference).norm());
    let orders = [
        (errors[0] / errors[1]).ln() / (dts[0] / dts[1]).ln(),
        (errors[1] / errors[2]).ln() / (dts[1] / dts[2]).ln(),
    ];
    println!(
        "{scheme:?}: dt = {dts:?} s, tip errors = {:?} m, observed orders = {orders:.3?}",
        errors.map(|e| format!("{e:.3e}"))
    );
    orders
}

#[test]
fn schemes_converge_at_their_orders() {
    // Tip speed 0.5 m/s: the tip swings out by about a third of the length (geometrically
    // nonlinear), and is at (0.99, 0.11) m at t = 2 s.
    let (t_end, v) = (2.0, 0.5);
    let reference = swing_tip_at(Scheme::ImplicitMidpoint, t_end / 25600.0, t_end, v);
    let dts = [t_end / 400.0, t_end / 800.0, t_end / 1600.0];
    for p in observed_orders(Scheme::BackwardEuler, dts, reference, t_end, v) {
        assert!((0.8..=1.3).contains(&p), "backward Euler order {p:.3}");
    }
    for p in observed_orders(Scheme::ImplicitMidpoint, dts, reference, t_end, v) {
        assert!((1.7..=2.4).contains(&p), "implicit midpoint order {p:.3}");
    }
    // The energy-conserving scheme is second order, but on these steps its error is still
    // dominated by higher-order terms (the force averaged along the straight chord of
    // rotating, stiff edges): the observed order is above 2 here, so only its lower bound
    // is asserted.
    for p in observed_orders(Scheme::EnergyConserving, dts, reference, t_end, v) {
        assert!(p >= 1.7, "energy-conserving order {p:.3}");
    }
}

#[test]
fn free_fall_is_exact_with_the_second_order_schemes() {
    let g = Vec3::new(0.3, -G, 1.2);
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.5, 0.0],
            length: LENGTH,
        },
        props(),
    )
    .elements(10)
    .allow_rigid_motion()
    .gravity(g)
    .build()
    .unwrap();
    let v0 = Vec3::new(0.5, 2.0, -1.0);
    let mut velocity = vec![0.0; rod.n_free()];
    for v in 0..=rod.n_edges() {
        for k in 0..3 {
            velocity[rod.dofs().vertex(v, k)] = v0[k];
        }
    }
    let dt = 0.01;
    let start = rod.rest_state().clone();
    for scheme in [Scheme::ImplicitMidpoint, Scheme::EnergyConserving] {
        // Newton to round-off: the test is about the scheme, not the solver's tolerance.
        let mut params = DynamicsParams::new(dt).with_scheme(scheme);
        params.solver.force_tolerance = 1e-14;
        let mut stepper = TimeStepper::new(&rod, start.clone(), velocity.clone(), params).unwrap();
        let mut worst: f64 = 0.0;
        for _ in 0..200 {
            assert!(stepper.step().converged);
            let t = stepper.time();
            for (x, x0) in stepper.state().positions().iter().zip(start.positions()) {
                let exact = x0 + v0 * t + g * (0.5 * t * t);
                worst = worst.max((x - exact).norm() / exact.norm().max(LENGTH));
            }
        }
        println!("free fall over 2 s, {scheme:?}: largest relative position error {worst:.3e}");
        // Round-off: ~ε per step, amplified by the conditioning of the step's Hessian
        // (stretching EA/l against m/h², ≈ 10⁴) in the Newton solve.
        assert!(worst < 1e-11, "{scheme:?}: free fall off by {worst:.3e}");
    }
    // Backward Euler is not exact (x_{n+1} = xₙ + h v_{n+1}): the test can tell.
    let params = DynamicsParams::new(dt).with_scheme(Scheme::BackwardEuler);
    let mut stepper = TimeStepper::new(&rod, start.clone(), velocity, params).unwrap();
    assert!(stepper.step().converged);
    let exact = start.positions()[0] + v0 * dt + g * (0.5 * dt * dt);
    assert!((stepper.state().positions()[0] - exact).norm() > 1e-6);
}

fn field_of(e: ModelError) -> String {
    match e {
        ModelError::InvalidParameter { field, .. } | ModelError::InvalidStructure { field, .. } => {
            field
        }
    }
}

#[test]
fn bad_input_names_the_field_and_range() {
    let rod = cantilever(5, true);
    let s = rod.rest_state().clone();
    let make = |p: DynamicsParams| TimeStepper::at_rest(&rod, s.clone(), p).err();
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = make(DynamicsParams::new(dt)).expect("dt rejected");
        let msg = e.to_string();
        assert!(msg.contains("`dt`") && msg.contains("> 0"), "{msg}");
    }
    let e = make(DynamicsParams::new(1e-3).with_rayleigh(-0.1, 0.0)).unwrap();
    assert_eq!(field_of(e.clone()), "rayleigh_mass");
    assert!(e.to_string().contains(">= 0"), "{e}");
    let e = make(DynamicsParams::new(1e-3).with_rayleigh(0.0, f64::NAN)).unwrap();
    assert_eq!(field_of(e), "rayleigh_stiffness");
    let e = TimeStepper::new(&rod, s.clone(), vec![0.0; 3], DynamicsParams::new(1e-3))
        .err()
        .unwrap();
    assert_eq!(field_of(e), "velocity");
    let mut v = vec![0.0; rod.n_free()];
    v[2] = f64::NAN;
    let e = TimeStepper::new(&rod, s.clone(), v, DynamicsParams::new(1e-3))
        .err()
        .unwrap();
    assert_eq!(field_of(e), "velocity[2]");
    let mut stepper = TimeStepper::at_rest(&rod, s.clone(), DynamicsParams::new(1e-3)).unwrap();
    let e = stepper.set_dt(f64::NAN).unwrap_err();
    assert_eq!(field_of(e), "dt");
    let mut p = DynamicsParams::new(1e-3);
    p.quadrature_points = 0;
    assert_eq!(field_of(make(p).unwrap()), "quadrature_points");
    println!("{}", make(DynamicsParams::new(-1.0)).unwrap());
}

#[test]
fn a_failed_step_says_so_and_does_not_advance() {
    let rod = cantilever(20, true);
    let mut params = DynamicsParams::new(0.5);
    params.solver.max_iterations = 1;
    let mut stepper = TimeStepper::at_rest(&rod, rod.rest_state().clone(), params).unwrap();
    let before = stepper.state().clone();
    let r = stepper.step();
    assert!(!r.converged);
    assert!(r.failure.is_some());
    assert_eq!(r.time, 0.0);
    assert_eq!(stepper.time(), 0.0);
    assert_eq!(stepper.state(), &before);
    assert!(stepper.velocity().iter().all(|&v| v == 0.0));
}

#[test]
fn rayleigh_damping_removes_energy_from_the_midpoint_rule() {
    let rod = cantilever(20, true);
    for (scheme, alpha, beta) in [
        (Scheme::EnergyConserving, 0.5, 0.0),
        (Scheme::EnergyConserving, 0.0, 2e-3),
        (Scheme::ImplicitMidpoint, 0.0, 2e-3),
    ] {
        let params = DynamicsParams::new(2e-3)
            .with_scheme(scheme)
            .with_rayleigh(alpha, beta);
        let mut stepper = TimeStepper::at_rest(&rod, rod.rest_state().clone(), params).unwrap();
        let e0 = stepper.energy().total();
        let mut kinetic: f64 = 0.0;
        for _ in 0..500 {
            assert!(stepper.step().converged);
            kinetic = kinetic.max(stepper.energy().kinetic);
        }
        let lost = (e0 - stepper.energy().total()) / kinetic;
        println!(
            "{scheme:?}, Rayleigh alpha = {alpha} 1/s, beta = {beta} s: lost {lost:.3e} of max \
             kinetic in 1 s"
        );
        assert!(lost > 1e-2, "damping lost only {lost:.3e}");
    }
}

/// Two discrete elastic rods joined at the origin at a right angle (a trunk along x ending
/// there, a branch leaving it along (1, 1, 0)), the trunk clamped at its start.
///
/// Not three: with a third member out of that plane ((1, −0.5, 0.3)), the first step's
/// Newton solve stalls at a residual of 7.6e-7 N (≈ 3·10⁻⁶ of a vertex weight) with every
/// scheme; the cause is not found yet (see the dynamics section of ARCHITECTURE.md).
fn branch(g: Vec3) -> Structure {
    let part = |start: [f64; 3], direction: [f64; 3], length: f64, n: usize| {
        RodBuilder::new(
            RestCurve::Straight {
                start,
                direction,
                length,
            },
            props(),
        )
        .elements(n)
        .allow_rigid_motion()
        .gravity(g)
    };
    let trunk = part([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0, 10).clamp_start();
    StructureBuilder::new()
        .member(Member::Der(trunk.build().unwrap()))
        .member(Member::Der(
            part([0.0; 3], [1.0, 1.0, 0.0], 0.7, 7).build().unwrap(),
        ))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 10,
            },
            JointEnd {
                member: 1,
                vertex: 0,
            },
        ])
        .build()
        .unwrap()
}

#[test]
fn a_jointed_structure_has_summed_joint_masses_and_conserves_energy() {
    // The joint's mass is the sum of the members' masses there, as its weight is: the
    // total is every member's mass once, less the clamped vertex's half edge.
    let clamped = branch(Vec3::new(0.0, -G, 0.0));
    let total: f64 = LumpedMass::of(&clamped).unwrap().diagonal().iter().sum();
    let lengths = [1.0, 0.7];
    let sum_l: f64 = lengths.iter().sum();
    let expected = 3.0 * RHO_A * (sum_l - 0.5 * 1.0 / 10.0) + RHO_A * 2.0 * EI / EA * sum_l;
    assert!(
        (total - expected).abs() <= 1e-12 * expected,
        "structure mass {total} kg, expected {expected} kg"
    );

    // Clamped trunk swinging under gravity: energy with the energy-conserving scheme.
    let mut params = DynamicsParams::new(2e-3);
    params.solver.force_tolerance = 1e-13;
    let mut stepper = TimeStepper::at_rest(&clamped, clamped.rest_state().clone(), params).unwrap();
    let e0 = stepper.energy().total();
    let (mut drift, mut kinetic): (f64, f64) = (0.0, 0.0);
    for _ in 0..500 {
        let r = stepper.step();
        assert!(r.converged, "{r:?}");
        let e = stepper.energy();
        drift = drift.max((e.total() - e0).abs());
        kinetic = kinetic.max(e.kinetic);
    }
    println!(
        "jointed structure, 500 steps of 2 ms: max |E - E0| / max kinetic = {:.3e}",
        drift / kinetic
    );
    assert!(kinetic > 0.0 && drift <= 1e-6 * kinetic);
}

#[test]
fn a_contact_problem_hands_a_cosserat_structures_frames_to_the_stepper() {
    // A structure of a Cosserat rod lists its frames and is stepped
    // (tests/framed_dynamics.rs); a contact problem around it passes them on (their rotary
    // inertia and orientations), so that its rotation DOFs are stepped as frames, not as
    // coordinates: with an obstacle it never touches, it steps the same motion to the bit.
    use slender_core::contact::{ContactParams, ContactProblem, Plane};
    let cosserat = CosseratBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: LENGTH,
        },
        props(),
        ShearStiffness { ga1: 1e5, ga2: 1e5 },
    )
    .elements(5)
    .clamp_start()
    .gravity(Vec3::new(0.0, -G, 0.0))
    .build()
    .unwrap();
    let s = StructureBuilder::new()
        .member(Member::Cosserat(cosserat))
        .build()
        .unwrap();
    let plane = Plane::new(Vec3::new(0.0, -10.0, 0.0), Vec3::y(), 0.0).unwrap();
    let contact = ContactProblem::new(
        &s,
        vec![std::sync::Arc::new(plane)],
        ContactParams::for_line_load(0.005, 1e-3, RHO_A * G),
        s.rest_state(),
    )
    .unwrap();
    let params = DynamicsParams::new(1e-3);
    let mut free = TimeStepper::at_rest(&s, s.rest_state().clone(), params).unwrap();
    let mut touching = TimeStepper::at_rest(&contact, s.rest_state().clone(), params)
        .expect("a contact problem around a Cosserat structure is stepped");
    assert_eq!(touching.mass().frames(), free.mass().frames());
    assert_eq!(touching.mass().frames().len(), 5, "one frame per edge");
    for _ in 0..50 {
        assert!(free.step().converged);
        assert!(touching.step().converged);
    }
    let (a, b) = (free.state(), touching.state());
    assert!(a.members[0].positions()[5].y < -1e-4, "the rod swings down");
    assert_eq!(a.members[0].positions(), b.members[0].positions());
    assert_eq!(free.velocity(), touching.velocity());
}

#[test]
fn one_point_average_is_the_implicit_midpoint_rule() {
    // With one Gauss node the averaged force is ∇E at xₙ + d/2: the energy-conserving
    // scheme's equations become the midpoint rule's, so the two trajectories must agree
    // (a check of the quadrature's weights and chart scaling).
    let rod = cantilever(20, true);
    let run = |scheme: Scheme, q: usize| {
        let mut params = DynamicsParams::new(2e-3).with_scheme(scheme);
        params.quadrature_points = q;
        params.solver.force_tolerance = 1e-13;
        let mut stepper = TimeStepper::at_rest(&rod, rod.rest_state().clone(), params).unwrap();
        for _ in 0..200 {
            assert!(stepper.step().converged);
        }
        stepper.state().positions().to_vec()
    };
    let midpoint = run(Scheme::ImplicitMidpoint, 3);
    let average = run(Scheme::EnergyConserving, 1);
    let gap = midpoint
        .iter()
        .zip(&average)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!("1-point average vs implicit midpoint after 200 steps: {gap:.3e} m");
    // Not bit-equal: the two solve different unknowns (x_{n+1} or x_{n+½}) to the Newton
    // tolerance, and the swing is nonlinear.
    assert!(gap < 1e-8, "gap {gap:.3e} m");
    let three = run(Scheme::EnergyConserving, 3);
    let gap3 = midpoint
        .iter()
        .zip(&three)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!("3-point average vs implicit midpoint after 200 steps: {gap3:.3e} m");
    assert!(gap3 > 1e2 * gap, "3-point average should differ");
}
