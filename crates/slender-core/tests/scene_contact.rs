//! Obstacles in scene files, solved by `Session`: a cable on a frictionless floor (the floor
//! and the clamp carry the weight), a free cable on a rough slope that holds (friction within
//! the cone, displacement far below the activation distance) and on a slope steeper than
//! atan μ (no equilibrium: reported as not converged, the last state kept), bad input naming
//! the field, and a saved scene with its obstacles solving to the same equilibrium.

use slender_core::scene::{Scene, SceneStep, Session};

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

const G: f64 = 9.81;
/// Cable: d = 8 mm, ρ = 1500 kg/m³.
const D: f64 = 0.008;
const RHO: f64 = 1500.0;

fn weight_per_length() -> f64 {
    RHO * std::f64::consts::PI * D * D / 4.0 * G
}

/// Sum of the contact forces (normal + friction) over every obstacle.
fn contact_total(step: &SceneStep) -> [f64; 3] {
    let mut t = [0.0; 3];
    for o in &step.obstacles {
        for c in &o.contacts {
            for (i, ti) in t.iter_mut().enumerate() {
                *ti += c.normal_force[i] + c.friction_force[i];
            }
        }
    }
    t
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The largest distance (m) between corresponding points of `a` and `b`.
fn largest_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| norm([p[0] - q[0], p[1] - q[1], p[2] - q[2]]))
        .fold(0.0, f64::max)
}

/// Every contact's friction is within the cone: |f_t| ≤ μ |f_n| (up to round-off).
fn assert_in_cone(step: &SceneStep) {
    for o in &step.obstacles {
        for c in &o.contacts {
            let (ft, fn_) = (norm(c.friction_force), norm(c.normal_force));
            assert!(
                ft <= o.friction * fn_ * (1.0 + 1e-9) + 1e-15,
                "{} vertex {}: friction {ft} > μ {} × normal {fn_}",
                o.name,
                c.vertex,
                o.friction
            );
        }
    }
}

const ACTIVATION: f64 = 1e-4;

/// A 1 m cable clamped horizontally at x = 0 at height r + ĝ/2, over a floor z = 0.
fn floor_scene(mu: f64) -> String {
    let z0 = D / 2.0 + ACTIVATION / 2.0;
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]
[[rods]]
name = "cable"
elements = 40
centerline = {{ kind = "straight", start = [0.0, 0.0, {z0}], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 5.0e8, poisson = 0.4, density = {RHO} }}
supports = [{{ kind = "clamp", vertex = "start" }}]
[[obstacles]]
name = "floor"
friction = {mu}
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}
[contact]
activation = {ACTIVATION}
"#
    )
}

#[test]
fn cable_on_frictionless_floor_floor_and_clamp_carry_the_weight() {
    let s = Session::new(scene(&floor_scene(0.0))).expect("compiles");
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged, "{:?}", s.report(0).status);
    let weight = weight_per_length() * 1.0;
    let contact = contact_total(&r);
    let clamp = r.rods[0].supports[0].force;
    let total_z = contact[2] + clamp[2];
    let err = (total_z - weight).abs() / weight;
    println!(
        "floor: contacts {} carry {:.6} N, clamp {:.6} N, weight {weight:.6} N, rel. error {err:.2e}, min gap {:?}",
        r.obstacles[0].contacts.len(),
        contact[2],
        clamp[2],
        r.min_gap
    );
    assert!(err < 1e-9, "vertical balance {err:e}");
    assert!(contact[2] > 0.9 * weight, "the floor carries most of it");
    let g = r.min_gap.expect("min gap");
    assert!(g > 0.0 && g < ACTIVATION, "min gap {g}");
    for c in &r.obstacles[0].contacts {
        assert!(c.gap > 0.0 && c.gap < ACTIVATION);
        assert_eq!(norm(c.friction_force), 0.0);
    }
    assert!(r.rods[0].relative_force_imbalance < 1e-9);
}

