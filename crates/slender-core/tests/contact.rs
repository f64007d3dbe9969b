//! Contact with rigid obstacles (`slender_core::contact`): exact derivatives of the barrier
//! energy against finite differences, and equilibria against closed forms — a heavy cable
//! clamped above the ground touches down where small-deflection beam theory says, a cable
//! draped over a drum conforms to it — with no penetration and forces that balance the weight.

use nalgebra::Vector3;
use slender_core::assembly::TermSet;
use slender_core::contact::{
    ContactParams, ContactProblem, ContactSites, Cylinder, Friction, Obstacle, Plane, Sphere,
    Torus, CONTACT, FRICTION,
};
use slender_core::rod::{RestCurve, RodBuilder, RodProperties, SectionStiffness};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};
use slender_core::testing::{check_derivatives, Rng};

/// A cable of d = 6 mm, ρ = 1400 kg/m³ (q = 0.388 N/m) and Young's modulus `e` (Pa; 137 MPa
/// gives EI = 8.7e-3 N m²); returns its properties and radius.
fn cable_properties_with(e: f64) -> (RodProperties, f64) {
    let d: f64 = 0.006;
    let area = std::f64::consts::PI * d * d / 4.0;
    let i = std::f64::consts::PI * d.powi(4) / 64.0;
    let props = RodProperties {
        stiffness: SectionStiffness::isotropic(e * area, e * i, e * i / 1.3),
        linear_density: 1400.0 * area,
    };
    (props, d / 2.0)
}

fn cable_properties() -> (RodProperties, f64) {
    cable_properties_with(1.37e8)
}

fn boxed(o: impl Obstacle + 'static) -> std::sync::Arc<dyn Obstacle> {
    std::sync::Arc::new(o)
}

