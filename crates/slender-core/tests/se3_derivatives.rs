//! The SE(3) beam against the generic derivative checker: every term group's
//! gradient and Hessian against central finite differences at random twisted, sheared,
//! anisotropic, naturally curved states, with the error falling like O(ε²); rigid-motion
//! invariance; zero energy and gradient at the rest shapes (straight, circle, helix).

use nalgebra::Vector3;
use slender_core::framed::{FramedState, ShearStiffness};
use slender_core::rod::{RestCurve, RodProperties, SectionStiffness};
use slender_core::se3::{Se3Builder, Se3Rod};
use slender_core::solver::EquilibriumProblem;
use slender_core::testing::{check_model, check_rest, Rng};

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

fn shear() -> ShearStiffness {
    ShearStiffness {
        ga1: 20.0,
        ga2: 35.0,
    }
}

fn helix() -> RestCurve {
    RestCurve::Helix {
        start: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        normal: [1.0, 0.0, 0.0],
        radius: 0.3,
        pitch: 0.2,
        length: 2.0,
    }
}

fn circle() -> RestCurve {
    RestCurve::Circle {
        start: [0.0; 3],
        tangent: [1.0, 0.0, 0.0],
        normal: [0.0, 1.0, 0.0],
        radius: 0.4,
        length: 2.0,
    }
}

fn straight() -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    }
}

fn rods() -> Vec<Se3Rod> {
    vec![
        Se3Builder::new(straight(), properties(), shear())
            .elements(6)
            .clamp_start()
            .gravity(Vector3::new(0.0, -3.0, 1.0))
            .point_force(6, Vector3::new(0.2, 0.1, -0.3))
            .point_moment(6, Vector3::new(0.1, -0.2, 0.3))
            .point_moment(2, Vector3::new(0.4, 0.1, 0.0))
            .build()
            .unwrap(),
        Se3Builder::new(helix(), properties(), shear())
            .elements(7)
            .clamp_start()
            .clamp_end()
            .natural_twist(0.7)
            .point_moment(3, Vector3::new(0.0, 0.3, -0.1))
            .build()
            .unwrap(),
        Se3Builder::new(circle(), properties(), shear())
            .elements(5)
            .pin(0)
            .pin(2)
            .pin(5)
            .gravity(Vector3::new(0.5, -2.0, 0.0))
            .build()
            .unwrap(),
    ]
}

/// A random deformed state: a few random steps from rest (positions and rotations moved
/// independently, so the edges are sheared and stretched too).
fn random_state(rod: &Se3Rod, rng: &mut Rng) -> FramedState {
    let mut s = rod.rest_state().clone();
    let mut out = s.clone();
    let n = rod.n_free();
    for _ in 0..3 {
        let dx: Vec<f64> = (0..n)
            .map(|i| rng.uniform() * if rod.dofs().is_rotation(i) { 0.3 } else { 0.04 })
            .collect();
        rod.displace(&s, &dx, 1.0, &mut out);
        std::mem::swap(&mut s, &mut out);
    }
    s
}

/// Direction scale of the finite differences: 1 m for coordinates, 4 rad for rotations. The
/// moment potentials are nearly linear in the rotations (exactly linear for a turn about their
/// axis), so their second differences need the larger rotation steps to rise above round-off.
fn scale(rod: &Se3Rod) -> impl Fn(usize) -> f64 + Copy + '_ {
    |i| if rod.dofs().is_rotation(i) { 4.0 } else { 1.0 }
}

#[test]
fn every_term_passes_the_derivative_checker() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (r, rod) in rods().iter().enumerate() {
        let states: Vec<FramedState> = (0..3).map(|_| random_state(rod, &mut rng)).collect();
        check_model(
            rod,
            &states,
            1.0,
            &mut rng,
            scale(rod),
            1.0,
            &format!("rod {r}"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn rest_shapes_have_zero_energy_and_gradient() {
    {
        for curve in [straight(), circle(), helix()] {
            for n in [1, 3, 17] {
                let rod = Se3Builder::new(curve.clone(), properties(), shear())
                    .elements(n)
                    .natural_twist(0.3)
                    .clamp_start()
                    .clamp_end()
                    .build()
                    .unwrap();
                check_rest(&rod, 1.0, &format!("{curve:?} N = {n}"))
                    .unwrap_or_else(|e| panic!("{e}"));
            }
        }
    }
}
