//! Tests of the message handler without a socket: named hostile messages get an error reply
//! naming the problem, and a fuzz test (proptest) of arbitrary text and of well-formed
//! requests with hostile values checks that [`handle`] never panics, always answers JSON with
//! `ok`, names the field of every error, and leaves the equilibrium as it was whenever it
//! refuses a request or an edit does not converge.

use std::cell::RefCell;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use serde_json::{json, Value};
use slender_core::scene::{Scene, Session};

use super::history::{History, MAX_UNDO};
use super::protocol::handle;

/// A short cable (12 elements, 0.6 m) clamped at its start, clipped at vertex 6, pinned at
/// its end, under gravity, and a coarse flat strip clamped at both ends: every kind of edit
/// applies to them and re-solves quickly.
const SCENE: &str = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 12
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.6 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [
    { kind = "clamp", vertex = "start" },
    { kind = "clip", vertex = 6 },
    { kind = "pin", vertex = "end" },
]
[[shells]]
name = "strip"
length = 0.2
width = 0.02
thickness = 5.0e-4
material = { young = 5.0e9, poisson = 0.3, density = 2000.0 }
elements = 4
width_elements = 1
grading = { kind = "uniform" }
clamps = [{ edge = "start" }, { edge = "end", offset = [-0.01, 0.0, 0.0] }]
"#;

fn session() -> Session {
    let scene: Scene = toml::from_str(SCENE).expect("the test scene parses");
    Session::new(scene).expect("the test scene compiles")
}

/// A 0.8 m cable clamped 6 cm above a rough floor, hanging onto a box, a ball, a round bar
/// and a ramp (an inline triangle mesh): every obstacle kind, contacts on three of them.
const CONTACT_SCENE: &str = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 20
centerline = { kind = "straight", start = [0.0, 0.0, 0.06], direction = [1.0, 0.0, 0.0], length = 0.8 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 2.0e8, poisson = 0.4, density = 1500.0 }
supports = [{ kind = "clamp", vertex = "start" }]
[[obstacles]]
name = "floor"
friction = 0.3
shape = { kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 2.0] }
[[obstacles]]
name = "block"
shape = { kind = "box", center = [0.2, 0.0, 0.015], size = [0.06, 0.08, 0.03], rotate = [0.0, 0.0, 0.4] }
[[obstacles]]
friction = 0.2
shape = { kind = "sphere", center = [0.4, 0.0, 0.0], radius = 0.045 }
[[obstacles]]
name = "bar"
shape = { kind = "cylinder", point = [0.55, 0.0, 0.025], axis = [0.0, 3.0, 0.0], radius = 0.012 }
[[obstacles]]
name = "ramp"
friction = 0.1
shape = { kind = "mesh", vertices = [[0.6, -0.12, 0.0], [0.85, -0.12, 0.04], [0.85, 0.12, 0.04], [0.6, 0.12, 0.0]], triangles = [[0, 1, 2], [0, 2, 3]] }
[[obstacles]]
name = "ring"
shape = { kind = "torus", center = [0.7, 0.08, 0.02], axis = [0.0, 0.0, 2.0], radius = 0.03, tube_radius = 0.008 }
[contact]
activation = 1e-4
"#;

fn contact_session() -> Session {
    let scene: Scene = toml::from_str(CONTACT_SCENE).expect("the contact scene parses");
    Session::new(scene).expect("the contact scene compiles")
}

/// The scene's smallest gap and its number of active contacts in a reply's view.
fn gap_and_contacts(v: &Value) -> (f64, usize) {
    let gap = v["view"]["min_gap"]
        .as_f64()
        .expect("a contact scene reports its min gap");
    let n = v["view"]["obstacles"]
        .as_array()
        .expect("the view lists the obstacles")
        .iter()
        .map(|o| o["contacts"].as_array().expect("contacts").len())
        .sum();
    (gap, n)
}

/// Every vertex position of every rod and strip, and the supports' and clamps' poses, bit
/// for bit.
fn equilibrium(s: &Session) -> (Vec<Vec<[f64; 3]>>, Vec<String>) {
    let step = s.results(0, None, 1.0, 1);
    let mut poses: Vec<String> = (0..s.compiled().rods.len())
        .flat_map(|r| (0..s.compiled().rods[r].supports.len()).map(move |k| (r, k)))
        .map(|(r, k)| format!("{:?}", s.pose(r, k)))
        .collect();
    for (i, c) in s.compiled().shells.iter().enumerate() {
        poses.extend((0..c.clamps.len()).map(|k| format!("{:?}", s.shell_pose(i, k))));
    }
    let shapes = step
        .rods
        .into_iter()
        .map(|r| r.positions)
        .chain(step.shells.into_iter().map(|s| s.positions))
        .collect();
    (shapes, poses)
}

/// Sends `message`; checks the reply's shape; returns it and whether the equilibrium was
/// kept. Panics (fails the test) on a malformed reply.
fn exchange(s: &mut Session, message: &str) -> (Value, bool) {
    let before = equilibrium(s);
    let reply = handle(s, message);
    let v: Value = serde_json::from_str(&reply).expect("the reply is JSON");
    let ok = v["ok"].as_bool().expect("the reply has a boolean `ok`");
    if !ok {
        let field = v["error"]["field"]
            .as_str()
            .expect("an error names its field");
        let message = v["error"]["message"]
            .as_str()
            .expect("an error says what is wrong");
        assert!(!field.is_empty() && !message.is_empty(), "{reply}");
    } else {
        assert!(
            v["view"]["rods"].is_array(),
            "an ok reply carries the view: {reply}"
        );
    }
    (v, equilibrium(s) == before)
}

fn error_of(v: &Value) -> (String, String) {
    (
        v["error"]["field"].as_str().unwrap_or("").to_string(),
        v["error"]["message"].as_str().unwrap_or("").to_string(),
    )
}