#[test]
fn barrier_derivatives_match_finite_differences_for_every_obstacle() {
    let props = RodProperties {
        stiffness: SectionStiffness::isotropic(50.0, 1.3, 0.7),
        linear_density: 0.9,
    };
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props,
    )
    .elements(8)
    .clamp_start()
    .gravity(Vector3::new(0.0, 0.0, -2.0))
    .build()
    .unwrap();
    let mut rng = Rng(11);
    let n = rod.n_free();
    let dx: Vec<f64> = (0..n)
        .map(|i| rng.uniform() * if rod.dofs().is_angle(i) { 0.3 } else { 0.004 })
        .collect();
    let mut state = rod.rest_state().clone();
    rod.displace(&rod.rest_state().clone(), &dx, 1.0, &mut state);
    // Every vertex within the activation distance of the plane and the ball, and of the drum
    // all but the first three; none within a few perturbations of it (the barrier's third
    // derivative jumps there, which would spoil the O(ε²) decay).
    let obstacles = vec![
        boxed(Plane::new(Vector3::new(0.0, 0.0, -0.03), Vector3::z(), 0.0).unwrap()),
        boxed(Sphere::new(Vector3::new(0.5, 0.0, 0.07), 0.03, 0.0).unwrap()),
        boxed(Cylinder::new(Vector3::new(0.8, 0.0, -0.06), Vector3::y(), 0.02, 0.0).unwrap()),
        // The rod runs through the ring off its axis (the medial axis, where the distance has a
        // cone point, stays 2 cm away).
        boxed(Torus::new(Vector3::new(0.3, 0.0, 0.02), Vector3::x(), 0.06, 0.02, 0.0).unwrap()),
    ];
    let params = ContactParams {
        radius: 0.01,
        activation: 0.5,
        stiffness: 3.0,
        stick_stiffness: 5.0,
        self_contact: false,
    };
    let problem = ContactProblem::new(&rod, obstacles, params, &state).unwrap();
    let active = problem.contact_forces(&state).len();
    assert!(
        active >= 20,
        "only {active} active contacts: the check would see little"
    );
    // Directions large enough that the finite-difference truncation error, not round-off,
    // dominates at the largest ε (ε·scale ≤ 2e-4 m against gaps ≥ 1.6e-2 m).
    let scale = |i: usize| if rod.dofs().is_angle(i) { 1.0 } else { 0.1 };
    check_derivatives(
        &problem,
        &state,
        1.0,
        CONTACT.set(),
        &mut rng,
        scale,
        "contact",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    check_derivatives(&problem, &state, 1.0, TermSet::ALL, &mut rng, scale, "all")
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn heavy_cable_touches_down_where_beam_theory_says() {
    // Clamped horizontally at height h above the ground, a heavy cable lies on the ground
    // beyond a suspended length a = (72 EI h / q)^(1/4) (small deflection: w = w' = w'' = 0 at
    // touchdown); the clamp carries 2qa/3 of the weight and the ground the rest.
    let (props, radius) = cable_properties();
    let h = 0.005;
    let (length, n) = (1.0, 200);
    let g = 9.81;
    let q = props.linear_density * g;
    let ei = props.stiffness.ei1;
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0, 0.0, radius + h],
            direction: [1.0, 0.0, 0.0],
            length,
        },
        props,
    )
    .elements(n)
    .clamp_start()
    .gravity(Vector3::new(0.0, 0.0, -g))
    .build()
    .unwrap();
    let activation = 1e-7;
    let params = ContactParams::for_line_load(radius, activation, q);
    let ground = boxed(Plane::new(Vector3::zeros(), Vector3::z(), 0.0).unwrap());
    let rest = rod.rest_state().clone();
    let problem = ContactProblem::new(&rod, vec![ground], params, &rest).unwrap();
    let mut solver = EquilibriumSolver::new(&problem, &rest, SolverParams::default());
    let solution = solver.solve(&problem, &rest, 0.0, 1.0);
    assert!(solution.report.converged(), "{:?}", solution.report);
    let state = &solution.state;
    let gap = problem.min_gap(state);
    assert!(
        gap > 0.0 && gap < activation,
        "min gap {gap:e}: penetration or no contact"
    );
    let forces = problem.contact_forces(state);
    let ground_force: f64 = forces.iter().map(|f| f.force.z).sum();
    let weight = q * length;
    let a = (72.0 * ei * (h - 0.5 * activation) / q).powf(0.25);
    let expected = weight - 2.0 * q * a / 3.0;
    let rel = (ground_force - expected) / weight;
    println!(
        "touchdown: a = {a:.4} m, ground force {ground_force:.6} N vs {expected:.6} N (rel. to weight {rel:.2e}), min gap {gap:.2e} m"
    );
    assert!(
        rel.abs() < 5e-3,
        "ground force off by {rel:e} of the weight"
    );
    // The first vertex that the ground carries (half its weight or more; vertices just
    // before touchdown sit within ĝ too, since the cable comes down like (a − x)³) is within
    // two elements of the touchdown point.
    let vertex_weight = q * length / n as f64;
    let first = forces
        .iter()
        .filter(|f| f.force.z >= 0.5 * vertex_weight)
        .map(|f| problem.sites()[f.site].vertex)
        .min()
        .unwrap();
    // Resolution: two elements, plus the span over which the cable comes within ĝ of the
    // ground before touchdown, w ≈ (qa/18EI)(a − x)³ < ĝ.
    let s_touch = first as f64 * length / n as f64;
    let fuzz = (18.0 * ei * activation / (q * a)).cbrt();
    assert!(
        (s_touch - a).abs() <= 2.0 * length / n as f64 + fuzz,
        "touchdown at s = {s_touch} vs a = {a} (± {fuzz})"
    );
    // Every force balances: clamp + ground + weight = 0.
    let clamp: Vector3<f64> = rod.reactions(state, 1.0).iter().map(|r| r.force).sum();
    let balance = clamp + Vector3::new(0.0, 0.0, ground_force - weight);
    assert!(
        balance.norm() <= 1e-6 * weight,
        "forces do not balance: {balance:?} (clamp {clamp:?})"
    );
}

