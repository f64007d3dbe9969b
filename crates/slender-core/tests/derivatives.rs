//! Every energy term's gradient and Hessian against central finite differences, at random
//! non-trivial states (twisted, anisotropic, naturally curved, both clamps), with the error
//! falling like O(ε²).

use nalgebra::{Rotation3, Vector3};
use slender_core::linalg::SymmetricBandMatrix;
use slender_core::rod::{
    RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness, Terms,
};
use slender_core::solver::EquilibriumProblem;

/// Deterministic xorshift generator: tests must not depend on a seed from the environment.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    fn vector(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.uniform()).collect()
    }
}

fn properties() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness {
            ea: 50.0,
            ei1: 1.3,
            ei2: 0.4,
            gj: 0.7,
        },
        linear_density: 0.9,
    }
}

fn rods() -> Vec<Rod> {
    let curved = RestCurve::Helix {
        start: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        normal: [1.0, 0.0, 0.0],
        radius: 0.3,
        pitch: 0.2,
        length: 2.0,
    };
    let straight = RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    };
    vec![
        RodBuilder::new(straight.clone(), properties())
            .elements(6)
            .clamp_start()
            .gravity(Vector3::new(0.0, -3.0, 1.0))
            .point_force(6, Vector3::new(0.2, 0.1, -0.3))
            .point_moment(6, Vector3::new(0.1, -0.2, 0.3))
            .point_moment(2, Vector3::new(0.4, 0.1, 0.0))
            .build()
            .unwrap(),
        RodBuilder::new(curved, properties())
            .elements(7)
            .clamp_start()
            .clamp_end()
            .natural_twist(0.7)
            .gravity(Vector3::new(0.5, -2.0, 0.0))
            .point_moment(3, Vector3::new(0.0, 0.3, -0.1))
            .build()
            .unwrap(),
        RodBuilder::new(straight, properties())
            .elements(5)
            .pin(0)
            .pin(2)
            .pin(5)
            .build()
            .unwrap(),
    ]
}

/// A random deformed state reached from rest by a few moderate random displacements (so the
/// reference frames and twists are transported along the way, as in a real solve).
fn random_state(rod: &Rod, rng: &mut Rng) -> RodState {
    let mut s = rod.rest_state().clone();
    let mut out = s.clone();
    let n = rod.n_free();
    for _ in 0..3 {
        let dx: Vec<f64> = (0..n)
            .map(|i| rng.uniform() * if rod.dofs().is_angle(i) { 0.8 } else { 0.04 })
            .collect();
        rod.displace(&s, &dx, 1.0, &mut out);
        std::mem::swap(&mut s, &mut out);
    }
    s
}