/// The coordinates of a message reach the session to the bit: the page writes each number in
/// its shortest form, and the parser must give back exactly that double (serde_json's default
/// fast path reads `0.0050000246600000004` as `0.00500002466`, one ulp off).
#[test]
fn the_numbers_of_a_message_are_read_to_the_bit() {
    let mut s = session();
    let y = 0.005_000_024_660_000_000_4_f64;
    assert_eq!(format!("{y}"), "0.0050000246600000004");
    let (v, _) = exchange(
        &mut s,
        r#"{"op": "move", "rod": 0, "support": 2, "position": [0.6, 0.0050000246600000004, 0.0]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    let pose = s.pose(0, 2).expect("the pin");
    assert_eq!(
        pose.position.y.to_bits(),
        y.to_bits(),
        "{}",
        pose.position.y
    );
    // And the reply gives it back as written.
    let pin = &v["view"]["rods"][0]["supports"][2]["position"][1];
    assert_eq!(pin.as_f64().map(f64::to_bits), Some(y.to_bits()), "{pin}");
}

#[test]
fn hostile_messages_are_refused_by_name_and_keep_the_equilibrium() {
    let mut s = session();
    let cases: &[(&str, &str, &str)] = &[
        // (message, expected field, expected words in the message)
        ("{bad json", "request", "key must be a string"),
        ("", "request", "EOF"),
        ("[1, 2]", "request", "op"),
        (r#"{"op": "teleport"}"#, "request", "unknown variant"),
        (r#"{"op": "state", "extra": 1}"#, "request", "unknown field"),
        (
            r#"{"op": "move", "rod": 0, "support": 7, "position": [0, 0, 0]}"#,
            "rods[0].supports[7]",
            "no such support",
        ),
        (
            r#"{"op": "move", "rod": 3, "support": 0, "position": [0, 0, 0]}"#,
            "rods[3]",
            "no such rod",
        ),
        (
            r#"{"op": "move", "rod": 0, "support": 2, "position": [NaN, 0, 0]}"#,
            "request",
            "NaN",
        ),
        (
            r#"{"op": "move", "rod": 0, "support": 2, "position": [1e999, 0, 0]}"#,
            "request",
            "number out of range",
        ),
        (
            r#"{"op": "add_support", "rod": 0, "kind": "clip", "at": 0.9}"#,
            "rods[0].supports.at",
            "beyond the cable",
        ),
        (
            r#"{"op": "add_support", "rod": 0, "kind": "clip", "at": -0.1}"#,
            "rods[0].supports.at",
            "beyond the cable",
        ),
        (
            r#"{"op": "add_support", "rod": 0, "kind": "clamp", "at": 0.3}"#,
            "rods[0].supports",
            "clamps are added in the scene file",
        ),
        (
            r#"{"op": "move_by", "rod": 0, "support": 2, "translation": [1e6, 0, 0]}"#,
            "rods[0].supports[2]",
            "too large",
        ),
        (
            r#"{"op": "move", "rod": 0, "support": 2, "position": [0.6, 0, 0], "rotation": [0, 0, 0.5]}"#,
            "rods[0].supports[2].rotation",
            "only translate",
        ),
        (
            r#"{"op": "remove_support", "rod": 0, "support": 3}"#,
            "rods[0].supports[3]",
            "no such support",
        ),
        (
            r#"{"op": "gravity", "gravity": [0, 0, 1e300]}"#,
            "gravity",
            "sensible magnitude",
        ),
        (
            r#"{"op": "length", "rod": 0, "length": -0.5}"#,
            "rods[0].centerline.length",
            "finite and positive",
        ),
        (
            r#"{"op": "length", "rod": 0, "length": 1e6}"#,
            "rods[0].centerline.length",
            "at most ×10",
        ),
        (
            r#"{"op": "length", "rod": 5, "length": 0.7}"#,
            "rods[5]",
            "no such rod",
        ),
        (
            r#"{"op": "length", "rod": 0, "length": NaN}"#,
            "request",
            "NaN",
        ),
        (
            r#"{"op": "obstacle", "obstacle": 0, "translation": [0, 0, 0.01]}"#,
            "obstacles[0]",
            "no such obstacle",
        ),
        (
            r#"{"op": "obstacle", "obstacle": 0, "translation": [0, 1e300, 0]}"#,
            "obstacles[0]",
            "no such obstacle",
        ),
        (
            r#"{"op": "force", "rod": 0, "force": 0, "value": [0, 0, -1]}"#,
            "rods[0].forces[0]",
            "no such force",
        ),
        (
            r#"{"op": "force", "rod": 0, "force": 0, "value": [0, 0, 1e300]}"#,
            "rods[0].forces[0]",
            "no such force",
        ),
        (
            r#"{"op": "unstable_policy", "policy": "maybe"}"#,
            "request",
            "unknown variant",
        ),
        (
            r#"{"op": "move", "shell": 0, "support": 2, "position": [0, 0, 0]}"#,
            "shells[0].clamps[2]",
            "no such clamp",
        ),
        (
            r#"{"op": "move_by", "shell": 4, "support": 0, "translation": [0, 0.01, 0]}"#,
            "shells[4]",
            "no such shell strip",
        ),
        (
            r#"{"op": "move", "rod": 0, "shell": 0, "support": 0, "position": [0, 0, 0]}"#,
            "shell",
            "not both",
        ),
        (
            r#"{"op": "move", "support": 0, "position": [0, 0, 0]}"#,
            "rod",
            "missing",
        ),
        (
            r#"{"op": "move_by", "shell": 0, "support": 1, "translation": [1e6, 0, 0]}"#,
            "shells[0].clamps[1]",
            "too large",
        ),
        (
            r#"{"op": "move_by", "shell": 0, "support": 1, "rotation": [1e300, 0, 0]}"#,
            "shells[0].clamps[1]",
            "must be finite",
        ),
    ];
    for (message, field, words) in cases {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(v["ok"], json!(false), "{message} was accepted: {v}");
        let (f, m) = error_of(&v);
        assert_eq!(&f, field, "{message}: {m}");
        assert!(m.contains(words), "{message}: {m:?} does not say {words:?}");
        assert!(kept, "{message} changed the equilibrium");
    }
}

#[test]
fn valid_edits_change_the_equilibrium_and_errors_after_them_do_not() {
    let mut s = session();
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "move_by", "rod": 0, "support": 2, "translation": [-0.05, 0.05, 0.02]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    let (v, _) = exchange(
        &mut s,
        r#"{"op": "add_support", "rod": 0, "kind": "clip", "at": 0.45}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(
        v["view"]["rods"][0]["supports"].as_array().unwrap().len(),
        4
    );
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "move_by", "rod": 0, "support": 3, "translation": [1e6, 0, 0]}"#,
    );
    assert_eq!(v["ok"], json!(false));
    assert!(kept);
    let (v, _) = exchange(
        &mut s,
        r#"{"op": "remove_support", "rod": 0, "support": 1}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(
        v["view"]["rods"][0]["supports"].as_array().unwrap().len(),
        3
    );
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let text = v["toml"].as_str().expect("save answers TOML");
    let saved: Scene = toml::from_str(text).expect("the saved scene parses");
    assert_eq!(saved.rods[0].supports.len(), 3);
    let (v, _) = exchange(&mut s, r#"{"op": "gltf"}"#);
    assert_eq!(v["gltf"]["asset"]["version"], json!("2.0"));
}

#[test]
fn a_force_message_sets_the_force_and_a_bad_one_keeps_the_equilibrium() {
    let text = SCENE.replace(
        r#"    { kind = "pin", vertex = "end" },
]"#,
        r#"    { kind = "pin", vertex = "end" },
]
forces = [{ vertex = 9, force = [0.0, 0.0, -0.01] }]"#,
    );
    let scene: Scene = toml::from_str(&text).expect("the scene parses");
    let mut s = Session::new(scene).expect("the scene compiles");
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "force", "rod": 0, "force": 0, "value": [0.0, 0.02, -0.05]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(s.spec().rods[0].forces[0].force, [0.0, 0.02, -0.05]);
    // The view lists it as the page draws it: the new value, at vertex 9 where it is now.
    let shown = &v["view"]["rods"][0]["forces"][0];
    assert_eq!(shown["force"], json!([0.0, 0.02, -0.05]), "{v}");
    assert_eq!(shown["vertex"], json!(9));
    assert_eq!(shown["follower"], json!(false));
    assert_eq!(
        shown["now"],
        json!([0.0, 0.02, -0.05]),
        "a dead force does not turn"
    );
    assert_eq!(shown["position"], v["view"]["rods"][0]["positions"][9]);
    for (message, field) in [
        (
            r#"{"op": "force", "rod": 0, "force": 0, "value": [0, 0, 1e300]}"#,
            "rods[0].forces[0].force",
        ),
        (
            r#"{"op": "force", "rod": 0, "force": 2, "value": [0, 0, 1]}"#,
            "rods[0].forces[2]",
        ),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{v}");
        assert!(kept, "{message}");
    }
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.rods[0].forces[0].force, [0.0, 0.02, -0.05]);
}

/// The clipped-cable example (a 100-element cable, three clips, a dead twisting moment of
/// 0.01 N m about x on vertex 35).
fn clipped_cable() -> Session {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/clipped_cable.toml"
    ))
    .expect("the example exists");
    Session::new(toml::from_str(&text).expect("parses")).expect("compiles")
}

