//! Structures (members joined at joints, sliders, twist holds) against independent references:
//! the generic derivative checker, a single rod (bit for bit), a splice (= one longer rod),
//! a branch (force balance), a ring (zero rest gradient) and columns whose buckling loads are
//! closed forms (Euler), decided by the Hessian inertia.

use nalgebra::Vector3;
use slender_core::geometry::Vec3;
use slender_core::rod::{RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};
use slender_core::structure::{
    JointEnd, Member, SliderSupport, Structure, StructureBuilder, StructureState, TwistHold,
};
use slender_core::testing::{check_model, Rng};

fn props() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness {
            ea: 400.0,
            ei1: 1.3,
            ei2: 0.9,
            gj: 0.7,
        },
        linear_density: 0.8,
    }
}

fn straight(start: [f64; 3], direction: [f64; 3], length: f64) -> RestCurve {
    RestCurve::Straight {
        start,
        direction,
        length,
    }
}

fn rod(curve: RestCurve, n: usize) -> RodBuilder {
    RodBuilder::new(curve, props())
        .elements(n)
        .allow_rigid_motion()
}

/// Three rods meeting at the origin: a trunk along −x ending there, two branches leaving it.
fn branch(g: Vec3) -> Structure {
    let trunk = rod(straight([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0), 5)
        .clamp_start()
        .gravity(g)
        .build()
        .unwrap();
    let b1 = rod(straight([0.0; 3], [1.0, 1.0, 0.0], 0.7), 4)
        .gravity(g)
        .build()
        .unwrap();
    let b2 = rod(straight([0.0; 3], [1.0, -0.5, 0.3], 0.6), 3)
        .gravity(g)
        .point_force(3, Vector3::new(0.0, 0.1, -0.2))
        .build()
        .unwrap();
    StructureBuilder::new()
        .member(Member::Der(trunk))
        .member(Member::Der(b1))
        .member(Member::Der(b2))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 5,
            },
            JointEnd {
                member: 1,
                vertex: 0,
            },
            JointEnd {
                member: 2,
                vertex: 0,
            },
        ])
        .build()
        .expect("branch")
}

/// A closed ring (a circle whose ends are joined), pinned at three vertices.
fn ring() -> Structure {
    let r = RodBuilder::new(
        RestCurve::Circle {
            start: [0.0; 3],
            tangent: [1.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            radius: 0.3,
            length: 2.0 * std::f64::consts::PI * 0.3,
        },
        props(),
    )
    .elements(12)
    .pin(3)
    .pin(7)
    .pin(10)
    .gravity(Vector3::new(0.0, 0.0, -2.0))
    .build()
    .unwrap();
    StructureBuilder::new()
        .member(Member::Der(r))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 12,
            },
            JointEnd {
                member: 0,
                vertex: 0,
            },
        ])
        .build()
        .expect("ring")
}

fn random_state(s: &Structure, rng: &mut Rng) -> StructureState {
    let mut state = s.rest_state().clone();
    let mut out = state.clone();
    for _ in 0..3 {
        let dx: Vec<f64> = (0..s.n_free()).map(|_| rng.uniform() * 0.03).collect();
        s.displace(&state, &dx, 1.0, &mut out);
        std::mem::swap(&mut state, &mut out);
    }
    state
}

#[test]
fn branch_and_ring_pass_the_derivative_checker() {
    let mut rng = Rng(0xABCD_EF01);
    for (name, s) in [
        ("branch", branch(Vector3::new(0.0, -3.0, 1.0))),
        ("ring", ring()),
    ] {
        let states: Vec<StructureState> = (0..3).map(|_| random_state(&s, &mut rng)).collect();
        // Directions of unit size on a structure whose edges are 0.15 m: scale them to the
        // size of the ring, so that ε steps are small against its curvature.
        check_model(&s, &states, 1.0, &mut rng, |_| 0.3, 1.0, name)
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_single_rod_as_a_structure_is_the_rod_bit_for_bit() {
    let g = Vector3::new(0.0, -9.0, 0.0);
    let build = || {
        RodBuilder::new(straight([0.0; 3], [1.0, 0.0, 0.0], 1.0), props())
            .elements(20)
            .clamp_start()
            .gravity(g)
            .build()
            .unwrap()
    };
    let r = build();
    let sol = EquilibriumSolver::new(&r, r.rest_state(), SolverParams::default()).solve(
        &r,
        r.rest_state(),
        0.0,
        1.0,
    );
    let s = StructureBuilder::new()
        .member(Member::Der(build()))
        .build()
        .unwrap();
    assert!(s.is_banded());
    let sol2 = EquilibriumSolver::new(&s, s.rest_state(), SolverParams::default()).solve(
        &s,
        s.rest_state(),
        0.0,
        1.0,
    );
    assert!(sol.report.converged() && sol2.report.converged());
    let st = sol2.state.members[0].as_der().unwrap();
    assert_eq!(st.positions(), sol.state.positions());
    assert_eq!(sol.report.iterations, sol2.report.iterations);
}

fn solve(s: &Structure) -> StructureState {
    let mut solver = EquilibriumSolver::new(s, s.rest_state(), SolverParams::default());
    let sol = solver.solve(s, s.rest_state(), 0.0, 1.0);
    assert!(sol.report.converged(), "{:?}", sol.report.status);
    sol.state
}

#[test]
fn a_splice_is_one_longer_rod() {
    // A cantilever of 20 elements, and the same cantilever as two rods of 8 and 12 elements
    // spliced end to start: the same discrete energy, so the same equilibrium.
    let g = Vector3::new(0.0, -20.0, 3.0);
    let one = RodBuilder::new(straight([0.0; 3], [1.0, 0.0, 0.0], 1.0), props())
        .elements(20)
        .clamp_start()
        .gravity(g)
        .build()
        .unwrap();
    let sol = EquilibriumSolver::new(&one, one.rest_state(), SolverParams::default()).solve(
        &one,
        one.rest_state(),
        0.0,
        1.0,
    );
    let a = rod(straight([0.0; 3], [1.0, 0.0, 0.0], 0.4), 8)
        .clamp_start()
        .gravity(g)
        .build()
        .unwrap();
    let b = rod(straight([0.4, 0.0, 0.0], [1.0, 0.0, 0.0], 0.6), 12)
        .gravity(g)
        .build()
        .unwrap();
    let s = StructureBuilder::new()
        .member(Member::Der(a))
        .member(Member::Der(b))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 8,
            },
            JointEnd {
                member: 1,
                vertex: 0,
            },
        ])
        .build()
        .unwrap();
    let st = solve(&s);
    let tip = st.members[1].positions()[12];
    let expected = sol.state.positions()[20];
    assert!((tip - expected).norm() < 1e-9, "{tip:?} vs {expected:?}");
}

