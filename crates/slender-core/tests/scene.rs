//! Scene building blocks checked against invariances and exact facts: polylines reproduce
//! their points, an interior clamp decouples the two sides, moving every support rigidly
//! moves the equilibrium rigidly, and reactions balance the loads.

use nalgebra::Rotation3;
use slender_core::geometry::Vec3;
use slender_core::rod::{RestCurve, RodBuilder, RodProperties, SectionStiffness, SupportMotion};
use slender_core::scene::solve::SceneSolver;
use slender_core::scene::spec::{
    Centerline, MotionStage, PointForceSpec, RodEnd, RodSpec, SectionSpec, SupportKind,
    SupportSpec, VertexRef,
};
use slender_core::scene::Scene;
use slender_core::solver::{EquilibriumSolver, SolverParams};

fn props() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness {
            ea: 1e5,
            ei1: 0.02,
            ei2: 0.01,
            gj: 0.015,
        },
        linear_density: 0.05,
    }
}

fn rod_spec(centerline: Centerline, supports: Vec<(SupportKind, VertexRef)>) -> RodSpec {
    RodSpec {
        name: None,
        centerline,
        section: SectionSpec::Stiffness {
            ea: 1e5,
            ei1: 0.02,
            ei2: 0.01,
            gj: 0.015,
            linear_density: 0.05,
            display_radius: None,
        },
        material: None,
        elements: Some(24),
        grading: None,
        first_director: None,
        supports: supports
            .into_iter()
            .map(|(kind, vertex)| SupportSpec {
                kind,
                vertex: Some(vertex),
                at: None,
                axis: None,
            })
            .collect(),
        forces: Vec::new(),
        moments: Vec::new(),
        line_loads: Vec::new(),
        closed: false,
        min_bend_radius: None,
        model: Default::default(),
        shear_stiffness: None,
        contact_radius: None,
    }
}

fn scene(rods: Vec<RodSpec>, gravity: [f64; 3]) -> Scene {
    Scene {
        gravity,
        solver: SolverParams::default(),
        rods,
        shells: Vec::new(),
        joints: Vec::new(),
        motion: Vec::new(),
        unstable: Default::default(),
        time: None,
        obstacles: Vec::new(),
        contact: None,
    }
}

#[test]
fn polyline_nodes_are_its_points_exactly() {
    let points = vec![
        [0.0, 0.0, 0.0],
        [0.3, 0.1, 0.0],
        [0.7, 0.1, 0.2],
        [1.0, 0.0, 0.1],
    ];
    let s = scene(
        vec![RodSpec {
            elements: None,
            ..rod_spec(
                Centerline::Polyline {
                    points: points.clone(),
                },
                vec![(SupportKind::Clamp, VertexRef::Named(RodEnd::Start))],
            )
        }],
        [0.0; 3],
    );
    let c = s.compile().unwrap();
    let rest = c.rest_positions(0);
    assert_eq!(rest.len(), points.len());
    for (p, q) in rest.iter().zip(&points) {
        assert_eq!([p.x, p.y, p.z], *q);
    }
}

#[test]
fn an_interior_clamp_decouples_the_two_sides() {
    // A rod clamped at vertex 12 with a load on its right part only: the left part, a
    // cantilever without load, must stay exactly at rest; the right part is the same as a
    // separate cantilever built from that half.
    let straight = Centerline::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 2.0,
    };
    let mut spec = rod_spec(straight, vec![(SupportKind::Clamp, VertexRef::Index(12))]);
    spec.forces.push(PointForceSpec {
        vertex: VertexRef::Named(RodEnd::End),
        force: [0.0, 0.01, -0.02],
        follower: false,
    });
    let sc = scene(vec![spec], [0.0; 3]);
    let c = sc.compile().unwrap();
    assert_eq!(c.rods[0].parts.len(), 2);
    let (_, step) = SceneSolver::new(&sc, &c);
    assert!(step.converged);
    let x = &step.rods[0].positions;
    for (i, p) in x.iter().enumerate().take(13) {
        let rest = [i as f64 * 2.0 / 24.0, 0.0, 0.0];
        for k in 0..3 {
            assert!((p[k] - rest[k]).abs() < 1e-15, "vertex {i} moved");
        }
    }
    let half = RodBuilder::new(
        RestCurve::Straight {
            start: [1.0, 0.0, 0.0],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props(),
    )
    .elements(12)
    .clamp_start()
    .point_force(12, Vec3::new(0.0, 0.01, -0.02))
    .build()
    .unwrap();
    let start = half.rest_state().clone();
    // Solved to round-off, like the scene solver (which polishes past the default tolerance).
    let tight = SolverParams {
        force_tolerance: 1e-14,
        energy_tolerance: 1e-30,
        ..SolverParams::default()
    };
    let sol = EquilibriumSolver::new(&half, &start, tight).solve(&half, &start, 0.0, 1.0);
    let tip = sol.state.positions()[12];
    let t = x[24];
    assert!(
        (Vec3::from(t) - tip).norm() < 1e-11,
        "{t:?} vs separate half {tip:?}"
    );
    // The clamp's reaction balances the tip force.
    let r = &step.rods[0].supports[0];
    assert!((Vec3::from(r.force) + Vec3::new(0.0, 0.01, -0.02)).norm() < 1e-10);
}