#[test]
fn a_moment_message_sets_the_moment_and_a_bad_one_keeps_the_equilibrium() {
    let mut s = clipped_cable();
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "moment", "rod": 0, "moment": 0, "value": [0.02, 0.0, 0.005]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(s.spec().rods[0].moments[0].moment, [0.02, 0.0, 0.005]);
    let shown = &v["view"]["rods"][0]["moments"][0];
    assert_eq!(shown["moment"], json!([0.02, 0.0, 0.005]), "{v}");
    assert_eq!(shown["follower"], json!(false));
    for (message, field) in [
        (
            r#"{"op": "moment", "rod": 0, "moment": 0, "value": [0, 1e300, 0]}"#,
            "rods[0].moments[0].moment",
        ),
        (
            r#"{"op": "moment", "rod": 0, "moment": 1, "value": [0, 0, 1]}"#,
            "rods[0].moments[1]",
        ),
        (
            r#"{"op": "moment", "rod": 4, "moment": 0, "value": [0, 0, 1]}"#,
            "rods[4].moments[0]",
        ),
        (
            r#"{"op": "moment", "rod": 0, "moment": 0, "value": [0, "x", 1]}"#,
            "request",
        ),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{v}");
        assert!(kept, "{message}");
    }
    // A moment added by arc length (at the file's nearest vertex), then removed.
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "add_moment", "rod": 0, "at": 0.25, "value": [0.0, 0.0, 0.01]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(
        v["view"]["rods"][0]["moments"][1]["moment"],
        json!([0.0, 0.0, 0.01]),
        "{v}"
    );
    for (message, field) in [
        (
            r#"{"op": "add_moment", "rod": 0, "at": 7.0}"#,
            "rods[0].moments.at",
        ),
        (
            r#"{"op": "remove_moment", "rod": 0, "moment": 2}"#,
            "rods[0].moments[2]",
        ),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{v}");
        assert!(kept, "{message}");
    }
    let (v, _) = exchange(&mut s, r#"{"op": "remove_moment", "rod": 0, "moment": 1}"#);
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert_eq!(s.spec().rods[0].moments.len(), 1);
    // The saved scene carries the new moment, and its solve gives the session's equilibrium.
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.rods[0].moments[0].moment, [0.02, 0.0, 0.005]);
    let again = Session::new(saved).expect("the saved scene solves");
    let (a, b) = (equilibrium(&s).0, equilibrium(&again).0);
    let d = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    assert!(d <= 1e-9, "{d:e} m between the session and its saved scene");
}

#[test]
fn a_follower_force_message_sets_the_force_at_rest_and_the_view_turns_it() {
    // The follower cantilever example (EI = 1 N m², tip follower +y at rest): its force is
    // edited like a dead one, and the view draws it as it acts now, normal to the tip.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/follower_cantilever.toml"
    ))
    .expect("the example exists");
    let scene: Scene = toml::from_str(&text).expect("the scene parses");
    let mut s = Session::new(scene).expect("the scene compiles");
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "force", "rod": 0, "force": 0, "value": [0.0, 3.0, 0.0]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    let rod = &v["view"]["rods"][0];
    let shown = &rod["forces"][0];
    assert_eq!(shown["force"], json!([0.0, 3.0, 0.0]), "{v}");
    assert_eq!(shown["follower"], json!(true));
    let vec = |x: &Value| -> Vec<f64> {
        x.as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_f64().unwrap())
            .collect()
    };
    let now = vec(&shown["now"]);
    let n = rod["positions"].as_array().unwrap().len();
    let (a, b) = (vec(&rod["positions"][n - 2]), vec(&rod["positions"][n - 1]));
    let tip: Vec<f64> = (0..3).map(|k| b[k] - a[k]).collect();
    let dot: f64 = (0..3).map(|k| now[k] * tip[k]).sum();
    let size = now.iter().map(|x| x * x).sum::<f64>().sqrt();
    let tip_len = tip.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((size - 3.0).abs() <= 1e-12, "|now| = {size} N");
    assert!(
        dot.abs() <= 1e-9 * size * tip_len,
        "now {now:?}, tip {tip:?}"
    );
    assert!(now[0] < -1.0, "turned with the tip: {now:?}");
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.rods[0].forces[0].force, [0.0, 3.0, 0.0]);
    assert!(saved.rods[0].forces[0].follower);
}

/// Sends `message` through `history`; the reply as JSON.
fn through(h: &mut History, s: &mut Session, message: &str) -> Value {
    serde_json::from_str(&h.handle(s, message)).expect("the reply is JSON")
}

/// The text of the first rod's `positions` in a reply, as sent: the page compares these
/// numbers, and a lossy parse could map two different texts to one float.
fn positions_text(reply: &str) -> String {
    let start = reply.find("\"positions\":").expect("a rod's positions");
    let end = start + reply[start..].find("]]").expect("the end of the positions") + 2;
    reply[start..end].to_string()
}