/// A free 0.5 m cable lying across a plane through the origin tilted by `angle` about x (its
/// fall line in the y–z plane), at gap ĝ/2, held only against spinning about its own axis.
fn slope_scene(angle: f64, mu: f64) -> String {
    let (s, c) = angle.sin_cos();
    let n = [0.0, -s, c];
    let h = D / 2.0 + ACTIVATION / 2.0;
    let start = [-0.25, n[1] * h, n[2] * h];
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]
[[rods]]
name = "cable"
elements = 20
centerline = {{ kind = "straight", start = [{}, {}, {}], direction = [1.0, 0.0, 0.0], length = 0.5 }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 5.0e8, poisson = 0.4, density = {RHO} }}
supports = [{{ kind = "twist_hold", vertex = "start" }}]
[[obstacles]]
name = "slope"
friction = {mu}
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [{}, {}, {}] }}
[contact]
activation = {ACTIVATION}
"#,
        start[0], start[1], start[2], n[0], n[1], n[2]
    )
}

#[test]
fn cable_on_rough_slope_holds_below_the_friction_angle() {
    let mu: f64 = 0.5;
    let angle = 0.8 * mu.atan();
    let spec = scene(&slope_scene(angle, mu));
    let rest = spec.clone();
    let s = Session::new(spec).expect("compiles");
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged, "{:?}", s.report(0).status);
    assert_in_cone(&r);
    // Held by the slope alone: the contacts carry the whole weight.
    let weight = weight_per_length() * 0.5;
    let contact = contact_total(&r);
    let err = ((contact[2] - weight).abs() + contact[0].abs() + contact[1].abs()) / weight;
    // Tangential displacement from rest: elastic deflection of the sticking anchors only.
    let x0 = Session::new(rest).unwrap().compiled().rest_positions(0);
    let mut slide: f64 = 0.0;
    for (p, q) in r.rods[0].positions.iter().zip(&x0) {
        slide = slide.max(
            (p[0] - q[0])
                .abs()
                .max(((p[1] - q[1]) * angle.cos() + (p[2] - q[2]) * angle.sin()).abs()),
        );
    }
    let ratio = r.obstacles[0]
        .contacts
        .iter()
        .map(|c| norm(c.friction_force) / norm(c.normal_force))
        .fold(0.0, f64::max);
    println!(
        "slope {:.2}° (atan μ = {:.2}°): {} contacts, weight balance {err:.2e}, largest |f_t|/|f_n| {ratio:.4} (tan = {:.4}), tangential displacement {slide:.3e} m",
        angle.to_degrees(),
        mu.atan().to_degrees(),
        r.obstacles[0].contacts.len(),
        angle.tan()
    );
    assert_eq!(r.obstacles[0].contacts.len(), 21);
    assert!(r.obstacles[0].contacts.iter().all(|c| c.sticking));
    assert!(err < 1e-6, "weight balance {err:e}");
    assert!(slide < 1e-3 * ACTIVATION, "slid {slide} m");
    assert!(
        (ratio - angle.tan()).abs() < 1e-3,
        "f_t/f_n {ratio} vs tan {}",
        angle.tan()
    );
}

#[test]
fn cable_on_slope_steeper_than_the_friction_angle_is_not_held() {
    let mu: f64 = 0.5;
    let angle = 1.3 * mu.atan();
    let s = Session::new(scene(&slope_scene(angle, mu))).expect("compiles");
    let rep = s.report(0);
    println!("steep slope {:.2}°: {:?}", angle.to_degrees(), rep.status);
    assert!(!rep.converged(), "a quasi-static solve cannot hold it");
    let r = s.results(0, None, 1.0, 1);
    assert!(!r.converged);
}