#[test]
fn moving_all_supports_rigidly_moves_the_equilibrium_rigidly() {
    // No loads but a helix held by a clamp at its start: rotating and translating the clamp
    // must carry the (unstressed) rod along as a rigid body.
    let helix = Centerline::Helix {
        start: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        normal: [1.0, 0.0, 0.0],
        radius: 0.1,
        pitch: 0.05,
        length: 1.5,
    };
    let mut s = scene(
        vec![rod_spec(
            helix,
            vec![(SupportKind::Clamp, VertexRef::Named(RodEnd::Start))],
        )],
        [0.0; 3],
    );
    let rot = [0.3, -0.5, 0.8];
    let tr = [0.2, 0.1, -0.3];
    s.motion.push(MotionStage {
        obstacle: None,
        rod: Some(0),
        shell: None,
        support: 0,
        translate: tr,
        rotate: rot,
        steps: 3,
    });
    let c = s.compile().unwrap();
    let (mut solver, first) = SceneSolver::new(&s, &c);
    let rest = first.rods[0].positions.clone();
    let mut last = first;
    for k in 1..=3 {
        last = solver.run_motion_step(k);
        assert!(last.converged, "step {k}");
    }
    let r = Rotation3::new(Vec3::from(rot));
    for (p, q) in last.rods[0].positions.iter().zip(&rest) {
        let expected = r * Vec3::from(*q) + Vec3::from(tr);
        assert!(
            (Vec3::from(*p) - expected).norm() < 1e-9,
            "{p:?} vs {expected:?}"
        );
    }
    // Unloaded: the clamp carries nothing.
    let sup = &last.rods[0].supports[0];
    assert!(Vec3::from(sup.force).norm() < 1e-9 && Vec3::from(sup.moment).norm() < 1e-9);
}

#[test]
fn support_motion_rejects_unsupported_vertices() {
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props(),
    )
    .elements(4)
    .clamp_start()
    .build()
    .unwrap();
    let err = rod
        .with_support_moved(
            rod.rest_state(),
            &SupportMotion {
                vertices: vec![3],
                pivot: Vec3::zeros(),
                rotation: Vec3::zeros(),
                translation: Vec3::x(),
            },
        )
        .unwrap_err();
    assert!(err.to_string().contains("vertex 3 is not held"));
}

#[test]
fn reactions_balance_gravity_on_a_pinned_and_clamped_arc() {
    let arc = Centerline::Circle {
        start: [0.0; 3],
        tangent: [1.0, 0.0, 0.0],
        normal: [0.0, 1.0, 0.0],
        radius: 0.4,
        length: 1.0,
    };
    let sc = scene(
        vec![rod_spec(
            arc,
            vec![
                (SupportKind::Clamp, VertexRef::Named(RodEnd::Start)),
                (SupportKind::Pin, VertexRef::Index(16)),
                (SupportKind::Clip, VertexRef::Named(RodEnd::End)),
            ],
        )],
        [0.0, -3.0, -9.81],
    );
    let c = sc.compile().unwrap();
    let (_, step) = SceneSolver::new(&sc, &c);
    assert!(step.converged);
    let r = &step.rods[0];
    assert!(
        r.relative_force_imbalance < 1e-9,
        "{}",
        r.relative_force_imbalance
    );
    assert!(
        r.relative_moment_imbalance < 1e-9,
        "{}",
        r.relative_moment_imbalance
    );
    // Total vertical reaction = weight of the rest polygon (lumped masses sum to ρA Σ chords).
    let part = &c.rods[0].parts[0];
    let rod = c.structures[part.structure].members()[part.member]
        .as_der()
        .unwrap();
    let mass: f64 = rod.vertex_masses().iter().sum();
    let fz: f64 = r.supports.iter().map(|s| s.force[2]).sum();
    assert!((fz / (mass * 9.81) - 1.0).abs() < 1e-9);
}