#[test]
fn heavy_cable_draped_over_a_drum_wraps_it_without_penetrating() {
    // Clamped horizontally 2 cm above the top of a drum half-way along it, a heavy, limp
    // cable (qL²/EI ≈ 450) comes down on the drum and hangs over it: the half beyond the drum
    // bends it more sharply than the drum's curvature, so it wraps the drum along an arc,
    // lies on the drum's surface there within ĝ, never inside, and the clamp and the drum
    // carry its weight.
    let (props, radius) = cable_properties_with(1.37e7);
    let (length, n) = (1.0, 100);
    let g = 9.81;
    let q = props.linear_density * g;
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0, 0.0, 0.0],
            direction: [1.0, 0.0, 0.0],
            length,
        },
        props,
    )
    .elements(n)
    .clamp_start()
    .gravity(Vector3::new(0.0, 0.0, -g))
    .build()
    .unwrap();
    let drum_radius = 0.1;
    let centre = Vector3::new(0.5, 0.0, -0.02 - radius - drum_radius);
    let drum = boxed(Cylinder::new(centre, Vector3::y(), drum_radius, 0.0).unwrap());
    let activation = 1e-6;
    let params = ContactParams::for_line_load(radius, activation, q);
    let rest = rod.rest_state().clone();
    let problem = ContactProblem::new(&rod, vec![drum], params, &rest).unwrap();
    let mut solver = EquilibriumSolver::new(&problem, &rest, SolverParams::default());
    let solution = solver.solve(&problem, &rest, 0.0, 1.0);
    assert!(solution.report.converged(), "{:?}", solution.report);
    let state = &solution.state;
    let gap = problem.min_gap(state);
    assert!(gap > 0.0 && gap < activation, "min gap {gap:e}");
    let forces = problem.contact_forces(state);
    let carried: Vec<_> = forces
        .iter()
        .filter(|f| f.force.norm() > 1e-3 * q)
        .collect();
    assert!(
        carried.len() >= 5,
        "{} contacts: not wrapped",
        carried.len()
    );
    // Touching vertices lie on the drum's surface offset by the radius, within ĝ.
    for f in &forces {
        let p = state.positions()[problem.sites()[f.site].vertex];
        let d = ((p - centre) - Vector3::y() * (p - centre).y).norm() - drum_radius - radius;
        assert!(
            d > 0.0 && d < activation,
            "vertex at {d:e} from the surface"
        );
    }
    // The wrapped arc: from near the top of the drum down its far side.
    let angle = |f: &&slender_core::contact::ContactForce| f.normal.z.atan2(f.normal.x);
    let (a0, a1) = carried
        .iter()
        .map(angle)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
    // Forces balance.
    let weight = q * length;
    let contact: Vector3<f64> = forces.iter().map(|f| f.force).sum();
    let clamps: Vector3<f64> = rod.reactions(state, 1.0).iter().map(|r| r.force).sum();
    let balance = contact + clamps - Vector3::new(0.0, 0.0, weight);
    println!(
        "drape: {} contacts carrying load, on the drum from {:.1}° to {:.1}° (from +x), drum force {:?} N of weight {weight:.5} N, min gap {gap:.2e} m, balance {:.2e} N",
        carried.len(),
        a0.to_degrees(),
        a1.to_degrees(),
        contact,
        balance.norm()
    );
    assert!(a1 - a0 > 0.2, "wrap angle {} rad", a1 - a0);
    assert!(balance.norm() <= 1e-6 * weight, "{balance:?}");
    // Frictionless: every contact force is along the drum's normal (no tangential part).
    for f in &forces {
        assert!(f.force.cross(&f.normal).norm() <= 1e-12 * f.force.norm());
    }
}