#[test]
fn bad_obstacles_and_contact_tables_name_the_field() {
    let base = floor_scene(0.0);
    let floor = r#"shape = { kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }"#;
    let cases: Vec<(String, &str)> = vec![
        (base.replace("friction = 0", "friction = -0.1"), "obstacles[0].friction"),
        (
            base.replace(floor, r#"shape = { kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 0.0] }"#),
            "obstacles[0].shape.normal",
        ),
        (
            base.replace(floor, r#"shape = { kind = "sphere", center = [0.5, 0.0, -1.0], radius = 0.0 }"#),
            "obstacles[0].shape.radius",
        ),
        (
            base.replace(floor, r#"shape = { kind = "box", center = [0.5, 0.0, -1.0], size = [1.0, 0.0, 1.0] }"#),
            "obstacles[0].shape.size[1]",
        ),
        (
            base.replace(floor, r#"shape = { kind = "cylinder", point = [0.5, 0.0, -1.0], axis = [0.0, 1.0, 0.0], radius = -1.0 }"#),
            "obstacles[0].shape.radius",
        ),
        (
            base.replace(
                floor,
                r#"shape = { kind = "mesh", vertices = [[0.0, -1.0, -0.1], [2.0, -1.0, -0.1], [0.0, 1.0, -0.1], [1.0, -1.0, -0.1]], triangles = [[0, 1, 2], [0, 1, 3]] }"#,
            ),
            "obstacles[0].shape.triangles[1]",
        ),
        (
            // The cable starts inside a sphere.
            format!(
                "{base}\n[[obstacles]]\nshape = {{ kind = \"sphere\", center = [0.5, 0.0, 0.0], radius = 0.05 }}\n"
            ),
            "obstacles[1]",
        ),
        (base.replace("activation = 0.0001", "activation = 0.0"), "contact.activation"),
        (
            base.replace("activation = 0.0001", "activation = 0.0001\nstiffness = -1.0"),
            "contact.stiffness",
        ),
        (
            base.replace(
                "section = { shape = \"circle\", diameter = 0.008 }\nmaterial = { young = 5.0e8, poisson = 0.4, density = 1500 }",
                "section = { shape = \"stiffness\", ea = 1e4, ei1 = 0.1, ei2 = 0.1, gj = 0.1, linear_density = 0.08 }",
            ),
            "rods[0].contact_radius",
        ),
        (
            base.replace(
                "supports = [{ kind = \"clamp\", vertex = \"start\" }]",
                "supports = [{ kind = \"clamp\", vertex = \"start\" }]\ncontact_radius = 0.0",
            ),
            "rods[0].contact_radius",
        ),
    ];
    for (text, path) in cases {
        let (p, m) = match Session::new(
            toml::from_str::<Scene>(&text).unwrap_or_else(|e| panic!("{e}\n{text}")),
        ) {
            Ok(_) => panic!("accepted ({path}):\n{text}"),
            Err(e) => (e.path, e.message),
        };
        println!("{p}: {m}");
        assert_eq!(p, path, "{m}");
    }
    // Time stepping with obstacles compiles, except with the midpoint rule (its extrapolated
    // state may end inside an obstacle), which is refused naming the scheme.
    assert!(Session::new(scene(&base)).is_ok());
    let timed: Scene = scene(&format!("{base}\n[time]\ndt = 0.001\nduration = 0.01\n"));
    assert!(timed.compile().is_ok());
    let midpoint: Scene = scene(&format!(
        "{base}\n[time]\ndt = 0.001\nduration = 0.01\nscheme = \"midpoint\"\n"
    ));
    let e = midpoint.compile().expect_err("refused");
    assert_eq!(e.path, "time.scheme", "{}", e.message);
    println!("{}: {}", e.path, e.message);
}

#[test]
fn saved_scene_with_obstacles_solves_to_the_same_equilibrium() {
    let text = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 40
centerline = { kind = "straight", start = [0.0, 0.0, 0.3], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.008 }
material = { young = 5.0e8, poisson = 0.4, density = 1500.0 }
supports = [{ kind = "clamp", vertex = "start" }]
[[obstacles]]
name = "bracket"
shape = { kind = "cylinder", point = [0.35, 0.0, 0.2], axis = [0.0, 1.0, 0.0], radius = 0.03 }
[[obstacles]]
name = "floor"
shape = { kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }
[contact]
activation = 1e-4
"#;
    let mut s = Session::new(scene(text)).expect("compiles");
    assert!(s.report(0).converged(), "{:?}", s.report(0).status);
    let e = s
        .move_support_by(
            0,
            0,
            nalgebra::Vector3::zeros(),
            nalgebra::Vector3::new(-0.03, 0.0, 0.02),
        )
        .expect("edit");
    assert!(e.converged, "{:?}", e.reason);
    let saved = s.saved();
    assert_eq!(saved.obstacles.len(), 2);
    let round: Scene = toml::from_str(&toml::to_string(&saved).expect("toml")).expect("parses");
    assert_eq!(round, saved);
    let mut again = Session::new(round).expect("compiles");
    for k in 1..=again.motion_steps() {
        let st = again.run_motion_step(k);
        assert!(st.converged);
    }
    let a = s.results(0, None, 1.0, 1);
    let b = again.results(0, None, 1.0, 1);
    let diff = largest_distance(&a.rods[0].positions, &b.rods[0].positions);
    println!(
        "saved scene: largest position difference {diff:.3e} m, bracket contacts {} / {}",
        a.obstacles[0].contacts.len(),
        b.obstacles[0].contacts.len()
    );
    assert!(diff < 1e-6, "{diff}");
    assert!(a.rods[0].relative_force_imbalance < 1e-9);
}

#[test]
fn self_contact_in_scenes_solves_and_refuses_a_crossing_start() {
    let cable = |points: &str| {
        format!(
            r#"
gravity = [0.0, 0.0, -{G}]
[[rods]]
name = "cable"
centerline = {{ kind = "polyline", points = {points} }}
elements = 40
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 5.0e8, poisson = 0.4, density = {RHO} }}
supports = [{{ kind = "clamp", vertex = "start" }}]
[contact]
self_contact = true
activation = {ACTIVATION}
"#
        )
    };
    // A hook: out, across and back toward its start, not touching itself.
    let ok = cable("[[0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [0.3, 0.1, 0.0], [0.1, 0.1, 0.0]]");
    let s = Session::new(scene(&ok)).expect("compiles");
    let r = s.results(0, None, 1.0, 1);
    println!(
        "self-contact hook: {:?}, relative imbalance {:.2e}",
        s.report(0).status,
        r.rods[0].relative_force_imbalance
    );
    assert!(r.converged, "{:?}", s.report(0).status);
    assert!(r.obstacles.is_empty() && r.min_gap.is_none());
    assert!(r.rods[0].relative_force_imbalance < 1e-9);
    // Its last edge comes back within 3 mm of its first (radius 4 mm): refused.
    let crossing = cable(
        "[[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.1, 0.0], [0.25, 0.1, 0.0], [0.25, 0.003, 0.0]]",
    );
    let e = Session::new(scene(&crossing)).err().expect("refused");
    println!("{}: {}", e.path, e.message);
    assert_eq!(e.path, "contact.self_contact");
}

/// 1 cm drags of the clamp of examples/cable_over_bracket.toml, four in a row along each of
/// +x (pushing the cable toward the bracket), −x, +y, +z and −z: every one converges, with
/// every friction force within the cone and the clamp, the contacts and the weight in
/// balance. (With the sliding force a dead force −μ f_n ŝ, a linear potential that drags on
/// a contact that lifts off or turns, 16 of these 20 converged.)
#[test]
fn cable_over_bracket_follows_one_centimetre_drags_of_its_clamp_in_every_direction() {
    let mut base = scene(include_str!("../../../examples/cable_over_bracket.toml"));
    base.motion.clear();
    // The scene's data: a 1.6 m cable, d = 8 mm, ρ = 1500 kg/m³.
    let weight = weight_per_length() * 1.6;
    let directions = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    for d in directions {
        let mut s = Session::new(base.clone()).expect("compiles");
        assert!(s.report(0).converged(), "{:?}", s.report(0).status);
        for k in 0..4 {
            let e = s
                .move_support_by(
                    0,
                    0,
                    nalgebra::Vector3::zeros(),
                    nalgebra::Vector3::from(d) * 0.01,
                )
                .expect("edit");
            assert!(e.converged, "{d:?} drag {k}: {:?}", e.reason);
            let r = s.results(0, None, 1.0, 1);
            assert!(r.converged, "{d:?} drag {k}");
            // A sliding force is μ f_n of the state before the last warm re-solve: within
            // the solver's tolerance of μ times the reported normal force.
            for o in &r.obstacles {
                for c in &o.contacts {
                    let (ft, fn_) = (norm(c.friction_force), norm(c.normal_force));
                    assert!(
                        ft <= o.friction * fn_ * (1.0 + 1e-5) + 1e-15,
                        "{d:?} drag {k}: {} vertex {}: friction {ft} > μ {} × normal {fn_}",
                        o.name,
                        c.vertex,
                        o.friction
                    );
                }
            }
            let contact = contact_total(&r);
            let clamp = r.rods[0].supports[0].force;
            let total = [
                contact[0] + clamp[0],
                contact[1] + clamp[1],
                contact[2] + clamp[2] - weight,
            ];
            let err = norm(total) / weight;
            assert!(err <= 1e-6, "{d:?} drag {k}: imbalance {err:e}");
            assert!(
                r.rods[0].relative_force_imbalance < 1e-9,
                "{d:?} drag {k}: {}",
                r.rods[0].relative_force_imbalance
            );
        }
    }
}

/// The clamp of examples/cable_over_bracket.toml (floor made frictionless) dragged 1 cm down
/// and sideways, pressing the cable onto the bracket and the floor it rests on: the first
/// guess holds the resting cable where it touches (the drag's motion faded out toward the
/// contacts, as toward a support), so each drag converges in one load step (carried rigidly,
/// the cable's vertices were stopped at the floor and the others not: 400 Newton iterations
/// in 22 load steps for the downward drag). Frictionless, the equilibrium does not depend on
/// the path: the scene solved cold with its cable starting at the dragged clamp (the gravity
/// ramp dropping it onto the bracket and the floor) ends on the same one.
#[test]
fn dragging_a_resting_cable_onto_its_contacts_holds_them_in_the_first_guess() {
    let mut base = scene(include_str!("../../../examples/cable_over_bracket.toml"));
    base.motion.clear();
    base.obstacles[1].friction = 0.0;
    for d in [[0.0, 0.0, -0.01], [0.0, 0.01, -0.01]] {
        let mut s = Session::new(base.clone()).expect("compiles");
        assert!(s.report(0).converged(), "{:?}", s.report(0).status);
        let e = s
            .move_support_by(0, 0, nalgebra::Vector3::zeros(), nalgebra::Vector3::from(d))
            .expect("edit");
        println!(
            "drag {d:?}: {} Newton iterations, {} load steps",
            e.iterations, e.load_steps
        );
        assert!(e.converged, "{d:?}: {:?}", e.reason);
        assert_eq!(e.load_steps, 1, "{d:?}");
        let a = s.results(0, None, 1.0, 1);
        assert!(
            !a.obstacles[1].contacts.is_empty(),
            "the cable rests on the floor"
        );
        let text = toml::to_string(&base).expect("toml");
        let start = format!("[{:?}, {:?}, {:?}]", d[0], d[1], 0.3 + d[2]);
        let moved = scene(&text.replacen("[0.0, 0.0, 0.3]", &start, 1));
        assert_ne!(moved, base, "the cable's start moved");
        let cold = Session::new(moved).expect("compiles");
        assert!(cold.report(0).converged(), "{:?}", cold.report(0).status);
        let b = cold.results(0, None, 1.0, 1);
        let diff = largest_distance(&a.rods[0].positions, &b.rods[0].positions);
        println!("  cold solve from {start}: largest position difference {diff:.3e} m");
        assert!(diff < 1e-6, "{d:?}: {diff}");
    }
}

/// A 0.5 m cantilever (d = 6 mm, E = 1 GPa, ρ = 1500 kg/m³) of `elements` elements along x,
/// clamped at x = 0, sagging under gravity over the obstacle `shape` (a TOML inline table)
/// named `name`.
fn cantilever_over(elements: usize, name: &str, shape: &str) -> String {
    format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = {elements}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.5 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1500.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}]
[[obstacles]]
name = "{name}"
shape = {shape}
"#
    )
}

