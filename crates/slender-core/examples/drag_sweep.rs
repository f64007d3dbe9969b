//! A robustness sweep of interactive edits: every rod model dragged through the moves a
//! harness engineer makes (a soft hose circled, a heavy cable given slack, an end twisted by
//! two turns, a U-turn, ends pushed together into a loop, clips dragged, a thin steel wire
//! circled, a cable resting on a bracket and a floor), flat cables dragged and twisted, and
//! cables paid out and pulled in. Prints per case the moves that failed or ended unstable, the
//! worst relative residual, the largest Newton iteration count and the wall time (with
//! `VERBOSE` set, each edit's iterations and load steps, and why a failed edit failed).
//!
//! `cargo run --release -p slender-core --example drag_sweep [FILTER]` (FILTER: a substring of
//! the case names, e.g. `se3` or `shell`).

use std::f64::consts::PI;
use std::time::Instant;

use slender_core::geometry::Vec3;
use slender_core::scene::{EditReport, Scene, SceneError, Session};

/// One rod clamped at both ends along x: model, elements, length (m), diameter (m), Young's
/// modulus (Pa), density (kg/m³), extra supports, gravity on or off.
#[allow(clippy::too_many_arguments)]
fn cable(model: &str, n: usize, len: f64, d: f64, e: f64, rho: f64, extra: &str, g: bool) -> Scene {
    let gz = if g { -9.81 } else { 0.0 };
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, {gz}]
[[rods]]
name = "cable"
model = "{model}"
elements = {n}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = {len} }}
section = {{ shape = "circle", diameter = {d} }}
material = {{ young = {e}, poisson = 0.4, density = {rho} }}
supports = [ {{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }}{extra} ]
"#
    ))
    .expect("a valid scene")
}

/// examples/cable_over_bracket.toml (a cable clamped at one end, draped over a round bracket
/// onto a floor) with the rod model `model` and floor friction `mu`, without its motion.
fn cable_on_bracket(model: &str, mu: f64) -> Scene {
    let mut scene: Scene = toml::from_str(
        &include_str!("../../../examples/cable_over_bracket.toml").replace(
            "name = \"cable\"",
            &format!("name = \"cable\"\nmodel = \"{model}\""),
        ),
    )
    .expect("a valid scene");
    scene.motion.clear();
    scene.obstacles[1].friction = mu;
    scene
}

/// A flat cable 0.5 m long clamped at both edges: width (m), thickness (m), Young's modulus.
fn flat_cable(w: f64, t: f64, e: f64) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[shells]]
length = 0.5
width = {w}
thickness = {t}
material = {{ young = {e}, poisson = 0.35, density = 1400.0 }}
elements = 30
grading = {{ kind = "uniform" }}
clamps = [ {{ edge = "start" }}, {{ edge = "end" }} ]
"#
    ))
    .expect("a valid scene")
}

/// A named scene and the moves (rotation vector, translation) of its dragged support.
type Case<'a> = (&'a str, Scene, Vec<(Vec3, Vec3)>);

/// Tallies of one case.
#[derive(Default)]
struct Tally {
    edits: usize,
    failed: usize,
    unstable: usize,
    worst_residual: f64,
    max_iterations: usize,
}

impl Tally {
    fn add(&mut self, r: Result<EditReport, SceneError>) {
        self.edits += 1;
        match r {
            Ok(r) if r.converged => {
                if std::env::var("VERBOSE").is_ok() {
                    println!(
                        "  edit {:2}: {:4} iterations, {:3} load steps, residual {:.1e}",
                        self.edits, r.iterations, r.load_steps, r.relative_residual
                    );
                }
                self.unstable += usize::from(!r.stable);
                self.worst_residual = self.worst_residual.max(r.relative_residual);
                self.max_iterations = self.max_iterations.max(r.iterations);
            }
            Ok(r) => {
                self.failed += 1;
                if std::env::var("VERBOSE").is_ok() {
                    println!("  not converged: {:?}", r.reason);
                }
            }
            Err(e) => {
                self.failed += 1;
                if std::env::var("VERBOSE").is_ok() {
                    println!("  refused: {e}");
                }
            }
        }
    }

    fn print(&self, name: &str, started: Instant) {
        println!(
            "{name:32} {:3} edits {:2} failed {:2} unstable  worst residual {:8.1e}  max iterations {:4}  {:8.1} ms",
            self.edits,
            self.failed,
            self.unstable,
            self.worst_residual,
            self.max_iterations,
            started.elapsed().as_secs_f64() * 1e3
        );
    }
}

