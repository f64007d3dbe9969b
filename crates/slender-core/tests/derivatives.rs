//! The rod against the generic derivative checker (`slender_core::testing`): every term group's
//! gradient and Hessian against central finite differences at random non-trivial states
//! (twisted, anisotropic, naturally curved, both clamps, pins), with the error falling like
//! O(ε²); rigid-motion invariance; zero gradient at the rest shapes.

use nalgebra::{SMatrix, SVector, Vector3};
use slender_core::assembly::{Assembler, TermGroup, TermSet};
use slender_core::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use slender_core::rod::{RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness};
use slender_core::solver::{EquilibriumProblem, MassMetric};
use slender_core::testing::{
    check_derivatives, check_model, check_rest, check_rigid_invariance, Rng,
};

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

/// Direction scale of the finite differences (unit steps in m and rad; ε scales them).
fn scale(_rod: &Rod) -> impl Fn(usize) -> f64 + Copy {
    |_| 1.0
}

#[test]
fn every_term_passes_the_derivative_checker() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (r, rod) in rods().iter().enumerate() {
        let states: Vec<RodState> = (0..3).map(|_| random_state(rod, &mut rng)).collect();
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

/// The rod with a deliberate error in its derivatives: an extra gradient or Hessian entry on
/// the first free DOF that no energy accounts for.
struct Faulty<'a> {
    rod: &'a Rod,
    gradient_error: f64,
    hessian_error: f64,
}

impl MassMetric for Faulty<'_> {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.rod.inertia_metric(i)
    }
    fn eigenvalue_scale(&self) -> f64 {
        self.rod.eigenvalue_scale()
    }
}

impl EquilibriumProblem for Faulty<'_> {
    type State = RodState;
    type Hessian = SymmetricBandMatrix;
    fn n_free(&self) -> usize {
        self.rod.n_free()
    }
    fn new_hessian(&self) -> SymmetricBandMatrix {
        self.rod.new_hessian()
    }
    fn term_groups(&self) -> &[TermGroup] {
        self.rod.term_groups()
    }
    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &RodState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.rod.assemble_selected(state, load, asm);
        let g = SVector::<f64, 1>::new(self.gradient_error);
        let h = SMatrix::<f64, 1, 1>::new(self.hessian_error);
        asm.local(&[0], 0.0, 0.0, &g, &h);
    }
    fn difference(&self, a: &RodState, b: &RodState, out: &mut [f64]) {
        self.rod.difference(a, b, out)
    }
    fn displace(&self, s: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.rod.displace(s, dx, alpha, out)
    }
    fn chart(&self, s: &RodState, dx: &[f64], out: &mut RodState) {
        self.rod.chart(s, dx, out)
    }
    fn max_step(&self, s: &RodState, dx: &[f64]) -> f64 {
        self.rod.max_step(s, dx)
    }
    fn force_length(&self, i: usize) -> f64 {
        self.rod.force_length(i)
    }
    fn dof_magnitude(&self, s: &RodState, i: usize) -> f64 {
        self.rod.dof_magnitude(s, i)
    }
}

#[test]
fn the_checker_catches_wrong_gradients_and_hessians() {
    // A check that cannot fail proves nothing.
    let rods = rods();
    let rod = &rods[0];
    let mut rng = Rng(7);
    let s = random_state(rod, &mut rng);
    let sc = scale(rod);
    let exact = Faulty {
        rod,
        gradient_error: 0.0,
        hessian_error: 0.0,
    };
    check_derivatives(&exact, &s, 1.0, TermSet::ALL, &mut rng, sc, "exact")
        .unwrap_or_else(|e| panic!("{e}"));
    let wrong_gradient = Faulty {
        rod,
        gradient_error: 0.05,
        hessian_error: 0.0,
    };
    let e = check_derivatives(&wrong_gradient, &s, 1.0, TermSet::ALL, &mut rng, sc, "g");
    assert!(e.is_err_and(|m| m.contains("gradient")));
    let wrong_hessian = Faulty {
        rod,
        gradient_error: 0.0,
        hessian_error: 5.0,
    };
    let e = check_derivatives(&wrong_hessian, &s, 1.0, TermSet::ALL, &mut rng, sc, "h");
    assert!(e.is_err_and(|m| m.contains("Hessian")));
}

#[test]
fn rigid_motions_change_no_internal_energy() {
    let mut rng = Rng(42);
    for (r, rod) in rods().iter().enumerate() {
        let states = vec![random_state(rod, &mut rng)];
        check_rigid_invariance(rod, &states, &mut rng, &format!("rod {r}"))
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn rest_shapes_have_zero_gradient() {
    for (r, rod) in rods().iter().enumerate() {
        check_rest(rod, 1.0, &format!("rod {r}")).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_newton_solve_with_a_nan_in_its_hessian_fails_at_once_and_says_why() {
    // No shift regularizes a Hessian with a NaN: the iterate fails naming it, instead of
    // doubling the shift up to its cap (about a thousand failed factorizations per iterate,
    // which held a mutated flat-cable scene of the scene fuzz for minutes).
    let rods = rods();
    let rod = &rods[0];
    let faulty = Faulty {
        rod,
        gradient_error: 1.0,
        hessian_error: f64::NAN,
    };
    let mut state = rod.rest_state().clone();
    let mut ws = slender_core::solver::NewtonWorkspace::new(&faulty, &state);
    let out = slender_core::solver::newton(
        &faulty,
        &mut state,
        1.0,
        &slender_core::solver::SolverParams::default(),
        &mut ws,
    );
    assert!(!out.converged);
    let reason = out.failure.unwrap_or_default();
    assert!(
        reason.contains("non-finite Hessian entry in row 0"),
        "{reason}"
    );
}