/// A bar thinner than an element passes between two vertices of a coarse cable (contact acts at
/// the vertices): the solve converges to a cable running through the bar, and the step says so
/// — the edge, the obstacle, how deep. Meshed finer than the bar, the cable rests on it and
/// nothing is reported.
#[test]
fn an_edge_running_through_a_thin_bar_is_reported() {
    // A 0.5 m cantilever whose free sag at x = 0.3125 m (mid-edge of 4 elements) is about
    // 2.6 cm; the bar (radius 1 cm) is centred 2 cm below the rest line there.
    let text = |elements: usize| {
        cantilever_over(
            elements,
            "bar",
            "{ kind = \"cylinder\", point = [0.3125, 0.0, -0.02], axis = [0.0, 1.0, 0.0], radius = 0.01 }",
        )
    };
    let coarse = Session::new(scene(&text(4))).expect("compiles");
    assert!(
        coarse.report(0).converged(),
        "{:?}",
        coarse.report(0).status
    );
    let step = coarse.results(0, None, 1.0, 1);
    assert!(
        step.obstacles[0].contacts.is_empty(),
        "no vertex is near the bar"
    );
    let through = &step.edges_through_obstacles;
    println!("coarse cable: {through:?}");
    assert_eq!(through.len(), 1, "{through:?}");
    let e = &through[0];
    assert_eq!(
        (e.rod.as_str(), e.edge, e.obstacle.as_str()),
        ("cable", 2, "bar")
    );
    // The deepest point is inside the bar: within its radius of the axis, by `depth`.
    let r = ((e.position[0] - 0.3125).powi(2) + (e.position[2] + 0.02).powi(2)).sqrt();
    assert!(
        (0.01 - r - e.depth).abs() < 1e-9,
        "r = {r}, depth {}",
        e.depth
    );
    assert!(e.depth > 1e-3 && e.depth < 0.01, "depth {}", e.depth);

    let fine = Session::new(scene(&text(100))).expect("compiles");
    assert!(fine.report(0).converged(), "{:?}", fine.report(0).status);
    let step = fine.results(0, None, 1.0, 1);
    assert!(
        !step.obstacles[0].contacts.is_empty(),
        "the fine cable rests on the bar"
    );
    assert!(
        step.edges_through_obstacles.is_empty(),
        "{:?}",
        step.edges_through_obstacles
    );
}

