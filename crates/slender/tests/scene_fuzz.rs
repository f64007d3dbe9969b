//! Property test: random and mutated scene files never make the parser, the validation or the
//! solver panic, and every rejection comes with a message.

// scene_io reads obstacle meshes through its sibling module.
#[path = "../src/solve/mesh_file.rs"]
#[allow(dead_code)]
mod mesh_file;
#[path = "../src/solve/scene_io.rs"]
#[allow(dead_code)]
mod scene_io;

use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;

/// How far fuzzed inputs got: parsed, compiled, solved (printed with --nocapture).
static REACHED: [AtomicUsize; 3] = [
    AtomicUsize::new(0),
    AtomicUsize::new(0),
    AtomicUsize::new(0),
];
use scene_io::{parse_scene, Syntax};
use slender_core::scene::solve::SceneSolver;

fn examples() -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    names
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

/// Replacement tokens for numbers, names and keys: edge cases a user could type.
const TOKENS: &[&str] = &[
    "0",
    "1",
    "-1",
    "2",
    "3",
    "7",
    "19",
    "20",
    "21",
    "40",
    "41",
    "1000000",
    "0.0",
    "-0.0",
    "1e-300",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0.5",
    "-2.5",
    "\"start\"",
    "\"end\"",
    "\"clip\"",
    "\"pin\"",
    "\"clamp\"",
    "\"polyline\"",
    "\"helix\"",
    "\"arc\"",
    "\"stiffness\"",
    "\"rectangle\"",
    "[]",
    "[0.0, 0.0]",
    "[1.0, 0.0, 0.0]",
    "[0.0, 0.0, 0.0]",
    "{}",
    "true",
    "\"x\"",
    "elements",
    "vertex",
    "[[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]",
];

/// One edit of a scene text.
#[derive(Clone, Debug)]
enum Mutation {
    /// Replace the k-th number/word token with a TOKENS entry.
    Token(usize, usize),
    /// Delete line k.
    DeleteLine(usize),
    /// Duplicate line k.
    DuplicateLine(usize),
    /// Insert a byte at position k.
    InsertByte(usize, u8),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..TOKENS.len()).prop_map(|(k, t)| Mutation::Token(k, t)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(k, b)| Mutation::InsertByte(k, b)),
    ]
}

/// Byte ranges of tokens worth replacing: numbers, quoted strings and bare words.
fn tokens(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'#' {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i] == b'"' {
            let s = i;
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += 1;
            }
            i += 1;
            out.push((s, i.min(b.len())));
        } else if b[i].is_ascii_alphanumeric() || b[i] == b'-' || b[i] == b'.' {
            let s = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b"-.+_".contains(&b[i])) {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

fn apply(text: &str, m: &Mutation) -> String {
    match *m {
        Mutation::Token(k, t) => {
            let toks = tokens(text);
            if toks.is_empty() {
                return text.to_string();
            }
            let (s, e) = toks[k % toks.len()];
            format!("{}{}{}", &text[..s], TOKENS[t], &text[e..])
        }
        Mutation::DeleteLine(k) | Mutation::DuplicateLine(k) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return text.to_string();
            }
            let i = k % lines.len();
            if matches!(m, Mutation::DeleteLine(_)) {
                lines.remove(i);
            } else {
                lines.insert(i, lines[i]);
            }
            lines.join("\n")
        }
        Mutation::InsertByte(k, byte) => {
            let mut bytes = text.as_bytes().to_vec();
            let i = k % (bytes.len() + 1);
            bytes.insert(i, byte);
            String::from_utf8_lossy(&bytes).into_owned()
        }
    }
}