#[test]
fn bad_input_names_the_field() {
    let (props, radius) = cable_properties();
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props,
    )
    .elements(10)
    .clamp_start()
    .build()
    .unwrap();
    let rest = rod.rest_state().clone();
    let plane = || boxed(Plane::new(Vector3::new(0.0, 0.0, -0.1), Vector3::z(), 0.0).unwrap());
    let ok = ContactParams {
        radius,
        activation: 1e-4,
        stiffness: 1.0,
        stick_stiffness: 1.0,
        self_contact: false,
    };
    for (params, field) in [
        (
            ContactParams {
                activation: 0.0,
                ..ok
            },
            "activation",
        ),
        (
            ContactParams {
                stiffness: f64::NAN,
                ..ok
            },
            "stiffness",
        ),
        (ContactParams { radius: -1.0, ..ok }, "radius"),
    ] {
        let e = ContactProblem::new(&rod, vec![plane()], params, &rest).unwrap_err();
        assert!(e.to_string().contains(field), "{e}");
    }
    // The cable starting inside an obstacle is refused, naming it.
    let inside = boxed(Sphere::new(Vector3::new(0.5, 0.0, 0.0), 0.05, 0.0).unwrap());
    let e = ContactProblem::new(&rod, vec![plane(), inside], ok, &rest).unwrap_err();
    assert!(e.to_string().contains("obstacles[1]"), "{e}");
    // Obstacles refuse bad shapes and friction.
    assert!(Sphere::new(Vector3::zeros(), 0.0, 0.1)
        .unwrap_err()
        .to_string()
        .contains("radius"));
    assert!(Cylinder::new(Vector3::zeros(), Vector3::zeros(), 1.0, 0.1)
        .unwrap_err()
        .to_string()
        .contains("axis"));
    assert!(Cylinder::new(Vector3::zeros(), Vector3::x(), 1.0, -0.5)
        .unwrap_err()
        .to_string()
        .contains("friction"));
}

#[test]
fn steps_stop_short_of_every_obstacle() {
    // The time of impact of each shape against a closed form.
    let plane = Plane::new(Vector3::zeros(), Vector3::z(), 0.0).unwrap();
    let p = Vector3::new(0.0, 0.0, 1.0);
    assert_eq!(
        plane.time_of_impact(&p, &Vector3::new(3.0, 0.0, -4.0), 0.2),
        0.2
    );
    assert_eq!(
        plane.time_of_impact(&p, &Vector3::new(0.0, 0.0, -0.5), 0.2),
        1.0
    );
    assert_eq!(
        plane.time_of_impact(&p, &Vector3::new(0.0, 0.0, 5.0), 0.2),
        1.0
    );
    let ball = Sphere::new(Vector3::zeros(), 1.0, 0.0).unwrap();
    let from = Vector3::new(-3.0, 0.0, 0.0);
    let t = ball.time_of_impact(&from, &Vector3::new(4.0, 0.0, 0.0), 0.5);
    assert!((t - 1.5 / 4.0).abs() < 1e-15, "{t}");
    // A chord passing outside the inflated ball is free.
    let t = ball.time_of_impact(
        &Vector3::new(-3.0, 2.0, 0.0),
        &Vector3::new(6.0, 0.0, 0.0),
        0.5,
    );
    assert_eq!(t, 1.0);
    let drum = Cylinder::new(Vector3::zeros(), Vector3::y(), 1.0, 0.0).unwrap();
    // Motion along the axis never hits; across it, at the inflated radius.
    assert_eq!(
        drum.time_of_impact(&from, &Vector3::new(0.0, 9.0, 0.0), 0.0),
        1.0
    );
    let t = drum.time_of_impact(&from, &Vector3::new(4.0, 7.0, 0.0), 0.0);
    assert!((t - 0.5).abs() < 1e-15, "{t}");
}