fn assemble(rod: &Rod, s: &RodState, terms: Terms) -> (f64, Vec<f64>, SymmetricBandMatrix) {
    let n = rod.n_free();
    let mut g = vec![0.0; n];
    let mut h = SymmetricBandMatrix::new(n, rod.half_bandwidth());
    let e = rod
        .assemble_terms(s, 1.0, terms, Some(&mut g), Some(&mut h), None)
        .energy;
    (e, g, h)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Returns (gradient errors, Hessian errors) over a range of ε, relative to the size of the
/// exact derivatives.
///
/// Both use *energy* differences with every trial state's frames transported from `s`: that
/// is the function whose derivatives the model claims (time-parallel frames). Differencing
/// gradients at displaced states instead would mix energies with different source frames,
/// which agree only to first order (transport has holonomy).
fn fd_errors(rod: &Rod, s: &RodState, terms: Terms, u: &[f64], v: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (_, g, h) = assemble(rod, s, terms);
    let mut hv = vec![0.0; v.len()];
    h.mul_vec(v, &mut hv);
    let gv: f64 = g.iter().zip(v).map(|(a, b)| a * b).sum();
    let uhv: f64 = u.iter().zip(&hv).map(|(a, b)| a * b).sum();
    let scale_g = gv.abs().max(norm(&g) * norm(v) * 1e-3).max(1e-300);
    let mut hu = vec![0.0; u.len()];
    h.mul_vec(u, &mut hu);
    let scale_h = uhv.abs().max(norm(&hu) * norm(v) * 1e-3).max(1e-300);
    let mut err_g = Vec::new();
    let mut err_h = Vec::new();
    let mut trial = s.clone();
    let mut energy_at = |a: f64, b: f64| {
        let w: Vec<f64> = u.iter().zip(v).map(|(x, y)| a * x + b * y).collect();
        rod.displace_linear(s, &w, 1.0, &mut trial);
        rod.energy_terms(&trial, 1.0, terms)
    };
    for eps in [2e-3, 6e-4, 2e-4, 6e-5, 2e-5] {
        let d1 = (energy_at(0.0, eps) - energy_at(0.0, -eps)) / (2.0 * eps);
        err_g.push((d1 - gv).abs() / scale_g);
        let d2 = (energy_at(eps, eps) - energy_at(eps, -eps) - energy_at(-eps, eps)
            + energy_at(-eps, -eps))
            / (4.0 * eps * eps);
        err_h.push((d2 - uhv).abs() / scale_h);
    }
    (err_g, err_h)
}

fn assert_second_order(errors: &[f64], what: &str) {
    // Over a decade of ε the error must fall by ~100 (allow 30) until it reaches round-off.
    let e0 = errors[0];
    let e2 = errors[2];
    assert!(
        e2 < e0 / 30.0 || e2 < 1e-9,
        "{what}: not O(ε²): errors {errors:?}"
    );
    assert!(
        errors.iter().cloned().fold(f64::INFINITY, f64::min) < 1e-5,
        "{what}: {errors:?}"
    );
}

fn check(terms: Terms, name: &str) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (r, rod) in rods().iter().enumerate() {
        for trial in 0..3 {
            let s = random_state(rod, &mut rng);
            let u = rng.vector(rod.n_free());
            let v = rng.vector(rod.n_free());
            let (eg, eh) = fd_errors(rod, &s, terms, &u, &v);
            assert_second_order(&eg, &format!("{name} gradient, rod {r}, trial {trial}"));
            assert_second_order(&eh, &format!("{name} Hessian, rod {r}, trial {trial}"));
        }
    }
}

#[test]
fn stretching_derivatives_match_finite_differences() {
    check(
        Terms {
            stretching: true,
            ..Terms::NONE
        },
        "stretching",
    );
}

#[test]
fn bending_derivatives_match_finite_differences() {
    check(
        Terms {
            bending: true,
            ..Terms::NONE
        },
        "bending",
    );
}

#[test]
fn twisting_derivatives_match_finite_differences() {
    check(
        Terms {
            twisting: true,
            ..Terms::NONE
        },
        "twisting",
    );
}

#[test]
fn external_load_derivatives_match_finite_differences() {
    // Gravity and point forces are linear; point moments are not (see `rod/moment.rs`).
    check(
        Terms {
            external: true,
            ..Terms::NONE
        },
        "external",
    );
}

#[test]
fn all_terms_together_match_finite_differences() {
    check(Terms::ALL, "total");
}

#[test]
fn rigid_motions_change_no_internal_energy() {
    let internal = Terms {
        external: false,
        ..Terms::ALL
    };
    let mut rng = Rng(42);
    for rod in rods() {
        let s = random_state(&rod, &mut rng);
        let e0 = rod.energy_terms(&s, 1.0, internal);
        assert!(e0 > 1e-6, "state must be deformed");
        for _ in 0..5 {
            let axis = Vector3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let rot = Rotation3::new(axis * 3.0);
            let moved = s.rigidly_transformed(&rot, &Vector3::new(rng.uniform(), 2.0, -1.0));
            let e1 = rod.energy_terms(&moved, 1.0, internal);
            assert!((e1 - e0).abs() <= 1e-12 * e0, "{e0} vs {e1}");
        }
    }
}

#[test]
fn rest_shapes_have_zero_gradient() {
    let internal = Terms {
        external: false,
        ..Terms::ALL
    };
    for rod in rods() {
        let (e, g, _) = assemble(&rod, rod.rest_state(), internal);
        assert!(e.abs() < 1e-28, "rest energy {e}");
        assert!(g.iter().all(|x| x.abs() < 1e-13), "rest gradient {g:?}");
    }
}
