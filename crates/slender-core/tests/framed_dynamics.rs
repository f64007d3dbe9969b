//! Implicit dynamics of the rods with material frames (discrete Cosserat rod, SE(3) beam)
//! against independent references: finite differences of the step's incremental potential
//! (inertial term alone and whole) at random rotations away from the identity; Newton's
//! quadratic convergence; free frames against the torque-free symmetric top in closed form
//! (orders on SO(3), conserved angular momentum); cantilever bending and torsional
//! frequencies (Euler–Bernoulli, Saint-Venant) from the eigenproblem and from time
//! histories; energy of a large swing; orders of the schemes; a rod spinning about its axis.
//!
//! Run: `cargo test -p slender-core --release --test framed_dynamics -- --nocapture` (prints
//! the measured figures).

use nalgebra::{DMatrix, SymmetricEigen, UnitQuaternion, Vector3};
use slender_core::assembly::TermSet;
use slender_core::cosserat::CosseratBuilder;
use slender_core::dynamics::{
    DynamicsParams, FlatDofs, IncrementalProblem, LumpedMass, Scheme, TimeStepper,
};
use slender_core::framed::{DofSlot, FramedModel, FramedRodBuilder, FramedState, ShearStiffness};
use slender_core::linalg::{SymmetricFactor, SymmetricMatrix};
use slender_core::rod::{RestCurve, RodProperties, SectionStiffness};
use slender_core::se3::Se3Builder;
use slender_core::solver::EquilibriumProblem;
use slender_core::testing::{fd_errors, Rng};

/// A framed model the tests drive (both the Cosserat rod and the SE(3) beam are).
trait Model: FramedModel + FlatDofs<State = FramedState> {}
impl<T: FramedModel + FlatDofs<State = FramedState>> Model for T {}

fn line(direction: [f64; 3], length: f64) -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction,
        length,
    }
}

/// Runs `$body` with `$rod` bound to a Cosserat rod and then to an SE(3) beam, both built by
/// `$setup` applied to `$b` (the shared builder), and `$name` to the model's name.
macro_rules! both_models {
    (($curve:expr, $props:expr, $shear:expr), |$b:ident| $setup:expr, |$name:ident, $rod:ident| $body:block) => {{
        {
            let $b = CosseratBuilder::new($curve, $props, $shear);
            let $rod = $setup.build().expect("valid Cosserat rod");
            let $name = "cosserat";
            $body
        }
        {
            let $b = Se3Builder::new($curve, $props, $shear);
            let $rod = $setup.build().expect("valid SE(3) beam");
            let $name = "se3";
            $body
        }
    }};
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b) / b
}

/// The free-DOF vector of per-frame angular velocities `omega(f)` (rad/s).
fn frame_velocity<P: Model>(rod: &P, omega: impl Fn(usize) -> Vector3<f64>) -> Vec<f64> {
    let mut v = vec![0.0; rod.n_free()];
    for (f, frame) in rod.frames().iter().enumerate() {
        let w = omega(f);
        for (k, &i) in frame.dofs.iter().enumerate() {
            if i != usize::MAX {
                v[i] = w[k];
            }
        }
    }
    v
}

// ---------------------------------------------------------------------------------------
// Derivatives and Newton
// ---------------------------------------------------------------------------------------

/// Anisotropic section of moderate stiffness (every term of the same order).
fn moderate() -> (RodProperties, ShearStiffness) {
    (
        RodProperties {
            stiffness: SectionStiffness {
                ea: 50.0,
                ei1: 1.3,
                ei2: 0.4,
                gj: 0.7,
            },
            linear_density: 0.9,
        },
        ShearStiffness {
            ga1: 20.0,
            ga2: 35.0,
        },
    )
}

/// A random state of `rod`: the rest state moved by random positions (±`dx` m) and frame
/// turns (±`turn` rad per component), by the model's retraction.
fn random_state<P: Model>(rod: &P, rng: &mut Rng, dx: f64, turn: f64) -> FramedState {
    let dofs = rod.core().dofs();
    let step: Vec<f64> = (0..rod.n_free())
        .map(|i| rng.uniform() * if dofs.is_rotation(i) { turn } else { dx })
        .collect();
    let mut out = rod.core().rest_state().clone();
    rod.displace(rod.core().rest_state(), &step, 1.0, &mut out);
    out
}