#[test]
fn moving_an_interior_clamp_moves_both_sides_rigidly_and_a_moved_clip_keeps_balance() {
    // Rod 0: held only by a clamp at its middle vertex, unloaded: moving and rotating that
    // clamp must carry both halves along rigidly. Rod 1: clamped at its start and led through
    // a clip that is moved and turned: the reactions must balance each other.
    let straight = || Centerline::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    };
    let a = rod_spec(straight(), vec![(SupportKind::Clamp, VertexRef::Index(12))]);
    let mut b = rod_spec(
        straight(),
        vec![
            (SupportKind::Clamp, VertexRef::Named(RodEnd::Start)),
            (SupportKind::Clip, VertexRef::Index(16)),
        ],
    );
    b.name = Some("clipped".into());
    let mut s = scene(vec![a, b], [0.0; 3]);
    let (rot, tr) = ([0.4, 0.0, 0.3], [0.0, 0.05, 0.1]);
    s.motion.push(MotionStage {
        obstacle: None,
        rod: Some(0),
        shell: None,
        support: 0,
        translate: tr,
        rotate: rot,
        steps: 2,
    });
    s.motion.push(MotionStage {
        obstacle: None,
        rod: Some(1),
        shell: None,
        support: 1,
        translate: [-0.1, 0.1, 0.0],
        rotate: [0.0, 0.0, 0.5],
        steps: 2,
    });
    let c = s.compile().unwrap();
    assert_eq!(c.rods[0].parts.len(), 2);
    let (mut solver, first) = SceneSolver::new(&s, &c);
    let rest = first.rods[0].positions.clone();
    for k in 1..=solver.motion_steps() {
        let step = solver.run_motion_step(k);
        assert!(step.converged, "step {k}");
        let r = &step.rods[1];
        assert!(r.relative_force_imbalance < 1e-9, "step {k}");
        assert!(r.relative_moment_imbalance < 1e-9, "step {k}");
        if k == 2 {
            let pivot = Vec3::new(0.5, 0.0, 0.0);
            let rotation = Rotation3::new(Vec3::from(rot));
            for (p, q) in step.rods[0].positions.iter().zip(&rest) {
                let expected = pivot + rotation * (Vec3::from(*q) - pivot) + Vec3::from(tr);
                assert!(
                    (Vec3::from(*p) - expected).norm() < 1e-9,
                    "{p:?} vs {expected:?}"
                );
            }
        }
        if k == 4 {
            // The clip's two held vertices moved rigidly about vertex 16.
            let x = &step.rods[1].positions;
            let r = Rotation3::new(Vec3::new(0.0, 0.0, 0.5));
            let p16 = Vec3::new(16.0 / 24.0 - 0.1, 0.1, 0.0);
            let p17 = p16 + r * Vec3::new(1.0 / 24.0, 0.0, 0.0);
            assert!((Vec3::from(x[16]) - p16).norm() < 1e-12);
            assert!((Vec3::from(x[17]) - p17).norm() < 1e-12);
        }
    }
}

#[test]
fn reactions_are_the_energy_derivatives_with_respect_to_the_support_motion() {
    // Envelope theorem: at an equilibrium, d(min E)/d(support position) = ∂E/∂(support) = the
    // reaction. Moving the end clamp by ±ε (and turning it by ±δ), re-solving and differencing
    // the energy checks the reaction force and the ghost-edge moment formula independently.
    let rod = RodBuilder::new(
        RestCurve::Circle {
            start: [0.0; 3],
            tangent: [1.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.2],
            radius: 0.5,
            length: 1.0,
        },
        props(),
    )
    .elements(30)
    .clamp_start()
    .clamp_end()
    .gravity(Vec3::new(0.0, -2.0, -9.81))
    .point_force(9, Vec3::new(0.01, 0.0, 0.02))
    .build()
    .unwrap();
    let tight = SolverParams {
        force_tolerance: 1e-14,
        energy_tolerance: 1e-30,
        ..SolverParams::default()
    };
    let rest = rod.rest_state().clone();
    let mut solver = EquilibriumSolver::new(&rod, &rest, tight);
    let s0 = solver.solve(&rod, &rest, 0.0, 1.0).state;
    let n = rod.n_edges();
    let reaction = rod
        .reactions(&s0, 1.0)
        .into_iter()
        .find(|r| r.vertex == n)
        .unwrap();
    let pivot = s0.positions()[n];
    let energy_after = |rotation: Vec3, translation: Vec3, solver: &mut EquilibriumSolver<_>| {
        let moved = rod
            .with_support_moved(
                &s0,
                &SupportMotion {
                    vertices: vec![n],
                    pivot,
                    rotation,
                    translation,
                },
            )
            .unwrap();
        let sol = solver.solve(&rod, &moved, 1.0, 1.0);
        assert!(sol.report.converged());
        rod.energy_terms(&sol.state, 1.0, slender_core::assembly::TermSet::ALL)
    };
    let eps = 1e-5;
    for k in 0..3 {
        let e = Vec3::ith(k, eps);
        let df = (energy_after(Vec3::zeros(), e, &mut solver)
            - energy_after(Vec3::zeros(), -e, &mut solver))
            / (2.0 * eps);
        let dm = (energy_after(e, Vec3::zeros(), &mut solver)
            - energy_after(-e, Vec3::zeros(), &mut solver))
            / (2.0 * eps);
        eprintln!(
            "k {k}: dE/dx {df:e} vs {:e}; dE/dphi {dm:e} vs {:e}",
            reaction.force[k], reaction.moment[k]
        );
        let f_scale = reaction.force.norm();
        let m_scale = reaction.moment.norm();
        assert!(
            (df - reaction.force[k]).abs() < 1e-6 * f_scale,
            "force {k}: dE/dx = {df}, reaction {}",
            reaction.force[k]
        );
        assert!(
            (dm - reaction.moment[k]).abs() < 1e-6 * m_scale,
            "moment {k}: dE/dφ = {dm}, reaction {}",
            reaction.moment[k]
        );
    }
}