#[test]
fn coil_pressed_against_itself_stops_at_its_solid_length() {
    // A steel coil spring (wire d = 2 mm, coil diameter 40 mm, pitch 5 mm, 3 turns; spring
    // rate G d⁴/(8 D³ n) ≈ 800 N/m) clamped at one end and pushed along its axis at the other
    // by 10 N, which shortens the free spring by ≈ 19 mm (it also tilts): its coils close
    // (3 mm per turn, 9 mm in all) and press on each other instead, touching without crossing.
    // (With the earlier step cap — one conservative bound of the coils' motion against their
    // gap — sliding coils took only small steps: this solve took about a minute and 20 N
    // stalled at 57 % of the load. The additive advancement of `ContactProblem::max_step`
    // lets them slide: about 3 s; 20 N not re-measured.)
    let d = 0.002;
    let r = 0.5 * d;
    let section = slender_core::rod::CrossSection::Circle { diameter: d };
    let material = slender_core::rod::Material {
        young: 2.0e11,
        poisson: 0.3,
        density: 7800.0,
    };
    let props = section.properties(&material).unwrap();
    let (turns, pitch, coil_radius) = (3.0, 0.005, 0.02);
    let length = turns * (2.0 * std::f64::consts::PI * coil_radius).hypot(pitch);
    let force = 10.0;
    let build = |self_contact: bool| {
        let rod = RodBuilder::new(
            RestCurve::Helix {
                start: [coil_radius, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
                normal: [1.0, 0.0, 0.0],
                radius: coil_radius,
                pitch,
                length,
            },
            props,
        )
        .elements(90)
        .clamp_start()
        .point_force(90, Vector3::new(0.0, 0.0, -force))
        .build()
        .unwrap();
        (rod, self_contact)
    };
    let (rod, _) = build(true);
    let activation = 1e-5;
    let params = ContactParams {
        radius: r,
        activation,
        stiffness: force / activation,
        stick_stiffness: 1.0,
        self_contact: true,
    };
    let rest = rod.rest_state().clone();
    let problem = ContactProblem::new(&rod, vec![], params, &rest).unwrap();
    let mut solver = EquilibriumSolver::new(&problem, &rest, SolverParams::default());
    let solution = solver.solve(&problem, &rest, 0.0, 1.0);
    assert!(solution.report.converged(), "{:?}", solution.report);
    let state = &solution.state;
    let gap = problem.min_self_gap(state);
    let contacts = problem.self_contact_forces(state);
    let end = state.positions()[90] - rest.positions()[90];
    println!(
        "coil: {} edge pairs in contact, min gap {gap:.3e} m, end moved {:.3} mm along the axis, largest pair force {:.3} N",
        contacts.len(),
        end.z * 1e3,
        contacts.iter().map(|c| c.3).fold(0.0, f64::max)
    );
    assert!(
        gap > 0.0 && gap < activation,
        "min gap {gap:e}: crossing or no contact"
    );
    assert!(contacts.len() >= 10, "{} pairs in contact", contacts.len());
    let closure = turns * (pitch - d);
    assert!(
        -end.z < closure + 2e-3 && -end.z > 0.5 * closure,
        "end moved {} m along the axis; the coils close by {closure} m",
        -end.z
    );
    // Without self-contact the same load pushes the coils through each other.
    let free = ContactProblem::new(
        &rod,
        vec![],
        ContactParams {
            self_contact: false,
            ..params
        },
        &rest,
    )
    .unwrap();
    let mut solver = EquilibriumSolver::new(&free, &rest, SolverParams::default());
    let through = solver.solve(&free, &rest, 0.0, 1.0);
    let z = through.state.positions()[90].z - rest.positions()[90].z;
    assert!(
        -z > closure + 5e-3,
        "without self-contact the end moved only {} m",
        -z
    );
}

#[test]
fn self_contact_derivatives_match_finite_differences() {
    // A coil whose neighbouring turns are within the activation distance: edge–edge pairs
    // (crossing and near-parallel, mollified) and vertex–edge pairs all active.
    let props = RodProperties {
        stiffness: SectionStiffness::isotropic(50.0, 1.3, 0.7),
        linear_density: 0.9,
    };
    let rod = RodBuilder::new(
        RestCurve::Helix {
            start: [0.1, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 0.1,
            pitch: 0.03,
            length: 2.2 * std::f64::consts::PI * 0.1,
        },
        props,
    )
    .elements(24)
    .clamp_start()
    .build()
    .unwrap();
    let mut rng = Rng(5);
    let n = rod.n_free();
    let dx: Vec<f64> = (0..n)
        .map(|i| rng.uniform() * if rod.dofs().is_angle(i) { 0.2 } else { 0.002 })
        .collect();
    let mut state = rod.rest_state().clone();
    rod.displace(&rod.rest_state().clone(), &dx, 1.0, &mut state);
    let params = ContactParams {
        radius: 0.005,
        activation: 0.04,
        stiffness: 2.0,
        stick_stiffness: 1.0,
        self_contact: true,
    };
    let problem = ContactProblem::new(&rod, vec![], params, &state).unwrap();
    let active = problem.self_contact_forces(&state).len();
    assert!(active >= 10, "{active} active primitives");
    let scale = |i: usize| if rod.dofs().is_angle(i) { 1.0 } else { 0.05 };
    check_derivatives(
        &problem,
        &state,
        1.0,
        CONTACT.set(),
        &mut rng,
        scale,
        "self-contact",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    // Starting with turns closer than twice the radius is refused.
    let tight = ContactParams {
        radius: 0.02,
        ..params
    };
    let e = ContactProblem::new(&rod, vec![], tight, &state).unwrap_err();
    assert!(e.to_string().contains("self_contact"), "{e}");
}

#[test]
fn each_member_keeps_its_own_radius_and_a_joint_the_largest() {
    use slender_core::structure::{JointEnd, Member, StructureBuilder};
    // Two cables joined end to end in an L at z = 0: a thin one (r = 2 mm) along x, a thick
    // one (r = 5 mm) along y from its end.
    let (props, _) = cable_properties();
    let thin = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 0.5,
        },
        props,
    )
    .elements(5)
    .clamp_start()
    .build()
    .unwrap();
    let thick = RodBuilder::new(
        RestCurve::Straight {
            start: [0.5, 0.0, 0.0],
            direction: [0.0, 1.0, 0.0],
            length: 0.5,
        },
        props,
    )
    .elements(5)
    .allow_rigid_motion()
    .build()
    .unwrap();
    let s = StructureBuilder::new()
        .member(Member::Der(thin))
        .member(Member::Der(thick))
        .joint(vec![
            JointEnd {
                member: 0,
                vertex: 5,
            },
            JointEnd {
                member: 1,
                vertex: 0,
            },
        ])
        .allow_free_motion() // the thick cable may spin about its axis: no solve here
        .build()
        .unwrap();
    let radii = [0.002, 0.005];
    let params = ContactParams::for_line_load(0.001, 1e-4, 1.0);
    let floor = |z: f64| {
        vec![boxed(
            Plane::new(Vector3::new(0.0, 0.0, z), Vector3::z(), 0.0).unwrap(),
        )]
    };
    let p = ContactProblem::with_radii(&s, floor(-0.006), params, s.rest_state(), &[], &radii)
        .expect("every site clear of the floor");
    for (k, site) in p.sites().iter().enumerate() {
        let expected = if site.member == 1 || site.vertex == 5 {
            0.005 // the thick member, and the joint's vertex (the master is the thin one's end)
        } else {
            0.002
        };
        assert_eq!(
            p.site_radius(k),
            expected,
            "member {} vertex {}",
            site.member,
            site.vertex
        );
    }
    assert!((p.min_gap(s.rest_state()) - 0.001).abs() < 1e-15);
    // 4.5 mm below: clear of the thin cable, inside the thick one's radius (its sites and
    // the joint's).
    let e = ContactProblem::with_radii(&s, floor(-0.0045), params, s.rest_state(), &[], &radii)
        .expect_err("the thick cable starts inside the floor");
    println!("{e}");
    assert!(e.to_string().contains("obstacles[0]") && e.to_string().contains("0.005"));
    // Without per-member radii every site has params.radius (1 mm).
    let p = ContactProblem::new(&s, floor(-0.0045), params, s.rest_state()).unwrap();
    assert!((0..p.sites().len()).all(|k| p.site_radius(k) == 0.001));
    for bad in [-1.0, f64::NAN] {
        let e = ContactProblem::with_radii(
            &s,
            floor(-0.006),
            params,
            s.rest_state(),
            &[],
            &[0.002, bad],
        )
        .expect_err("refused");
        println!("{e}");
        assert!(e.to_string().contains("radii[1]"), "{e}");
    }
}

/// The sliding contacts' lagged dissipation potential m φ_ε(|P (x − o)|) — on its sliding
/// branch (slip beyond ε) and its smoothed one (within ε), with tilted normals — has the
/// gradient and Hessian it claims; its force never exceeds m and opposes the slip.
#[test]
fn sliding_friction_derivatives_match_finite_differences() {
    let props = RodProperties {
        stiffness: SectionStiffness::isotropic(50.0, 1.3, 0.7),
        linear_density: 0.9,
    };
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props,
    )
    .elements(8)
    .clamp_start()
    .build()
    .unwrap();
    let mut rng = Rng(23);
    let n = rod.n_free();
    let dx: Vec<f64> = (0..n)
        .map(|i| rng.uniform() * if rod.dofs().is_angle(i) { 0.3 } else { 0.004 })
        .collect();
    let mut state = rod.rest_state().clone();
    rod.displace(&rod.rest_state().clone(), &dx, 1.0, &mut state);
    let obstacles = vec![boxed(
        Plane::new(Vector3::new(0.0, 0.0, -0.03), Vector3::z(), 0.4).unwrap(),
    )];
    let params = ContactParams {
        radius: 0.01,
        activation: 0.5,
        stiffness: 3.0,
        stick_stiffness: 5.0,
        self_contact: false,
    };
    let problem = ContactProblem::new(&rod, obstacles, params, &state).unwrap();
    // Slides with ε = m / (k_t w) = 0.01 m, slips of 3 ε and 0.2 ε, perturbations of a site
    // below 4e-3 m: every site stays on its branch, away from the C¹ seam at |slip| = ε, and
    // the sliding branch's curvature (1 / |slip|) shows truncation errors above round-off.
    let slides: Vec<Friction> = problem
        .sites()
        .iter()
        .enumerate()
        .map(|(k, site)| {
            let x = rod.site_position(&state, site);
            let normal = Vector3::new(0.2 * (k as f64).sin(), 0.1, 1.0).normalize();
            let magnitude = 0.05 * site.length;
            let eps = Friction::smoothing(magnitude, site.length, params.stick_stiffness);
            let t = normal
                .cross(&Vector3::new(1.0, 0.3 * k as f64, 0.0))
                .normalize();
            let slip = if k % 2 == 0 { 3.0 } else { 0.2 } * eps;
            Friction::Slide {
                origin: x - t * slip + normal * 0.05,
                normal,
                magnitude,
            }
        })
        .collect();
    problem.set_friction_state(&slides);
    for (f, site) in slides.iter().zip(problem.sites()) {
        let x = rod.site_position(&state, site);
        let force = f.force(&x, site.length, params.stick_stiffness);
        let Friction::Slide { magnitude, .. } = *f else {
            unreachable!()
        };
        assert!(force.norm() <= magnitude * (1.0 + 1e-12), "{force:?}");
        assert!(
            force.dot(&f.slip(&x)) < 0.0,
            "{force:?} does not oppose the slip"
        );
    }
    let scale = |_: usize| 1.0;
    check_derivatives(
        &problem,
        &state,
        1.0,
        FRICTION.set(),
        &mut rng,
        scale,
        "sliding friction",
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