/// Checks the step's incremental potential of every scheme at random states y (rotations of
/// O(1) rad from xₙ and from the rest frames), random velocities and Rayleigh damping: the
/// inertial and damping terms alone (no model term selected) and everything.
fn check_step_derivatives<P: Model>(rod: &P, name: &str) {
    let mut rng = Rng(0x5eed_1234_9876_abcd);
    let mass = LumpedMass::of(rod).unwrap();
    let dofs = rod.core().dofs();
    let scale = |i: usize| if dofs.is_rotation(i) { 0.3 } else { 0.05 };
    let mut worst = (0.0f64, 0.0f64);
    for scheme in [
        Scheme::BackwardEuler,
        Scheme::ImplicitMidpoint,
        Scheme::EnergyConserving,
    ] {
        for rayleigh in [(0.0, 0.0), (0.7, 0.02)] {
            let start = random_state(rod, &mut rng, 0.1, 0.9);
            let y = random_state(rod, &mut rng, 0.1, 0.9);
            let velocity: Vec<f64> = (0..rod.n_free()).map(|_| 3.0 * rng.uniform()).collect();
            let mut problem = IncrementalProblem::new(
                rod,
                scheme,
                start.clone(),
                velocity.clone(),
                mass.diagonal().to_vec(),
                0.05,
                rayleigh,
                3,
            );
            problem.restart(&start, &velocity, 1.0);
            for (terms, what) in [(TermSet::NONE, "inertia"), (TermSet::ALL, "all terms")] {
                let u: Vec<f64> = (0..rod.n_free()).map(|i| rng.uniform() * scale(i)).collect();
                let v: Vec<f64> = (0..rod.n_free()).map(|i| rng.uniform() * scale(i)).collect();
                let e = fd_errors(&problem, &y, 1.0, terms, &u, &v);
                let best = |x: &[f64]| x.iter().cloned().fold(f64::INFINITY, f64::min);
                let (g, h) = (best(&e.gradient), best(&e.hessian));
                worst.0 = worst.0.max(g);
                worst.1 = worst.1.max(h);
                // Central differences of energies: the error falls like ε² until round-off
                // (the inertia is nearly quadratic along these steps, so round-off is reached
                // early); the best of five steps must agree to 1e-6 (gradient) and 1e-5
                // (Hessian). Dropping dexp⁻¹ or its derivative costs O(1) here.
                assert!(
                    g < 1e-6 && h < 1e-5,
                    "{name} {scheme:?} rayleigh {rayleigh:?}: {what}: gradient errors {:?}, \
                     Hessian errors {:?}",
                    e.gradient,
                    e.hessian
                );
            }
        }
    }
    println!(
        "{name}: step potential vs central differences, worst best-of-five relative error: \
         gradient {:.2e}, Hessian {:.2e}",
        worst.0, worst.1
    );
}

#[test]
fn step_potential_derivatives_match_finite_differences() {
    let (p, g) = moderate();
    both_models!(
        (line([1.0, 0.3, -0.2], 1.0), p, g),
        |b| b
            .elements(5)
            .clamp_start()
            .gravity(Vector3::new(0.0, -3.0, 1.0))
            .point_moment(5, Vector3::new(0.1, -0.2, 0.3)),
        |name, rod| {
            check_step_derivatives(&rod, name);
        }
    );
    // Planar: one free rotation component per frame.
    both_models!(
        (line([1.0, 0.0, 0.0], 1.0), p, g),
        |b| b
            .elements(4)
            .clamp_start()
            .planar_motion(2)
            .gravity(Vector3::new(0.0, -3.0, 0.0)),
        |name, rod| {
            check_step_derivatives(&rod, &format!("{name} planar"));
        }
    );
}