#[test]
fn undo_and_redo_give_back_the_equilibria_exactly() {
    let (mut s, mut h) = (session(), History::default());
    let e0 = equilibrium(&s);
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "add_support", "rod": 0, "kind": "clip", "at": 0.2}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    let e1 = equilibrium(&s);
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "gravity", "gravity": [0.0, 0.0, -5.0]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    let e2 = equilibrium(&s);
    // An edit that does not converge keeps the equilibrium and is no step either.
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "gravity", "gravity": [0.0, 2.0, -5.0]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(false), "{v}");
    assert_eq!(equilibrium(&s), e2);
    // A refused edit is no step.
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "gravity", "gravity": [0.0, 0.0, 1e300]}"#,
    );
    assert_eq!(v["ok"], json!(false), "{v}");
    let v = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(
        (v["ok"].clone(), v["op"].clone()),
        (json!(true), json!("undo")),
        "{v}"
    );
    assert_eq!(v["history"], json!({"undo": 1, "redo": 1}));
    assert!(v["view"]["rods"].is_array(), "the reply carries the view");
    assert_eq!(equilibrium(&s), e1, "one step back: bit for bit");
    through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(equilibrium(&s), e0);
    assert_eq!(s.spec().rods[0].supports.len(), 3);
    let v = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(error_of(&v), ("undo".into(), "nothing to undo".into()));
    assert_eq!(equilibrium(&s), e0);
    through(&mut h, &mut s, r#"{"op": "redo"}"#);
    assert_eq!(equilibrium(&s), e1);
    let v = through(&mut h, &mut s, r#"{"op": "redo"}"#);
    assert_eq!(equilibrium(&s), e2);
    assert_eq!(s.spec().gravity, [0.0, 0.0, -5.0]);
    assert_eq!(v["history"], json!({"undo": 2, "redo": 0}));
    let v = through(&mut h, &mut s, r#"{"op": "redo"}"#);
    assert_eq!(error_of(&v).0, "redo");
    // A new edit after an undo drops the steps forward.
    through(&mut h, &mut s, r#"{"op": "undo"}"#);
    through(
        &mut h,
        &mut s,
        r#"{"op": "gravity", "gravity": [0.0, 0.0, -7.0]}"#,
    );
    let v = through(&mut h, &mut s, r#"{"op": "redo"}"#);
    assert_eq!(error_of(&v).0, "redo", "{v}");
}

#[test]
fn a_drag_after_a_checkpoint_is_undone_in_one_step() {
    let (mut s, mut h) = (session(), History::default());
    let before = equilibrium(&s);
    let shown = positions_text(&h.handle(&mut s, r#"{"op": "state"}"#));
    let v = through(&mut h, &mut s, r#"{"op": "checkpoint"}"#);
    assert_eq!(v["history"], json!({"undo": 1, "redo": 0}), "{v}");
    for y in [0.01, 0.02, 0.03] {
        let v = through(
            &mut h,
            &mut s,
            &format!(r#"{{"op": "move", "rod": 0, "support": 2, "position": [0.6, {y}, 0.0]}}"#),
        );
        assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    }
    assert_ne!(equilibrium(&s), before);
    let undone = h.handle(&mut s, r#"{"op": "undo"}"#);
    assert_eq!(equilibrium(&s), before);
    // The page gets the very numbers it showed before the drag.
    assert_eq!(positions_text(&undone), shown);
    // The history is bounded.
    for _ in 0..MAX_UNDO + 5 {
        through(&mut h, &mut s, r#"{"op": "checkpoint"}"#);
    }
    let v = through(&mut h, &mut s, r#"{"op": "checkpoint"}"#);
    assert_eq!(v["history"]["undo"], json!(MAX_UNDO));
}

#[test]
fn a_typed_pose_is_one_step_of_undo_and_ends_where_the_same_move_ends() {
    // `place` is `move` to an absolute pose, undone by itself (no checkpoint needed).
    let mut h = History::default();
    let mut s = session();
    let before = equilibrium(&s);
    let message = r#"{"op": "place", "rod": 0, "support": 2, "position": [0.58, 0.03, 0.02]}"#;
    let v = through(&mut h, &mut s, message);
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert_eq!(v["op"], json!("place"));
    let mut moved = session();
    let (w, _) = exchange(&mut moved, &message.replace("place", "move"));
    assert_eq!(w["edit"]["converged"], json!(true), "{w}");
    assert_eq!(equilibrium(&s), equilibrium(&moved), "place = move");
    let v = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(v["history"]["undo"], json!(0), "{v}");
    assert_eq!(equilibrium(&s), before, "one undo takes it back");
    // A pin has no orientation: refused by name, no step.
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "place", "rod": 0, "support": 2, "position": [0.6, 0.0, 0.0], "rotation": [0.0, 0.0, 0.3]}"#,
    );
    assert_eq!(error_of(&v).0, "rods[0].supports[2].rotation", "{v}");
    assert_eq!(equilibrium(&s), before);
    let v = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(v["ok"], json!(false), "a refused place is no step: {v}");
}

#[test]
fn add_force_and_remove_force_messages_edit_the_rods_forces() {
    let mut s = session();
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "add_force", "rod": 0, "at": 0.46, "value": [0.0, 0.01, -0.02]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    // 0.46 m on a 0.6 m cable of 12 elements: vertex 9 (0.45 m).
    let shown = &v["view"]["rods"][0]["forces"][0];
    assert_eq!(shown["vertex"], json!(9), "{v}");
    assert_eq!(shown["force"], json!([0.0, 0.01, -0.02]));
    for (message, field) in [
        (
            r#"{"op": "add_force", "rod": 0, "at": 0.9}"#,
            "rods[0].forces.at",
        ),
        (r#"{"op": "add_force", "rod": 5, "at": 0.1}"#, "rods[5]"),
        (
            r#"{"op": "add_force", "rod": 0, "at": 0.1, "value": [0, 1e300, 0]}"#,
            "rods[0].forces[1].force",
        ),
        (
            r#"{"op": "remove_force", "rod": 0, "force": 1}"#,
            "rods[0].forces[1]",
        ),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{v}");
        assert!(kept, "{message}");
    }
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.rods[0].forces[0].force, [0.0, 0.01, -0.02]);
    let (v, kept) = exchange(&mut s, r#"{"op": "remove_force", "rod": 0, "force": 0}"#);
    assert_eq!(v["ok"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(v["view"]["rods"][0]["forces"], json!([]));
    // Back to the equilibrium of the scene without the force.
    let (a, b) = (equilibrium(&s).0, equilibrium(&session()).0);
    let worst = a[0]
        .iter()
        .zip(&b[0])
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(worst <= 1e-9, "{worst:e} m");
}

#[test]
fn a_shell_force_message_sets_the_strips_force_and_a_bad_one_keeps_the_equilibrium() {
    let text = SCENE.replace(
        r#"clamps = [{ edge = "start" }, { edge = "end", offset = [-0.01, 0.0, 0.0] }]"#,
        r#"clamps = [{ edge = "start" }, { edge = "end", offset = [-0.01, 0.0, 0.0] }]
forces = [{ station = 2, column = 1, force = [0.0, -0.01, 0.0] }]"#,
    );
    let mut s = Session::new(toml::from_str(&text).unwrap()).unwrap();
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "force", "shell": 0, "force": 0, "value": [0.0, -0.05, 0.01]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(s.spec().shells[0].forces[0].force, [0.0, -0.05, 0.01]);
    // The view lists it where the page draws it: station 2, column 1 of a 4 × 1 grid is
    // vertex 2·2 + 1.
    let shown = &v["view"]["shells"][0]["forces"][0];
    assert_eq!(shown["force"], json!([0.0, -0.05, 0.01]), "{v}");
    assert_eq!(shown["vertex"], json!(5));
    assert_eq!(shown["position"], v["view"]["shells"][0]["positions"][5]);
    for (message, field) in [
        (
            r#"{"op": "force", "shell": 0, "force": 0, "value": [0, 1e300, 0]}"#,
            "shells[0].forces[0].force",
        ),
        (
            r#"{"op": "force", "shell": 0, "force": 1, "value": [0, 0, 1]}"#,
            "shells[0].forces[1]",
        ),
        (
            r#"{"op": "force", "shell": 3, "force": 0, "value": [0, 0, 1]}"#,
            "shells[3].forces[0]",
        ),
        (
            r#"{"op": "force", "rod": 0, "shell": 0, "force": 0, "value": [0, 0, 1]}"#,
            "shell",
        ),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{v}");
        assert!(kept, "{message}");
    }
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.shells[0].forces[0].force, [0.0, -0.05, 0.01]);
}

#[test]
fn add_force_and_remove_force_messages_edit_the_strips_forces() {
    // The strip clamped at its rest length (the test scene's pushes it in by 1 cm: a flat
    // strip under compression, which a lateral force snaps to a buckled shape that stays).
    let flat = SCENE.replace("offset = [-0.01, 0.0, 0.0]", "offset = [0.0, 0.0, 0.0]");
    let mut s = Session::new(toml::from_str(&flat).unwrap()).unwrap();
    let strip = |s: &Session| s.results(0, None, 1.0, 1).shells[0].positions.clone();
    let rest = strip(&s);
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "add_force", "shell": 0, "station": 2, "column": 1, "value": [0.0, -0.05, 0.0]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    // Station 2, column 1 of the 4 × 1 grid: vertex 2·2 + 1, drawn where the strip is now.
    let shown = &v["view"]["shells"][0]["forces"][0];
    assert_eq!(shown["vertex"], json!(5), "{v}");
    assert_eq!(shown["force"], json!([0.0, -0.05, 0.0]));
    assert_eq!(shown["position"], v["view"]["shells"][0]["positions"][5]);
    // The scene with that force, solved cold: the same equilibrium.
    let with = flat.replace(
        r#"clamps = [{ edge = "start" }, { edge = "end", offset = [0.0, 0.0, 0.0] }]"#,
        r#"clamps = [{ edge = "start" }, { edge = "end", offset = [0.0, 0.0, 0.0] }]
forces = [{ station = 2, column = 1, force = [0.0, -0.05, 0.0] }]"#,
    );
    let cold = Session::new(toml::from_str(&with).unwrap()).unwrap();
    let gap = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max)
    };
    let moved = gap(&strip(&s), &rest);
    assert!(moved > 1e-4, "the force moved the strip by {moved:e} m");
    assert!(
        gap(&strip(&s), &strip(&cold)) <= 1e-12,
        "{:e} m",
        gap(&strip(&s), &strip(&cold))
    );
    for (message, field) in [
        (
            r#"{"op": "add_force", "shell": 0, "station": 5, "column": 0}"#,
            "shells[0].forces[1].station",
        ),
        (
            r#"{"op": "add_force", "shell": 0, "station": 1, "column": 2}"#,
            "shells[0].forces[1].column",
        ),
        (r#"{"op": "add_force", "shell": 0, "station": 1}"#, "column"),
        (r#"{"op": "add_force", "shell": 0, "at": 0.1}"#, "station"),
        (
            r#"{"op": "add_force", "rod": 0, "station": 1, "column": 0}"#,
            "at",
        ),
        (
            r#"{"op": "add_force", "shell": 2, "station": 1, "column": 0}"#,
            "shells[2]",
        ),
        (
            r#"{"op": "add_force", "shell": 0, "station": 1, "column": 0, "value": [0, 1e300, 0]}"#,
            "shells[0].forces[1].force",
        ),
        (
            r#"{"op": "remove_force", "shell": 0, "force": 1}"#,
            "shells[0].forces[1]",
        ),
        (r#"{"op": "remove_force", "force": 0}"#, "rod"),
    ] {
        let (v, kept) = exchange(&mut s, message);
        assert_eq!(error_of(&v).0, field, "{message}: {v}");
        assert!(kept, "{message}");
    }
    let (v, _) = exchange(&mut s, r#"{"op": "save"}"#);
    let saved: Scene = toml::from_str(v["toml"].as_str().unwrap()).unwrap();
    assert_eq!(saved.shells[0].forces.len(), 1);
    assert_eq!(saved.shells[0].forces[0].force, [0.0, -0.05, 0.0]);
    let (v, kept) = exchange(&mut s, r#"{"op": "remove_force", "shell": 0, "force": 0}"#);
    assert_eq!(v["ok"], json!(true), "{v}");
    assert!(!kept);
    assert_eq!(v["view"]["shells"][0]["forces"], json!([]));
    assert!(
        gap(&strip(&s), &rest) <= 1e-12,
        "back to the unloaded strip: {:e} m",
        gap(&strip(&s), &rest)
    );
}

#[test]
fn the_axial_force_of_a_cable_pulled_at_its_end_is_the_pull_in_every_edge() {
    // Weightless, clamped at its start, pulled along its axis by F at its end: equilibrium
    // of any cut gives N = F in every edge, whatever the model (EA·ε with EA = E·πd²/4).
    let pull = 3.0;
    for model in ["der", "cosserat", "se3"] {
        let text = format!(
            r#"
gravity = [0.0, 0.0, 0.0]
[[rods]]
name = "cable"
model = "{model}"
elements = 10
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.5 }}
section = {{ shape = "circle", diameter = 0.002 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}]
forces = [{{ vertex = "end", force = [{pull}, 0.0, 0.0] }}]
"#
        );
        let mut s = Session::new(toml::from_str(&text).unwrap()).unwrap();
        let (v, _) = exchange(&mut s, r#"{"op": "state"}"#);
        let axial: Vec<f64> =
            serde_json::from_value(v["view"]["rods"][0]["axial_force"].clone()).unwrap();
        assert_eq!(axial.len(), 10, "{model}: one per edge");
        let worst = axial.iter().map(|n| (n - pull).abs()).fold(0.0, f64::max);
        assert!(worst <= 1e-6 * pull, "{model}: {axial:?}");
    }
}

#[test]
fn every_rod_model_is_dragged_to_the_equilibrium_of_the_equivalent_prescribed_motion() {
    // The drag a page sends for the end pin, and the same move as a motion stage of the scene
    // file (what `slender solve` runs): the same equilibrium, whatever the rod's formulation.
    for model in ["der", "cosserat", "cosserat_tan", "se3"] {
        let text = SCENE.replace(
            "name = \"cable\"",
            &format!("name = \"cable\"\nmodel = \"{model}\""),
        );
        let mut dragged = Session::new(toml::from_str(&text).unwrap()).unwrap();
        let (v, kept) = exchange(
            &mut dragged,
            r#"{"op": "move_by", "rod": 0, "support": 2, "translation": [-0.05, 0.05, 0.02]}"#,
        );
        assert_eq!(v["ok"], json!(true), "{model}: {v}");
        assert_eq!(v["edit"]["converged"], json!(true), "{model}: {v}");
        assert!(!kept);
        assert_eq!(v["view"]["rods"][0]["model"], json!(model));
        let moved =
            format!("{text}\n[[motion]]\nrod = 0\nsupport = 2\ntranslate = [-0.05, 0.05, 0.02]\n");
        let mut solved = Session::new(toml::from_str(&moved).unwrap()).unwrap();
        assert!(solved.run_motion_step(1).converged);
        let (a, b) = (equilibrium(&dragged).0, equilibrium(&solved).0);
        let tip = |x: &Vec<Vec<[f64; 3]>>| *x[0].last().unwrap();
        let (ta, tb) = (tip(&a), tip(&b));
        for k in 0..3 {
            assert!(
                (ta[k] - tb[k]).abs() <= 1e-9 * 0.6,
                "{model}: {ta:?} vs {tb:?}"
            );
        }
    }
}

/// A number a hostile client might send: ordinary, huge, tiny, negative, or not a number.
fn hostile_number() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => (-1.0f64..1.0).prop_map(|x| format!("{x}")),
        1 => (-1e6f64..1e6).prop_map(|x| format!("{x}")),
        1 => Just("1e308".to_string()),
        1 => Just("-1e308".to_string()),
        1 => Just("1e999".to_string()),
        1 => Just("NaN".to_string()),
        1 => Just("\"0.1\"".to_string()),
        1 => Just("null".to_string()),
        1 => Just("5e-324".to_string()),
    ]
}

fn index() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (0usize..5).prop_map(|i| i.to_string()),
        1 => Just("-1".to_string()),
        1 => Just("18446744073709551616".to_string()),
        1 => Just("1.5".to_string()),
    ]
}

fn vec3() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => [hostile_number(), hostile_number(), hostile_number()]
            .prop_map(|[a, b, c]| format!("[{a}, {b}, {c}]")),
        1 => Just("[0, 0]".to_string()),
        1 => Just("[]".to_string()),
    ]
}

/// Requests that parse as JSON objects, with an `op` and hostile or random values.
fn request() -> impl Strategy<Value = String> {
    let kind = prop_oneof![
        Just("clip"),
        Just("pin"),
        Just("slider"),
        Just("twist_hold"),
        Just("clamp"),
        Just("hook")
    ];
    prop_oneof![
        (index(), index(), vec3(), proptest::option::of(vec3())).prop_map(|(r, s, p, q)| match q {
            Some(q) => format!(r#"{{"op": "move", "rod": {r}, "support": {s}, "position": {p}, "rotation": {q}}}"#),
            None => format!(r#"{{"op": "move", "rod": {r}, "support": {s}, "position": {p}}}"#),
        }),
        (index(), index(), vec3(), vec3()).prop_map(|(r, s, t, q)| format!(
            r#"{{"op": "move_by", "rod": {r}, "support": {s}, "translation": {t}, "rotation": {q}}}"#
        )),
        (index(), index(), vec3(), proptest::option::of(vec3())).prop_map(|(r, s, p, q)| match q {
            Some(q) => format!(r#"{{"op": "place", "rod": {r}, "support": {s}, "position": {p}, "rotation": {q}}}"#),
            None => format!(r#"{{"op": "place", "shell": {r}, "support": {s}, "position": {p}}}"#),
        }),
        (index(), index(), vec3(), proptest::option::of(vec3())).prop_map(|(r, s, p, q)| match q {
            Some(q) => format!(r#"{{"op": "move", "shell": {r}, "support": {s}, "position": {p}, "rotation": {q}}}"#),
            None => format!(r#"{{"op": "move", "shell": {r}, "support": {s}, "position": {p}}}"#),
        }),
        (index(), index(), vec3(), vec3()).prop_map(|(r, s, t, q)| format!(
            r#"{{"op": "move_by", "shell": {r}, "support": {s}, "translation": {t}, "rotation": {q}}}"#
        )),
        (index(), kind, hostile_number()).prop_map(|(r, k, a)| format!(
            r#"{{"op": "add_support", "rod": {r}, "kind": "{k}", "at": {a}}}"#
        )),
        (index(), index()).prop_map(|(r, s)| format!(r#"{{"op": "remove_support", "rod": {r}, "support": {s}}}"#)),
        vec3().prop_map(|g| format!(r#"{{"op": "gravity", "gravity": {g}}}"#)),
        (index(), hostile_number()).prop_map(|(r, l)| format!(
            r#"{{"op": "length", "rod": {r}, "length": {l}}}"#
        )),
        (index(), vec3(), vec3()).prop_map(|(o, t, q)| format!(
            r#"{{"op": "obstacle", "obstacle": {o}, "translation": {t}, "rotation": {q}}}"#
        )),
        (index(), index(), vec3()).prop_map(|(r, f, v)| format!(
            r#"{{"op": "force", "rod": {r}, "force": {f}, "value": {v}}}"#
        )),
        (index(), index(), vec3()).prop_map(|(r, f, v)| format!(
            r#"{{"op": "force", "shell": {r}, "force": {f}, "value": {v}}}"#
        )),
        (index(), index(), vec3()).prop_map(|(r, m, v)| format!(
            r#"{{"op": "moment", "rod": {r}, "moment": {m}, "value": {v}}}"#
        )),
        (index(), hostile_number(), vec3()).prop_map(|(r, a, v)| format!(
            r#"{{"op": "add_moment", "rod": {r}, "at": {a}, "value": {v}}}"#
        )),
        (index(), index()).prop_map(|(r, m)| format!(
            r#"{{"op": "remove_moment", "rod": {r}, "moment": {m}}}"#
        )),
        (index(), hostile_number(), vec3()).prop_map(|(r, a, v)| format!(
            r#"{{"op": "add_force", "rod": {r}, "at": {a}, "value": {v}}}"#
        )),
        (index(), index()).prop_map(|(r, f)| format!(
            r#"{{"op": "remove_force", "rod": {r}, "force": {f}}}"#
        )),
        (index(), index(), index(), vec3()).prop_map(|(s, i, j, v)| format!(
            r#"{{"op": "add_force", "shell": {s}, "station": {i}, "column": {j}, "value": {v}}}"#
        )),
        (index(), index()).prop_map(|(s, f)| format!(
            r#"{{"op": "remove_force", "shell": {s}, "force": {f}}}"#
        )),
        Just(r#"{"op": "follow_stable"}"#.to_string()),
        Just(r#"{"op": "unstable_policy", "policy": "keep"}"#.to_string()),
        Just(r#"{"op": "state"}"#.to_string()),
        Just(r#"{"op": "save"}"#.to_string()),
    ]
}

/// Runs `cases` random messages from `strategy` against one session, in sequence.
fn fuzz(strategy: impl Strategy<Value = String>, cases: u32) {
    fuzz_session(session(), strategy, cases, |_| Ok(()));
}

/// Runs `cases` random messages from `strategy` against `session`, in sequence; `check` is
/// asked about every reply besides the common checks.
fn fuzz_session(
    session: Session,
    strategy: impl Strategy<Value = String>,
    cases: u32,
    check: impl Fn(&Value) -> Result<(), TestCaseError>,
) {
    let s = RefCell::new(session);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&strategy, |message| {
            let mut s = s.borrow_mut();
            let (v, kept) = exchange(&mut s, &message);
            let refused = v["ok"] == json!(false);
            let not_converged = v["edit"]["converged"] == json!(false);
            prop_assert!(
                !(refused || not_converged) || kept,
                "{message}: refused or not converged, yet the equilibrium changed: {v}"
            );
            check(&v)
        })
        .unwrap();
}

#[test]
fn fuzz_arbitrary_text() {
    fuzz(
        prop_oneof![
            any::<String>(),
            "\\PC{0,200}",
            "[{}\\[\\]\":,a-z0-9.eE+-]{0,80}"
        ],
        400,
    );
}

#[test]
fn fuzz_requests_with_hostile_values() {
    fuzz(request(), 300);
}

#[test]
fn fuzz_follower_scene_requests() {
    // The follower example: force edits (and removals) of a follower load go through its own
    // load path; an edit refused or not converged keeps the equilibrium there too.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/follower_cantilever.toml"
    ))
    .expect("the example exists");
    let session = Session::new(toml::from_str(&text).expect("parses")).expect("compiles");
    // Half of the messages edit the follower itself (rod 0, force 0) with random values.
    let follower_edit =
        vec3().prop_map(|v| format!(r#"{{"op": "force", "rod": 0, "force": 0, "value": {v}}}"#));
    fuzz_session(
        session,
        prop_oneof![1 => request(), 1 => follower_edit],
        64,
        |_| Ok(()),
    );
}

#[test]
fn a_follower_moment_is_shown_as_it_acts_now() {
    // A twisting follower moment (about the cable's axis at rest) at the tip of a cantilever
    // bent down by its weight: as it acts now it lies along the tip's tangent, with its size.
    let text = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cantilever"
elements = 30
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.006 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [{ kind = "clamp", vertex = "start" }]
moments = [{ vertex = 29, moment = [0.004, 0.0, 0.0], follower = true }]
"#;
    let mut s = Session::new(toml::from_str(text).expect("parses")).expect("compiles");
    let (v, _) = exchange(
        &mut s,
        r#"{"op": "moment", "rod": 0, "moment": 0, "value": [0.008, 0.0, 0.0]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    let rod = &v["view"]["rods"][0];
    let shown = &rod["moments"][0];
    assert_eq!(shown["moment"], json!([0.008, 0.0, 0.0]));
    assert_eq!(shown["follower"], json!(true));
    let vec = |x: &Value| -> [f64; 3] { serde_json::from_value(x.clone()).unwrap() };
    let now = vec(&shown["now"]);
    let (a, b) = (vec(&rod["positions"][29]), vec(&rod["positions"][30]));
    let e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (ne, nm) = (
        e.iter().map(|x| x * x).sum::<f64>().sqrt(),
        now.iter().map(|x| x * x).sum::<f64>().sqrt(),
    );
    let cross = [
        now[1] * e[2] - now[2] * e[1],
        now[2] * e[0] - now[0] * e[2],
        now[0] * e[1] - now[1] * e[0],
    ];
    let sine = cross.iter().map(|x| x * x).sum::<f64>().sqrt() / (nm * ne);
    assert!(e[2] / ne < -0.3, "the tip hangs down: {e:?}");
    assert!(
        (nm - 0.008).abs() <= 1e-15 && sine <= 1e-9,
        "now {now:?}, tip tangent {e:?}"
    );
}

#[test]
fn moment_edits_are_undone_one_by_one() {
    // Set, add and remove are each one step of undo, and each undo gives back the equilibrium
    // before it bit for bit.
    let (mut s, mut h) = (clipped_cable(), History::default());
    let e0 = equilibrium(&s);
    for message in [
        r#"{"op": "moment", "rod": 0, "moment": 0, "value": [0.0, 0.01, 0.0]}"#,
        r#"{"op": "add_moment", "rod": 0, "at": 0.5, "value": [0.005, 0.0, 0.0]}"#,
        r#"{"op": "remove_moment", "rod": 0, "moment": 0}"#,
    ] {
        let v = through(&mut h, &mut s, message);
        assert_eq!(v["edit"]["converged"], json!(true), "{message}: {v}");
    }
    assert_eq!(s.spec().rods[0].moments.len(), 1);
    assert_eq!(s.spec().rods[0].moments[0].moment, [0.005, 0.0, 0.0]);
    for moments in [2, 1] {
        let v = through(&mut h, &mut s, r#"{"op": "undo"}"#);
        assert_eq!(v["ok"], json!(true), "{v}");
        assert_eq!(s.spec().rods[0].moments.len(), moments);
    }
    through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(s.spec().rods[0].moments[0].moment, [0.01, 0.0, 0.0]);
    assert_eq!(
        equilibrium(&s),
        e0,
        "three undos: the example's equilibrium, bit for bit"
    );
}

#[test]
fn fuzz_moment_edits_of_the_clipped_cable() {
    // Half of the messages edit the example's dead moment (each a warm solve of the
    // 100-element cable along the moment's load path): mostly to values within ±0.05 N m in
    // any direction, else to random, often hostile ones.
    let plausible = [-0.05f64..0.05, -0.05f64..0.05, -0.05f64..0.05]
        .prop_map(|[a, b, c]| format!("[{a}, {b}, {c}]"));
    let moment_edit = prop_oneof![2 => plausible, 1 => vec3()]
        .prop_map(|v| format!(r#"{{"op": "moment", "rod": 0, "moment": 0, "value": {v}}}"#));
    fuzz_session(
        clipped_cable(),
        prop_oneof![1 => request(), 1 => moment_edit],
        32,
        |_| Ok(()),
    );
}

#[test]
fn a_strip_clamp_is_dragged_through_the_move_message() {
    let mut s = session();
    let (v, _) = exchange(&mut s, r#"{"op": "state"}"#);
    let clamp = &v["view"]["shells"][0]["clamps"][1];
    assert_eq!(clamp["edge"], json!("end"));
    let p: Vec<f64> = serde_json::from_value(clamp["position"].clone()).unwrap();
    assert!((p[0] - 0.19).abs() < 1e-15 && p[1].abs() < 1e-15, "{p:?}");
    let before = equilibrium(&s);
    let message = format!(
        r#"{{"op": "move", "shell": 0, "support": 1, "position": [{}, 0.01, 0.0], "rotation": [0.0, 0.0, 0.2]}}"#,
        p[0]
    );
    let (v, kept) = exchange(&mut s, &message);
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept, "the strip moved");
    let moved = &v["view"]["shells"][0]["clamps"][1];
    let q: Vec<f64> = serde_json::from_value(moved["position"].clone()).unwrap();
    assert!(
        (q[0] - p[0]).abs() + (q[1] - 0.01).abs() + q[2].abs() < 1e-15,
        "{q:?}"
    );
    let r: Vec<f64> = serde_json::from_value(moved["rotation"].clone()).unwrap();
    assert!((r[2] - 0.2).abs() < 1e-12, "{r:?}");
    // The rods did not move.
    assert_eq!(equilibrium(&s).0[0], before.0[0]);
}

#[test]
fn the_state_reply_draws_every_obstacle_and_every_update_carries_the_contacts() {
    let mut s = contact_session();
    let (v, _) = exchange(&mut s, r#"{"op": "state"}"#);
    let g = &v["geometry"];
    let kinds: Vec<&str> = g["obstacles"]
        .as_array()
        .expect("the state reply carries the obstacles' shapes")
        .iter()
        .map(|o| o["shape"]["kind"].as_str().unwrap())
        .collect();
    assert_eq!(
        kinds,
        ["plane", "box", "sphere", "cylinder", "mesh", "torus"]
    );
    let names: Vec<&str> = g["obstacles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["floor", "block", "obstacle2", "bar", "ramp", "ring"]
    );
    assert_eq!(g["activation"], json!(1e-4));
    assert_eq!(g["self_contact"], json!(false));
    let f = |x: &Value| x.as_f64().unwrap();
    let v3 = |x: &Value| [f(&x[0]), f(&x[1]), f(&x[2])];
    // The extent: the cable at rest (0 … 0.8 m along x), the bounded obstacles (the ramp to
    // y = ±0.12, the ball down to z = −0.045).
    let [lo, hi] = [v3(&g["extent"][0]), v3(&g["extent"][1])];
    assert!(
        (lo[0] - 0.0).abs() < 1e-12 && (hi[0] - 0.85).abs() < 1e-12,
        "{lo:?} {hi:?}"
    );
    assert!(
        (lo[1] + 0.12).abs() < 1e-12 && (lo[2] + 0.045).abs() < 1e-12,
        "{lo:?}"
    );
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    // The floor: a unit normal, a square of 1.5 diagonals centred under the extent's centre.
    let floor = &g["obstacles"][0]["shape"];
    assert_eq!(v3(&floor["normal"]), [0.0, 0.0, 1.0]);
    let c = v3(&floor["center"]);
    assert!((c[0] - 0.425).abs() < 1e-12 && c[2] == 0.0, "{c:?}");
    assert!((f(&floor["size"]) - 1.5 * diagonal).abs() < 1e-12);
    // The bar: a unit axis, centred on the extent along it, its extent plus half a diagonal.
    let bar = &g["obstacles"][3]["shape"];
    assert_eq!(v3(&bar["axis"]), [0.0, 1.0, 0.0]);
    let c = v3(&bar["center"]);
    assert!((c[0] - 0.55).abs() < 1e-12 && c[1].abs() < 1e-12 && (c[2] - 0.025).abs() < 1e-12);
    assert!((f(&bar["length"]) - (0.24 + 0.5 * diagonal)).abs() < 1e-12);
    assert_eq!(
        g["obstacles"][1]["shape"]["rotation"],
        json!([0.0, 0.0, 0.4])
    );
    assert_eq!(
        g["obstacles"][4]["shape"]["triangles"],
        json!([[0, 1, 2], [0, 2, 3]])
    );
    // The ring: its centre and radii as given, a unit axis.
    let ring = &g["obstacles"][5]["shape"];
    assert_eq!(v3(&ring["center"]), [0.7, 0.08, 0.02]);
    assert_eq!(v3(&ring["axis"]), [0.0, 0.0, 1.0]);
    assert_eq!((f(&ring["radius"]), f(&ring["tube_radius"])), (0.03, 0.008));
    assert_eq!(g["obstacles"][2]["friction"], json!(0.2));
    // The contacts: on the ball, the bar and the ramp, each within ĝ of the surface; the
    // resultant of an obstacle is the sum of its contacts' forces.
    let (gap, n) = gap_and_contacts(&v);
    assert!(gap > 0.0 && gap < 1e-4, "min gap {gap}");
    assert!(n >= 3, "{n} contacts");
    for o in v["view"]["obstacles"].as_array().unwrap() {
        let mut sum = [0.0; 3];
        for c in o["contacts"].as_array().unwrap() {
            let g = f(&c["gap"]);
            assert!(g > 0.0 && g < 1e-4, "{c}");
            for k in 0..3 {
                sum[k] += f(&c["normal_force"][k]) + f(&c["friction_force"][k]);
            }
        }
        let r = v3(&o["force"]);
        for k in 0..3 {
            assert!((r[k] - sum[k]).abs() <= 1e-12 * (1.0 + r[k].abs()), "{o}");
        }
    }
    assert!(v["view"]["rods"][0]["contact_radius"] == json!(0.002));
    // Updates carry the contacts, not the shapes.
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "move_by", "rod": 0, "support": 0, "translation": [0.0, 0.0, 0.01]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    assert!(!kept);
    assert!(v.get("geometry").is_none(), "only `state` sends the shapes");
    let (gap, n) = gap_and_contacts(&v);
    assert!(gap > 0.0 && n >= 1, "{gap} {n}");
    // Without obstacles: no shapes, no contacts, no gap.
    let (v, _) = exchange(&mut session(), r#"{"op": "state"}"#);
    assert_eq!(v["geometry"]["obstacles"], json!([]));
    assert_eq!(v["geometry"]["activation"], json!(null));
    assert_eq!(v["view"]["obstacles"], json!([]));
    assert_eq!(v["view"]["min_gap"], json!(null));
    assert_eq!(v["view"]["rods"][0]["contact_radius"], json!(null));
}

#[test]
fn a_clamp_dragged_into_the_floor_never_takes_the_cable_through_it() {
    // The clamp 6 cm above the floor, pushed down in 1 cm steps to 4 cm below it: every
    // reply has every gap positive; where the cable cannot follow, the edit does not converge
    // and the last equilibrium (outside) is kept.
    let mut s = contact_session();
    let mut refused_or_kept = 0;
    for _ in 0..10 {
        let (v, kept) = exchange(
            &mut s,
            r#"{"op": "move_by", "rod": 0, "support": 0, "translation": [0.0, 0.0, -0.01]}"#,
        );
        if v["ok"] == json!(false) || v["edit"]["converged"] == json!(false) {
            assert!(kept, "{v}");
            refused_or_kept += 1;
        }
        let (gap, _) = gap_and_contacts(&exchange(&mut s, r#"{"op": "state"}"#).0);
        assert!(gap > 0.0, "min gap {gap} after {v}");
        let z: Vec<f64> = s.results(0, None, 1.0, 1).rods[0]
            .positions
            .iter()
            .map(|p| p[2])
            .collect();
        assert!(
            z.iter().all(|&z| z > 0.0),
            "a vertex under the floor: {z:?}"
        );
    }
    assert!(refused_or_kept > 0, "the clamp went through the floor");
}

#[test]
fn an_added_force_that_does_not_converge_in_contact_keeps_the_equilibrium_exactly() {
    // Found by the fuzzer: the force is added at zero by a rebuild, which re-solves the
    // structure from its current shape (in contact, within the solver's tolerance of it); the
    // session goes back to the state before the rebuild, not to the rebuild's.
    let mut s = contact_session();
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "add_force", "rod": 0, "at": 0.4467115250814828, "value": [-0.34941269970820565, -724665.1192312094, -0.1297261822395854]}"#,
    );
    assert_eq!(v["edit"]["converged"], json!(false), "{v}");
    assert!(kept, "{v}");
    assert_eq!(v["view"]["rods"][0]["forces"], json!([]));
}

#[test]
fn fuzz_contact_scene_requests() {
    fuzz_session(contact_session(), request(), 60, |v| {
        if v["ok"] == json!(true) {
            let (gap, _) = gap_and_contacts(v);
            prop_assert!(gap > 0.0, "min gap {gap}: {v}");
        }
        Ok(())
    });
}

#[test]
fn fuzz_flat_cable_on_the_bracket_requests() {
    // A strip in contact: obstacle moves carry it along and re-solve it, and an edit refused
    // or not converged keeps its equilibrium (and the obstacles) where they were; every
    // accepted reply keeps every gap open.
    let scene: Scene = toml::from_str(include_str!(
        "../../../../examples/flat_cable_on_bracket.toml"
    ))
    .expect("the example parses");
    let session = Session::new(scene).expect("the example compiles");
    fuzz_session(session, request(), 40, |v| {
        if v["ok"] == json!(true) {
            let (gap, _) = gap_and_contacts(v);
            prop_assert!(gap > 0.0, "min gap {gap}: {v}");
        }
        Ok(())
    });
}

#[test]
fn self_contact_pairs_are_forwarded_as_the_results_list_them() {
    // Two cables crossing 8 mm apart, the upper one sagging onto the lower one (the page
    // test's scene). Where the core's results list the touching segment pairs, the view
    // carries them unchanged; where they do not, the view has none either.
    let scene: Scene = toml::from_str(include_str!(
        "../../../../tests/page/scenes/crossing_cables.toml"
    ))
    .expect("the crossing scene parses");
    let mut s = Session::new(scene).expect("the crossing scene compiles");
    let (v, _) = exchange(&mut s, r#"{"op": "state"}"#);
    assert_eq!(v["geometry"]["self_contact"], json!(true));
    assert_eq!(v["geometry"]["obstacles"], json!([]));
    // Through text, as the reply (serde_json's float parsing may differ from the f64 by an ulp).
    let step: Value =
        serde_json::from_str(&serde_json::to_string(&s.results(0, None, 1.0, 1)).unwrap()).unwrap();
    assert_eq!(v["view"]["segment_contacts"], step["segment_contacts"]);
    assert_eq!(v["view"]["min_segment_gap"], step["min_segment_gap"]);
    if let Some(pairs) = step["segment_contacts"].as_array() {
        assert!(!pairs.is_empty(), "the cables touch: {step}");
    }
    // Without self-contact nothing is forwarded.
    let (v, _) = exchange(&mut contact_session(), r#"{"op": "state"}"#);
    assert!(v["view"].get("segment_contacts").is_none());
    assert_eq!(v["geometry"]["self_contact"], json!(false));
}

#[test]
fn an_obstacle_message_moves_the_obstacle_and_undo_puts_it_back() {
    // The contact scene's round bar (obstacle 3) lifted 5 mm under the cable: the reply
    // carries the moved bar, its cable equilibrium is the session's, and undo restores both
    // to the bit.
    let mut s = contact_session();
    let mut h = History::default();
    let before = through(&mut h, &mut s, r#"{"op": "state"}"#);
    let bar = |v: &Value| v["geometry"]["obstacles"][3]["shape"]["center"].clone();
    let v = through(
        &mut h,
        &mut s,
        r#"{"op": "obstacle", "obstacle": 3, "translation": [0.0, 0.0, 0.005]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    let (b0, b1) = (bar(&before), bar(&v));
    assert!(
        (b1[2].as_f64().unwrap() - b0[2].as_f64().unwrap() - 0.005).abs() < 1e-12,
        "{b0} → {b1}"
    );
    let (gap, _) = gap_and_contacts(&v);
    assert!(gap > 0.0, "{gap}");
    // Saved, the scene keeps the bar where the file has it and moves it by a stage.
    let saved = through(&mut h, &mut s, r#"{"op": "save"}"#);
    let scene: Scene = toml::from_str(saved["toml"].as_str().unwrap()).unwrap();
    assert_eq!(scene.motion.len(), 1);
    assert_eq!(scene.motion[0].obstacle, Some(3));
    let undone = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(bar(&undone), b0);
    assert_eq!(undone["view"], before["view"]);
}

#[test]
fn an_obstacle_dragged_after_a_checkpoint_is_undone_in_one_step() {
    // The page's gizmo drags an obstacle live: a checkpoint, then `drag_obstacle` pieces
    // (each the move from the pose the server has). Without friction (with it the cable's
    // equilibrium depends on the path) they end where one `obstacle` move of the whole way
    // ends, and one undo takes the whole drag back.
    let frictionless = || {
        let text = ["friction = 0.3\n", "friction = 0.2\n", "friction = 0.1\n"]
            .iter()
            .fold(CONTACT_SCENE.to_string(), |t, f| t.replace(f, ""));
        assert!(!text.contains("friction"));
        Session::new(toml::from_str(&text).unwrap()).unwrap()
    };
    let mut s = frictionless();
    let mut h = History::default();
    let before = through(&mut h, &mut s, r#"{"op": "state"}"#);
    let v = through(&mut h, &mut s, r#"{"op": "checkpoint"}"#);
    assert_eq!(v["history"], json!({"undo": 1, "redo": 0}), "{v}");
    for _ in 0..5 {
        let v = through(
            &mut h,
            &mut s,
            r#"{"op": "drag_obstacle", "obstacle": 3, "translation": [0.0, 0.0, 0.001]}"#,
        );
        assert_eq!(v["edit"]["converged"], json!(true), "{v}");
        assert_eq!(v["op"], json!("obstacle"), "{v}");
    }
    let mut whole = frictionless();
    let (w, _) = exchange(
        &mut whole,
        r#"{"op": "obstacle", "obstacle": 3, "translation": [0.0, 0.0, 0.005]}"#,
    );
    assert_eq!(w["edit"]["converged"], json!(true), "{w}");
    let bar = |v: &Value| {
        v["geometry"]["obstacles"][3]["shape"]["center"][2]
            .as_f64()
            .unwrap()
    };
    let dragged = through(&mut h, &mut s, r#"{"op": "state"}"#);
    assert!(
        (bar(&dragged) - bar(&w)).abs() < 1e-15,
        "{} vs {}",
        bar(&dragged),
        bar(&w)
    );
    let (a, b) = (equilibrium(&s).0, equilibrium(&whole).0);
    let worst = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    println!("five drag pieces end {worst:e} m from one move of the whole way");
    assert!(worst < 1e-9, "five pieces end {worst:e} m from one move");
    let undone = through(&mut h, &mut s, r#"{"op": "undo"}"#);
    assert_eq!(undone["history"], json!({"undo": 0, "redo": 1}), "{undone}");
    assert_eq!(undone["view"], before["view"]);
    assert_eq!(bar(&undone), bar(&before));
}

#[test]
fn an_obstacle_turned_about_a_pivot_moves_its_reference_point_with_the_turn() {
    // The page's gizmo turns an obstacle about the centre of its drawn shape: the contact
    // scene's ring (obstacle 5, centre (0.7, 0.08, 0.02), axis z) turned by 0.2 rad about z
    // through a pivot 5 cm off its centre swings its centre about the pivot:
    // c' = q + R (c − q), in closed form (0.7 + 0.05 sin 0.2, 0.13 − 0.05 cos 0.2, 0.02).
    let mut s = contact_session();
    let (v, _) = exchange(
        &mut s,
        r#"{"op": "obstacle", "obstacle": 5, "rotation": [0.0, 0.0, 0.2], "pivot": [0.7, 0.13, 0.02]}"#,
    );
    assert_eq!(v["ok"], json!(true), "{v}");
    assert_eq!(v["edit"]["converged"], json!(true), "{v}");
    let ring = &v["geometry"]["obstacles"][5]["shape"];
    let centre: Vec<f64> = (0..3)
        .map(|i| ring["center"][i].as_f64().unwrap())
        .collect();
    let expected = [0.7 + 0.05 * 0.2f64.sin(), 0.13 - 0.05 * 0.2f64.cos(), 0.02];
    let off = (0..3)
        .map(|i| (centre[i] - expected[i]).abs())
        .fold(0.0, f64::max);
    assert!(off < 1e-15, "{centre:?} vs {expected:?}");
    // A turn about z keeps the ring's axis.
    assert_eq!(ring["axis"][2].as_f64().unwrap().abs(), 1.0, "{ring}");
    // A pivot that is not finite is refused by name.
    let (v, kept) = exchange(
        &mut s,
        r#"{"op": "obstacle", "obstacle": 5, "rotation": [0.0, 0.0, 0.2], "pivot": [0.7, 1e999, 0.02]}"#,
    );
    assert!(kept);
    assert_eq!(v["ok"], json!(false), "{v}");
}