/// Parses, validates and (if small enough) solves; panics only on a missing message.
fn exercise(text: &str, syntax: Syntax) {
    // Debugging aid: keep the input under test in a file (a hang leaves it there).
    if let Ok(p) = std::env::var("SCENE_FUZZ_LAST") {
        let t = std::thread::current();
        std::fs::write(format!("{p}.{}", t.name().unwrap_or("main")), text).unwrap();
    }
    let mut scene = match parse_scene(text, syntax, "fuzz") {
        Ok(s) => s,
        Err(e) => {
            let msg = format!("{e:#}");
            assert!(msg.len() > "fuzz: ".len(), "empty parse error");
            return;
        }
    };
    // The fuzz looks for panics, not for convergence: a mutated scene that crawls (a load far
    // too large for its solver settings, over a dozen motion steps and their branch switches,
    // each solve with the default budget of 20000 Newton iterations) could otherwise take many
    // minutes. A smaller budget per solve bounds each case and still reaches every path.
    scene.solver.max_total_iterations = scene
        .solver
        .max_total_iterations
        .min(3000)
        .max(scene.solver.max_iterations);
    REACHED[0].fetch_add(1, Ordering::Relaxed);
    let compiled = match scene.compile() {
        Ok(c) => c,
        Err(e) => {
            assert!(!e.path.is_empty() && !e.message.is_empty(), "{e:?}");
            return;
        }
    };
    REACHED[1].fetch_add(1, Ordering::Relaxed);
    let size: usize = compiled.rods.iter().map(|r| r.n_edges).sum();
    let motion: usize = compiled.motion.iter().map(|m| m.steps).sum();
    // Shell strips are bounded too: a mutated `elements` or aspect ratio can make a strip of
    // thousands of elements, whose solve then takes many minutes (a hang in a fuzz run).
    let shell_vertices: usize = compiled
        .shells
        .iter()
        .map(|s| s.rest_positions().len())
        .sum();
    if size > 500 || motion > 12 || shell_vertices > 300 {
        return;
    }
    REACHED[2].fetch_add(1, Ordering::Relaxed);
    let (mut solver, first) = SceneSolver::new(&scene, &compiled);
    check_step(&first);
    if !first.converged {
        return;
    }
    for k in 1..=solver.motion_steps() {
        let s = solver.run_motion_step(k);
        check_step(&s);
        if !s.converged {
            break;
        }
    }
}

/// A converged step has finite results; a failed one says why.
fn check_step(s: &slender_core::scene::SceneStep) {
    for r in &s.rods {
        for rep in &r.reports {
            match &rep.status {
                slender_core::solver::SolveStatus::Converged => {
                    assert!(r.positions.iter().flatten().all(|c| c.is_finite()));
                }
                slender_core::solver::SolveStatus::NotConverged { reason } => {
                    assert!(!reason.is_empty());
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn mutated_examples_never_panic(
        which in 0usize..16,
        edits in proptest::collection::vec(mutation(), 1..4),
    ) {
        let ex = examples();
        let mut text = ex[which % ex.len()].clone();
        for m in &edits {
            text = apply(&text, m);
        }
        exercise(&text, Syntax::Toml);
        eprintln!("parsed/compiled/solved so far: {:?}", REACHED.iter().map(|a| a.load(Ordering::Relaxed)).collect::<Vec<_>>());
    }

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}") {
        exercise(&text, Syntax::Toml);
        exercise(&text, Syntax::Json);
    }

    #[test]
    fn random_key_value_soup_never_panics(
        lines in proptest::collection::vec(
            (prop::sample::select(vec!["gravity", "rods", "[[rods]]", "name", "elements",
                "centerline", "section", "material", "supports", "motion", "[[motion]]",
                "rod", "support", "steps", "translate", "rotate", "[solver]", "max_iterations",
                "grading", "forces", "moments", "shells"]),
             0..TOKENS.len()),
            0..12),
    ) {
        let text: String = lines
            .iter()
            .map(|(k, t)| if k.starts_with('[') { format!("{k}\n") } else { format!("{k} = {}\n", TOKENS[*t]) })
            .collect();
        exercise(&text, Syntax::Toml);
    }
}

#[test]
fn every_example_parses_and_compiles() {
    for (i, text) in examples().iter().enumerate() {
        let scene = parse_scene(text, Syntax::Toml, "example").unwrap();
        scene
            .compile()
            .unwrap_or_else(|e| panic!("example {i}: {e}"));
    }
}

#[test]
fn the_readme_scene_is_the_u_cable_example() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let start = readme
        .find("```toml\n")
        .expect("a TOML block in the README")
        + 8;
    let block = &readme[start..start + readme[start..].find("```").unwrap()];
    let from_readme = parse_scene(block, Syntax::Toml, "README").unwrap();
    let text = std::fs::read_to_string(root.join("examples/u_cable_moved.toml")).unwrap();
    assert_eq!(
        from_readme,
        parse_scene(&text, Syntax::Toml, "example").unwrap()
    );
}