/// Newton by hand on one step's incremental potential: full steps in the model's chart from
/// the inertial target; the residuals |g|∞.
fn newton_residuals<P: Model>(rod: &P, scheme: Scheme) -> Vec<f64> {
    let mut rng = Rng(42);
    let mass = LumpedMass::of(rod).unwrap();
    let start = random_state(rod, &mut rng, 0.02, 0.2);
    let velocity: Vec<f64> = (0..rod.n_free()).map(|_| 2.0 * rng.uniform()).collect();
    let dt = 0.02;
    let problem = IncrementalProblem::new(
        rod,
        scheme,
        start.clone(),
        velocity.clone(),
        mass.diagonal().to_vec(),
        dt,
        (0.0, 0.0),
        3,
    );
    let mut y = start.clone();
    rod.displace(&start, &velocity, problem.stage(), &mut y);
    let n = rod.n_free();
    let (mut g, mut a) = (vec![0.0; n], vec![0.0; n]);
    let mut h = problem.new_hessian();
    let mut factor = <<P as EquilibriumProblem>::Hessian as SymmetricMatrix>::Factor::default();
    let mut residuals = Vec::new();
    let mut next = y.clone();
    for _ in 0..12 {
        problem.assemble(&y, 1.0, &mut g, &mut h, &mut a);
        let r = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        residuals.push(r);
        if r < 1e-13 {
            break;
        }
        let inertia = factor.factorize(&h, 0.0).unwrap();
        assert!(inertia.is_positive_definite(), "{inertia:?}");
        let mut dx = g.clone();
        factor.solve_in_place(&mut dx);
        dx.iter_mut().for_each(|x| *x = -*x);
        problem.chart(&y, &dx, &mut next);
        std::mem::swap(&mut y, &mut next);
    }
    residuals
}

#[test]
fn newton_converges_quadratically_on_a_step() {
    let (p, g) = moderate();
    both_models!(
        (line([1.0, 0.3, -0.2], 1.0), p, g),
        |b| b.elements(8).clamp_start().gravity(Vector3::new(0.0, -9.0, 2.0)),
        |name, rod| {
            for scheme in [
                Scheme::BackwardEuler,
                Scheme::ImplicitMidpoint,
                Scheme::EnergyConserving,
            ] {
                let r = newton_residuals(&rod, scheme);
                println!("{name} {scheme:?}: Newton residuals {:?}", r.iter().map(|x| format!("{x:.2e}")).collect::<Vec<_>>());
                // Quadratic: once in the basin, each residual (relative to the first) is
                // at most a modest multiple of the square of the previous one.
                let r0 = r[0];
                let mut checked = 0;
                for w in r.windows(2) {
                    let (e0, e1) = (w[0] / r0, w[1] / r0);
                    if e0 < 1e-2 && e0 > 1e-9 {
                        assert!(e1 <= 1e3 * e0 * e0, "{name} {scheme:?}: {e0:.2e} -> {e1:.2e}");
                        checked += 1;
                    }
                }
                assert!(checked >= 1, "{name} {scheme:?}: too few iterations to judge: {r:?}");
                assert!(*r.last().unwrap() < 1e-11, "{name} {scheme:?}: did not converge: {r:?}");
            }
        }
    );
}

// ---------------------------------------------------------------------------------------
// The torque-free symmetric top
// ---------------------------------------------------------------------------------------

/// A rod whose frames are free rigid bodies: every vertex pinned, stiffnesses ~1e-12 of the
/// inertial torques, section a circle (J₁ = J₂ = A, J₃ = C = 2A per frame).
fn loose_frames() -> (RodProperties, ShearStiffness) {
    (
        RodProperties {
            // I/A = EI/EA = 1e-2 m²: J₁ = ρA·1e-2·ℓ.
            stiffness: SectionStiffness::isotropic(1e-12, 1e-14, 1e-14),
            linear_density: 1.0,
        },
        ShearStiffness::isotropic(1e-12),
    )
}

/// The torque-free axisymmetric top (principal moments A, A, C): from R₀ with spatial
/// angular velocity ω₀, R(t) = exp(t π/A) R₀ exp(−κ t e₃) with π = I₀ω₀ and
/// κ = (C − A)/A · (d₃·ω₀) (ω = π/A − κ d₃, d₃·ω constant).
fn top(q0: &UnitQuaternion<f64>, omega0: &Vector3<f64>, a: f64, c: f64, t: f64) -> UnitQuaternion<f64> {
    let r = q0.to_rotation_matrix();
    let d3 = r.matrix().column(2).into_owned();
    let inertia = r.matrix() * nalgebra::Matrix3::from_diagonal(&Vector3::new(a, a, c)) * r.matrix().transpose();
    let pi = inertia * omega0;
    let kappa = (c - a) / a * d3.dot(omega0);
    UnitQuaternion::from_scaled_axis(pi * (t / a)) * q0 * UnitQuaternion::from_scaled_axis(Vector3::z() * (-kappa * t))
}