#[test]
fn a_shell_strip_is_solved_on_its_own_and_does_not_change_the_rods() {
    use slender_core::scene::spec::{MaterialSpec, ShellSpec};
    use slender_core::shell::{ShellBuilder, ShellProperties};
    let g = [0.0, -9.81, 0.0];
    let rod = rod_spec(
        Centerline::Straight {
            start: [0.0, 0.0, 1.0],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        vec![(SupportKind::Clamp, VertexRef::Index(0))],
    );
    let strip = ShellSpec {
        name: None,
        length: 0.2,
        width: 0.02,
        thickness: 3e-4,
        material: MaterialSpec {
            young: 5e9,
            poisson: Some(0.3),
            shear_modulus: None,
            density: 1200.0,
        },
        elements: Some(8),
        width_elements: None,
        grading: None,
        support: None,
        clamps: None,
        forces: Vec::new(),
        model: None,
    };
    let alone = scene(vec![rod.clone()], g);
    let mut mixed = scene(vec![rod], g);
    mixed.shells.push(strip.clone());
    let (_, a) = SceneSolver::new(&alone, &alone.compile().unwrap());
    let compiled = mixed.compile().unwrap();
    let (_, b) = SceneSolver::new(&mixed, &compiled);
    assert!(a.converged && b.converged);
    assert_eq!(
        a.rods[0].positions, b.rods[0].positions,
        "the strip changed the rod"
    );
    let sh = &b.shells[0];
    assert_eq!(sh.name, "shell0");
    // n_W from the aspect ratio, at least 2.
    assert_eq!(sh.elements, [8, 2]);
    // The same strip built and solved directly (flat start, load stepping) reaches the same
    // equilibrium as the scene's rod-predictor start, to the solver's tolerance.
    let shell = ShellBuilder::new(ShellProperties {
        length: 0.2,
        width: 0.02,
        thickness: 3e-4,
        young: 5e9,
        poisson: 0.3,
        density: 1200.0,
    })
    .elements(8, 2)
    .gravity(slender_core::geometry::Vec3::from(g))
    .build()
    .unwrap();
    let flat = shell.rest_state();
    let direct =
        slender_core::solver::EquilibriumSolver::new(&shell, &flat, SolverParams::default())
            .solve(&shell, &flat, 0.0, 1.0);
    assert!(direct.report.converged());
    for (p, q) in sh.positions.iter().zip(&direct.state.positions) {
        for c in 0..3 {
            assert!((p[c] - q[c]).abs() < 1e-8, "{p:?} vs {q:?}");
        }
    }
    // The clamp force carries the weight ρ h w L g.
    let weight = 1200.0 * 3e-4 * 0.02 * 0.2 * 9.81;
    assert!(
        (sh.clamp_force[1] / weight - 1.0).abs() < 1e-6,
        "{:?}",
        sh.clamp_force
    );
    // Anything but the edge x = 0 clamped is refused, naming the field.
    let mut pinned = mixed.clone();
    pinned.shells[0].support = Some("pin_end".into());
    let e = pinned.compile().unwrap_err();
    assert_eq!(e.path, "shells[0].support");
}