#[test]
fn an_edge_crossing_a_mesh_panel_is_reported() {
    // The cantilever of the bar test over a horizontal panel (a mesh: a surface without an
    // inside) 2 cm wide, 1 cm below the rest line at x = 0.15–0.17 m. With 4 elements edge 1
    // (x = 0.125–0.25 m) sags from 0.6 to 2.0 cm and crosses the panel between its
    // vertices; with 100 elements the cable rests on the panel.
    let text = |elements: usize| {
        cantilever_over(
            elements,
            "panel",
            "{ kind = \"mesh\", vertices = [[0.15, -0.1, -0.01], [0.17, -0.1, -0.01], \
             [0.17, 0.1, -0.01], [0.15, 0.1, -0.01]], triangles = [[0, 1, 2], [0, 2, 3]] }",
        )
    };
    let coarse = Session::new(scene(&text(4))).expect("compiles");
    assert!(
        coarse.report(0).converged(),
        "{:?}",
        coarse.report(0).status
    );
    let step = coarse.results(0, None, 1.0, 1);
    assert!(
        step.obstacles[0].contacts.is_empty(),
        "no vertex is near the panel"
    );
    let through = &step.edges_through_obstacles;
    println!("coarse cable over the panel: {through:?}");
    assert_eq!(through.len(), 1, "{through:?}");
    let e = &through[0];
    assert_eq!(
        (
            e.rod.as_str(),
            e.shell,
            e.edge,
            e.vertices.as_slice(),
            e.obstacle.as_str()
        ),
        ("cable", false, 1, [1, 2].as_slice(), "panel")
    );
    // It crosses at the panel, on the edge's chord between its two vertices.
    assert_eq!(e.depth, 0.0);
    assert!((e.position[2] + 0.01).abs() < 1e-9, "{e:?}");
    assert!((0.15..=0.17).contains(&e.position[0]), "{e:?}");
    let x = &step.rods[0].positions;
    let t = (e.position[0] - x[1][0]) / (x[2][0] - x[1][0]);
    for ((a, b), p) in x[1].iter().zip(&x[2]).zip(&e.position) {
        assert!((a + t * (b - a) - p).abs() < 1e-9, "{e:?}");
    }

    let fine = Session::new(scene(&text(100))).expect("compiles");
    assert!(fine.report(0).converged(), "{:?}", fine.report(0).status);
    let step = fine.results(0, None, 1.0, 1);
    assert!(
        !step.obstacles[0].contacts.is_empty(),
        "the fine cable rests on the panel"
    );
    assert!(
        step.edges_through_obstacles.is_empty(),
        "{:?}",
        step.edges_through_obstacles
    );
}