/// Largest angle (rad) between the frames after `t_end` with step `dt` and the closed form,
/// and the largest change of a frame's angular momentum relative to its size.
fn top_errors<P: Model>(rod: &P, scheme: Scheme, dt: f64, t_end: f64) -> (f64, f64) {
    let frames = rod.frames();
    let omega = |f: usize| {
        let s = f as f64;
        Vector3::new(1.5 + 0.1 * s, -0.8 + 0.05 * s, 2.0 - 0.07 * s)
    };
    let velocity = frame_velocity(rod, omega);
    let mut params = DynamicsParams::new(dt).with_scheme(scheme);
    params.solver.force_tolerance = 1e-12;
    let start = rod.core().rest_state().clone();
    let mut stepper = TimeStepper::new(rod, start.clone(), velocity, params).unwrap();
    let p0 = stepper.frame_momenta();
    let steps = (t_end / dt).round() as usize;
    let mut momentum_drift: f64 = 0.0;
    for _ in 0..steps {
        let r = stepper.step();
        assert!(r.converged, "{scheme:?} dt = {dt}: {r:?}");
        for (p, q) in stepper.frame_momenta().iter().zip(&p0) {
            momentum_drift = momentum_drift.max((p - q).norm() / q.norm());
        }
    }
    let mut orientations = Vec::new();
    rod.frame_orientations(&start, &mut orientations);
    let mut now = Vec::new();
    rod.frame_orientations(stepper.state(), &mut now);
    let mut err: f64 = 0.0;
    for (f, frame) in frames.iter().enumerate() {
        let (a, c) = (frame.principal[0], frame.principal[2]);
        assert!((frame.principal[1] - a).abs() <= 1e-15 * a && (c / a - 2.0).abs() < 1e-12);
        let exact = top(&orientations[f], &omega(f), a, c, steps as f64 * dt);
        err = err.max(now[f].angle_to(&exact));
    }
    (err, momentum_drift)
}

#[test]
fn free_frames_turn_as_the_torque_free_symmetric_top() {
    let (p, g) = loose_frames();
    let n = 6;
    let t_end = 1.0;
    both_models!(
        (line([1.0, 0.0, 0.0], 1.0), p, g),
        |b| (0..=n).fold(b.elements(n), |b, v| b.pin(v)),
        |name, rod| {
            assert!(rod.core().dofs().n_free() == 3 * rod.frames().len());
            // Without torques backward Euler's step is the second-order one too (its first-
            // order error comes from the forces): all three schemes are second order here,
            // which the mid-step inertia Ĩ makes so (with Iₙ they would be first order).
            for scheme in [
                Scheme::BackwardEuler,
                Scheme::ImplicitMidpoint,
                Scheme::EnergyConserving,
            ] {
                let dts = [t_end / 50.0, t_end / 100.0, t_end / 200.0];
                let runs = dts.map(|dt| top_errors(&rod, scheme, dt, t_end));
                let orders = [
                    (runs[0].0 / runs[1].0).log2(),
                    (runs[1].0 / runs[2].0).log2(),
                ];
                let drift = runs.iter().map(|r| r.1).fold(0.0, f64::max);
                println!(
                    "{name} {scheme:?} top: angle errors {:?} rad, observed orders {orders:.3?}, \
                     max relative change of a frame's angular momentum {drift:.2e}",
                    runs.map(|r| format!("{:.3e}", r.0))
                );
                for o in orders {
                    assert!((1.8..=2.3).contains(&o), "{name} {scheme:?} order {o:.3}");
                }
                // Torque-free: π of every frame is kept (to the solver tolerance and the
                // residual stiffness).
                assert!(drift < 1e-9, "{name} {scheme:?}: momentum drift {drift:.2e}");
            }
        }
    );
}