/// `n` moves, the k-th by r·(cos, sin)(2πk/n) in the y–z plane (m) plus `dx` (m) along x: the
/// support walks a closed n-gon with sides of length r, drifting by `dx` per move.
fn circle(n: usize, r: f64, dx: f64) -> Vec<(Vec3, Vec3)> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 2.0 * PI / n as f64;
            (Vec3::zeros(), Vec3::new(dx, r * a.cos(), r * a.sin()))
        })
        .collect()
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let z = Vec3::zeros();
    let clips = r#", { kind = "clip", vertex = 30 }, { kind = "clip", vertex = 60 }"#;
    for model in ["der", "cosserat", "cosserat_tan", "se3"] {
        let cases: Vec<Case> = vec![
            (
                "soft hose circled",
                cable(model, 50, 1.0, 0.01, 1e6, 1100.0, "", true),
                circle(12, 0.1, 0.0).repeat(2),
            ),
            (
                "heavy cable given slack",
                cable(model, 60, 3.0, 0.02, 1e8, 3000.0, "", true),
                vec![(z, Vec3::new(-0.2, 0.0, 0.0)); 10],
            ),
            (
                "end twisted two turns",
                cable(model, 100, 1.0, 0.006, 1e9, 1400.0, "", true),
                vec![(Vec3::new(PI / 6.0, 0.0, 0.0), Vec3::new(-0.01, 0.0, 0.0)); 24],
            ),
            (
                "U-turn",
                cable(model, 100, 1.0, 0.006, 1e9, 1400.0, "", true),
                vec![(Vec3::new(0.0, 0.0, PI / 12.0), Vec3::new(-0.04, 0.02, 0.0)); 12],
            ),
            (
                "ends pushed into a loop",
                cable(model, 100, 1.0, 0.006, 1e9, 1400.0, "", false),
                {
                    let mut v = vec![(z, Vec3::new(0.0, 0.0, 0.001))];
                    v.extend(vec![(z, Vec3::new(-0.1, 0.0, 0.0)); 9]);
                    v
                },
            ),
            (
                "clips, end circled and turned",
                cable(model, 100, 1.0, 0.006, 1e9, 1400.0, clips, true),
                circle(16, 0.05, 0.0)
                    .into_iter()
                    .map(|(_, t)| (Vec3::new(0.0, 0.2, 0.0), t))
                    .collect(),
            ),
            (
                "steel wire circled",
                cable(model, 100, 1.0, 0.002, 2e11, 7800.0, "", true),
                circle(12, 0.03, -0.01),
            ),
        ];
        for (name, scene, moves) in cases {
            let name = format!("{model}: {name}");
            if name.contains(&filter) {
                run(&name, scene, &moves, |s, r, t| {
                    s.move_support_by(0, 1, r, t)
                });
            }
        }
        // The clamp of a cable resting on a bracket and a floor walked round a 1 cm-sided
        // 12-gon in the vertical plane along the cable, pressing it onto its contacts and
        // lifting it off them.
        let vertical_circle: Vec<(Vec3, Vec3)> = circle(12, 0.01, 0.0)
            .into_iter()
            .map(|(r, t)| (r, Vec3::new(t.y, 0.0, t.z)))
            .collect();
        for mu in [0.0, 0.3] {
            let name = format!("{model}: on a bracket and a floor (mu {mu}), clamp circled");
            if name.contains(&filter) {
                run(
                    &name,
                    cable_on_bracket(model, mu),
                    &vertical_circle,
                    |s, r, t| s.move_support_by(0, 0, r, t),
                );
            }
        }
        let name = format!("{model}: cable paid out, pulled in");
        if name.contains(&filter) {
            let started = Instant::now();
            let mut session = Session::new(cable(model, 100, 1.0, 0.006, 1e9, 1400.0, clips, true))
                .expect("the scene solves");
            let mut tally = Tally::default();
            for l in [1.02, 1.1, 1.3, 1.2, 1.0, 0.98] {
                tally.add(session.set_rod_length(0, l));
            }
            tally.print(&name, started);
        }
    }
    let flat: [Case; 4] = [
        (
            "flat cable: end twisted",
            flat_cable(0.02, 5e-4, 2e9),
            vec![(Vec3::new(PI / 12.0, 0.0, 0.0), Vec3::new(-0.01, 0.0, 0.0)); 12],
        ),
        (
            "flat cable: end turned over",
            flat_cable(0.02, 5e-4, 2e9),
            vec![(Vec3::new(0.0, PI / 12.0, 0.0), Vec3::new(-0.04, 0.0, 0.02)); 12],
        ),
        (
            "flat cable: end circled",
            flat_cable(0.03, 3e-4, 3e9),
            circle(12, 0.05, -0.01),
        ),
        (
            "flat cable: end moved in-plane",
            flat_cable(0.03, 3e-4, 3e9),
            vec![(z, Vec3::new(-0.02, 0.0, 0.03)); 10],
        ),
    ];
    for (name, scene, moves) in flat {
        if name.contains(&filter) {
            run(name, scene, &moves, |s, r, t| {
                s.move_shell_clamp_by(0, 1, r, t)
            });
        }
    }
}

/// Solves `scene`, moves its support by each of `moves` with `edit` and prints the tally.
fn run(
    name: &str,
    scene: Scene,
    moves: &[(Vec3, Vec3)],
    mut edit: impl FnMut(&mut Session, Vec3, Vec3) -> Result<EditReport, SceneError>,
) {
    let started = Instant::now();
    let mut session = Session::new(scene).expect("the scene solves");
    let mut tally = Tally::default();
    for &(rotation, translation) in moves {
        tally.add(edit(&mut session, rotation, translation));
    }
    tally.print(name, started);
}