#[test]
fn a_branch_balances_its_loads_at_the_clamp() {
    let g = Vector3::new(0.0, -3.0, 1.0);
    let s = branch(g);
    let st = solve(&s);
    // The trunk's clamp carries the whole weight and the point force.
    let mut load = Vec3::zeros();
    let mut reaction = Vec3::zeros();
    for (m, member) in s.members().iter().enumerate() {
        let r: &Rod = member.as_der().unwrap();
        let rs = st.members[m].as_der().unwrap();
        load += r.applied_loads(rs, 1.0).force;
        if m == 0 {
            reaction = r.reactions(rs, 1.0)[0].force;
        }
    }
    // The joint is five elements from the clamp, so the clamp's reaction (from the trunk's own
    // terms) must balance every load of the three members.
    let rel = (reaction + load).norm() / load.norm();
    assert!(
        rel < 1e-8,
        "clamp reaction {reaction:?} vs load {load:?}: {rel:e}"
    );
}

#[test]
fn a_ring_is_stress_free_at_rest() {
    let s = ring();
    let n = s.n_free();
    let mut g = vec![0.0; n];
    let mut h = s.new_hessian();
    let mut ab = vec![0.0; n];
    let info = s.assemble(s.rest_state(), 0.0, &mut g, &mut h, &mut ab);
    assert!(info.energy.abs() < 1e-24, "{}", info.energy);
    assert!(g.iter().all(|x| x.abs() < 1e-12), "{g:?}");
}

/// Euler's column on a pin (start) and a slider along its axis (end), loaded by a dead axial
/// force at the slider's vertex: stable below P = π²EI/L², unstable above, by inertia.
#[test]
fn pinned_slider_column_buckles_at_euler_load() {
    let ei = 0.9_f64.min(1.3);
    let pcr = std::f64::consts::PI.powi(2) * ei / 1.0;
    for (factor, stable) in [(0.97, true), (1.03, false)] {
        let r = rod(straight([0.0; 3], [1.0, 0.0, 0.0], 1.0), 60)
            .pin(0)
            .point_force(60, Vector3::new(-factor * pcr, 0.0, 0.0))
            .build()
            .unwrap();
        let s = StructureBuilder::new()
            .member(Member::Der(r))
            .slider(SliderSupport {
                member: 0,
                vertex: 60,
                axis: Vector3::new(1.0, 0.0, 0.0),
            })
            .twist_hold(TwistHold { member: 0, edge: 0 })
            .build()
            .expect("column");
        let mut solver = EquilibriumSolver::new(&s, s.rest_state(), SolverParams::default());
        let sol = solver.solve(&s, s.rest_state(), 0.0, 1.0);
        assert!(sol.report.converged());
        assert_eq!(
            sol.report.stable(),
            Some(stable),
            "P/Pcr = {factor}: {:?}",
            sol.report.inertia
        );
    }
}

#[test]
fn bad_joints_and_sliders_are_errors_naming_the_field() {
    let a = || {
        rod(straight([0.0; 3], [1.0, 0.0, 0.0], 1.0), 4)
            .clamp_start()
            .build()
            .unwrap()
    };
    let far = || {
        rod(straight([2.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0), 4)
            .build()
            .unwrap()
    };
    let e = StructureBuilder::new()
        .member(Member::Der(a()))
        .member(Member::Der(far()))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 4,
            },
            JointEnd {
                member: 1,
                vertex: 0,
            },
        ])
        .build()
        .unwrap_err()
        .to_string();
    assert!(e.contains("joints[0][1]") && e.contains("must meet"), "{e}");
    let e = StructureBuilder::new()
        .member(Member::Der(a()))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 2,
            },
            JointEnd {
                member: 0,
                vertex: 4,
            },
        ])
        .build()
        .unwrap_err()
        .to_string();
    assert!(e.contains("joints[0][0].vertex"), "{e}");
    let e = StructureBuilder::new()
        .member(Member::Der(a()))
        .slider(SliderSupport {
            member: 0,
            vertex: 4,
            axis: Vector3::zeros(),
        })
        .build()
        .unwrap_err()
        .to_string();
    assert!(e.contains("sliders[0].axis"), "{e}");
    let free = rod(straight([0.0; 3], [1.0, 0.0, 0.0], 1.0), 4)
        .pin(0)
        .build()
        .unwrap();
    let e = StructureBuilder::new()
        .member(Member::Der(free))
        .build()
        .unwrap_err()
        .to_string();
    assert!(e.contains("free rigid-body motion"), "{e}");
}

#[allow(dead_code)]
fn unused(_: RodState) {}
