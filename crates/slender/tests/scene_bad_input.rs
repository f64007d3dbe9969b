//! Bad scene files: each is rejected with a non-zero exit code, a message that names the place
//! in the file and what is valid, and no output directory left behind.

use std::path::PathBuf;
use std::process::Command;

const GOOD: &str = r#"
gravity = [0.0, 0.0, -9.81]

[[rods]]
name = "cable"
elements = 20
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.005 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [
    { kind = "clamp", vertex = "start" },
    { kind = "pin", vertex = 12 },
]
"#;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slender-bad-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` as `file`, runs `slender solve`, returns (exit code, stderr) and checks that
/// no output was left.
fn run(name: &str, file: &str, text: &str) -> (i32, String) {
    let d = dir(name);
    let scene = d.join(file);
    std::fs::write(&scene, text).unwrap();
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .arg("solve")
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let code = o.status.code().unwrap_or(-1);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!out.exists(), "{name}: output directory left behind");
    let leftovers: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != file)
        .collect();
    assert!(leftovers.is_empty(), "{name}: partial files {leftovers:?}");
    (code, err)
}

fn rejects(name: &str, text: &str, needles: &[&str]) {
    let (code, err) = run(name, "scene.toml", text);
    assert_ne!(code, 0, "{name}: accepted");
    for n in needles {
        assert!(err.contains(n), "{name}: message lacks {n:?}:\n{err}");
    }
}

#[test]
fn the_good_scene_solves() {
    let d = dir("good");
    let scene = d.join("scene.toml");
    std::fs::write(&scene, GOOD).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(d.join("out"))
        .arg(&scene)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(d.join("out/report.json").exists());
}

#[test]
fn unknown_keys_are_located() {
    rejects(
        "unknown-top",
        &GOOD.replace("gravity =", "gravty ="),
        &["scene.toml:2:1", "unknown field `gravty`", "gravity"],
    );
    rejects(
        "unknown-section",
        &GOOD.replace("diameter = 0.005", "diametre = 0.005"),
        &["scene.toml:8:", "diametre", "diameter"],
    );
}

#[test]
fn missing_fields_are_named() {
    rejects(
        "missing-section",
        &GOOD.replace("section = { shape = \"circle\", diameter = 0.005 }\n", ""),
        &["scene.toml:", "missing field `section`"],
    );
    rejects(
        "missing-material",
        &GOOD.replace(
            "material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }\n",
            "",
        ),
        &["rods[0].material", "missing"],
    );
    rejects(
        "nu-and-g",
        &GOOD.replace("poisson = 0.4,", "poisson = 0.4, shear_modulus = 3e8,"),
        &[
            "rods[0].material",
            "exactly one of `poisson` or `shear_modulus`",
        ],
    );
}

#[test]
fn nan_and_non_positive_values_are_rejected_with_the_valid_range() {
    rejects(
        "nan-diameter",
        &GOOD.replace("diameter = 0.005", "diameter = nan"),
        &[
            "rods[0].section.diameter",
            "NaN",
            "must be finite and in [1e-30, 1e30]",
        ],
    );
    rejects(
        "nan-gravity",
        &GOOD.replace("-9.81]", "nan]"),
        &["gravity", "finite"],
    );
    rejects(
        "negative-young",
        &GOOD.replace("young = 1.0e9", "young = -1.0e9"),
        &[
            "rods[0].material.young",
            "-1000000000.0",
            "must be finite and in [1e-30, 1e30]",
        ],
    );
    let stiff = GOOD
        .replace(
            "section = { shape = \"circle\", diameter = 0.005 }",
            "section = { shape = \"stiffness\", ea = 1e5, ei1 = 0.0, ei2 = 1e-2, gj = 1e-2, linear_density = 0.03 }",
        )
        .replace(
            "material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }\n",
            "",
        );
    rejects(
        "zero-ei",
        &stiff,
        &["rods[0].section.ei1", "0.0", "must be finite and in [1e-30"],
    );
    rejects(
        "zero-length",
        &GOOD.replace("length = 1.0", "length = 0.0"),
        &["rods[0].centerline.length", "must be finite and in [1e-30"],
    );
    rejects(
        "zero-elements",
        &GOOD.replace("elements = 20", "elements = 0"),
        &["rods[0].elements", "1..="],
    );
    rejects(
        "solver",
        &format!("{GOOD}\n[solver]\nforce_tolerance = -1.0\n"),
        &["solver", "force_tolerance", "> 0"],
    );
}

#[test]
fn coincident_points_are_named() {
    let poly = GOOD
        .replace(
            "centerline = { kind = \"straight\", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }",
            "centerline = { kind = \"polyline\", points = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]] }",
        )
        .replace("elements = 20\n", "");
    rejects(
        "coincident",
        &poly.replace("{ kind = \"pin\", vertex = 12 },", ""),
        &[
            "rods[0].centerline",
            "points[2]",
            "coincides with points[1]",
        ],
    );
}

#[test]
fn supports_on_missing_vertices_are_named() {
    rejects(
        "vertex-range",
        &GOOD.replace("vertex = 12", "vertex = 40"),
        &["rods[0].supports[1].vertex", "40", "<= 20"],
    );
    rejects(
        "vertex-negative",
        &GOOD.replace("vertex = 12", "vertex = -3"),
        &["scene.toml:", "vertex -3", "\"start\" or \"end\""],
    );
    rejects(
        "vertex-name",
        &GOOD.replace("vertex = 12", "vertex = \"middle\""),
        &["scene.toml:", "\"middle\"", "\"start\" or \"end\""],
    );
    rejects(
        "two-on-one",
        &GOOD.replace("vertex = 12", "vertex = 0"),
        &["rods[0].supports[1].vertex", "already held by supports[0]"],
    );
    rejects(
        "motion-support",
        &format!("{GOOD}\n[[motion]]\nrod = 0\nsupport = 5\ntranslate = [0.0, 0.0, 0.1]\n"),
        &["motion[0].support", "5", "< 2"],
    );
    rejects(
        "rotate-pin",
        &format!("{GOOD}\n[[motion]]\nrod = 0\nsupport = 1\nrotate = [0.0, 0.0, 0.1]\n"),
        &["motion[0].rotate", "pin"],
    );
}

#[test]
fn free_rigid_body_motions_are_rejected() {
    let no_supports = GOOD.replace(
        "supports = [\n    { kind = \"clamp\", vertex = \"start\" },\n    { kind = \"pin\", vertex = 12 },\n]\n",
        "",
    );
    rejects(
        "no-support",
        &no_supports,
        &["rods[0].supports", "rigid body"],
    );
    rejects(
        "one-pin",
        &GOOD.replace("{ kind = \"clamp\", vertex = \"start\" },", ""),
        &["rods[0].supports", "rigid body"],
    );
    // Clips hold positions and tangents but not the twist: a straight rod between two clips
    // can spin about its own axis. Only the stiffness matrix shows it.
    rejects(
        "clips-spin",
        &GOOD
            .replace(
                "{ kind = \"clamp\", vertex = \"start\" },",
                "{ kind = \"clip\", vertex = \"start\" },",
            )
            .replace(
                "{ kind = \"pin\", vertex = 12 },",
                "{ kind = \"clip\", vertex = \"end\" },",
            ),
        &["rods[0].supports", "free rigid-body motion"],
    );
}

/// A valid shell strip; the cases below change one line of it.
const SHELL: &str = "[[shells]]
length = 0.3
width = 0.03
thickness = 0.0002
material = { young = 1.0e10, poisson = 0.0, density = 1000.0 }
elements = 6
";

/// Rejected with exit 2 (bad input), no output left, a message naming `needles`.
fn rejects_with_2(name: &str, text: &str, needles: &[&str]) {
    let (code, err) = run(name, "scene.toml", text);
    assert_eq!(code, 2, "{name}: exit code\n{err}");
    for n in needles {
        assert!(err.contains(n), "{name}: message lacks {n:?}:\n{err}");
    }
}

#[test]
fn bad_shell_strips_are_named() {
    let shell = |from: &str, to: &str| {
        assert!(SHELL.contains(from), "{from}");
        format!("gravity = [0.0, -9.81, 0.0]\n{}", SHELL.replace(from, to))
    };
    // The three extreme values are the inputs the scene fuzz found (`scene_fuzz.rs`): they
    // passed a plain `> 0` and the solve then met an infinite Hessian entry.
    let cases: [(&str, &str, &str, &[&str]); 15] = [
        (
            "zero length",
            "length = 0.3",
            "length = 0.0",
            &["shells[0].length", "[1e-30, 1e30]"],
        ),
        (
            "width 1e-300",
            "width = 0.03",
            "width = 1e-300",
            &["shells[0].width", "[1e-30, 1e30]"],
        ),
        (
            "young 1e308",
            "young = 1.0e10",
            "young = 1e308",
            &["shells[0].material.young", "[1e-30, 1e30]"],
        ),
        (
            "thickness 1e308",
            "thickness = 0.0002",
            "thickness = 1e308",
            &["shells[0].thickness", "[1e-30, 1e30]"],
        ),
        (
            "negative width",
            "width = 0.03",
            "width = -0.03",
            &["shells[0].width", "[1e-30, 1e30]"],
        ),
        (
            "zero thickness",
            "thickness = 0.0002",
            "thickness = 0.0",
            &["shells[0].thickness", "[1e-30, 1e30]"],
        ),
        (
            "nan thickness",
            "thickness = 0.0002",
            "thickness = nan",
            &["shells[0].thickness", "finite"],
        ),
        (
            "poisson 0.5",
            "poisson = 0.0",
            "poisson = 0.5",
            &["shells[0].material.poisson", "(-1, 0.5)"],
        ),
        (
            "poisson -1",
            "poisson = 0.0",
            "poisson = -1.0",
            &["shells[0].material.poisson", "(-1, 0.5)"],
        ),
        (
            "zero young",
            "young = 1.0e10",
            "young = 0.0",
            &["shells[0].material.young", "[1e-30, 1e30]"],
        ),
        (
            "zero elements",
            "elements = 6",
            "elements = 0",
            &["shells[0].elements", "at least 1"],
        ),
        (
            "zero width elements",
            "elements = 6",
            "elements = 6\nwidth_elements = 0",
            &["shells[0].width_elements", "at least 1"],
        ),
        (
            "huge mesh",
            "elements = 6",
            "elements = 1000000",
            &["shells[0].elements", "triangles"],
        ),
        (
            "pinned strip",
            "elements = 6",
            "elements = 6\nsupport = \"pin\"",
            &["shells[0].support", "clamp_start", "x = 0"],
        ),
        ("old mesh key", "elements = 6", "mesh = [20, 4]", &["mesh"]),
    ];
    for (name, from, to, needles) in cases {
        rejects_with_2(name, &shell(from, to), needles);
    }
    // A shell and a rod may not share a name (their output files would collide).
    rejects_with_2(
        "shared name",
        &format!("{GOOD}\n{}name = \"{}\"\n", SHELL, "cable"),
        &["shells[0].name", "unique"],
    );
}

#[test]
fn json_scenes_are_located_too() {
    let json = r#"{
  "rods": [{
    "centerline": {"kind": "straight", "start": [0,0,0], "direction": [1,0,0], "length": 1},
    "section": {"shape": "circle", "diameter": 0.005},
    "material": {"young": 1e9, "poisson": 0.4, "density": 1400},
    "supports": [{"kind": "clamp", "vertex": "start"}],
    "colour": "red"
  }]
}"#;
    let (code, err) = run("json-unknown", "scene.json", json);
    assert_ne!(code, 0);
    assert!(
        err.contains("scene.json:7:") && err.contains("colour"),
        "{err}"
    );
    let (code, err) = run("json-syntax", "scene.json", "{\"rods\": [}");
    assert_ne!(code, 0);
    assert!(err.contains("scene.json:1:"), "{err}");
}

#[test]
fn syntax_errors_and_unreadable_files_are_reported() {
    rejects("syntax", "[[rods]\nname = 1", &["scene.toml:1:"]);
    let (code, err) = run("not-utf8", "scene.toml", "\u{0}");
    assert_ne!(code, 0);
    assert!(!err.is_empty());
    let d = dir("missing");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--out"])
        .arg(d.join("out"))
        .arg(d.join("nope.toml"))
        .output()
        .unwrap();
    assert_ne!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nope.toml"));
    assert!(!d.join("out").exists());
}

#[test]
fn a_foreign_output_directory_is_not_overwritten() {
    let d = dir("foreign");
    let scene = d.join("scene.toml");
    std::fs::write(&scene, GOOD).unwrap();
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("precious.txt"), "keep").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(&out)
        .arg(&scene)
        .output()
        .unwrap();
    assert_ne!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not empty"));
    assert_eq!(
        std::fs::read_to_string(out.join("precious.txt")).unwrap(),
        "keep"
    );
}

#[test]
fn a_solve_that_does_not_converge_says_so() {
    // A heavy load with one Newton iteration per step and no step refinement cannot converge:
    // the outputs are written, report.json and solver.csv say why, and the exit code is 1.
    let d = dir("no-convergence");
    let scene = d.join("scene.toml");
    std::fs::write(
        &scene,
        format!(
            "{}\n[solver]\nmax_iterations = 1\nmin_load_step = 0.5\nsnap_iterations = 1\n",
            GOOD.replace("-9.81]", "-9810.0]")
        ),
    )
    .unwrap();
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["solve", "--no-preview", "--out"])
        .arg(&out)
        .arg(&scene)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("did not converge"));
    // The step table claims no stability for a shape that is no equilibrium.
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("(no equilibrium)")
            && !stdout.contains("UNSTABLE")
            && !stdout.contains(" stable"),
        "{stdout}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["converged"], serde_json::Value::Bool(false));
    let solver = std::fs::read_to_string(out.join("solver.csv")).unwrap();
    assert!(solver.lines().nth(1).unwrap().contains("false"), "{solver}");
    assert!(solver.contains("load step fell below"), "{solver}");
}

#[test]
fn bad_new_supports_loads_rings_and_joints_are_named() {
    // A sliding support slides along one straight axis: a curved guide (a list of points)
    // is not a direction.
    rejects(
        "slider-curved-axis",
        &GOOD.replace(
            "{ kind = \"pin\", vertex = 12 }",
            "{ kind = \"slider\", vertex = 12, axis = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]] }",
        ),
        &["scene.toml:", "axis"],
    );
    rejects(
        "slider-zero-axis",
        &GOOD.replace(
            "{ kind = \"pin\", vertex = 12 }",
            "{ kind = \"slider\", vertex = 12, axis = [0.0, 0.0, 0.0] }",
        ),
        &["rods[0].supports[1].axis", "non-zero", "straight axis"],
    );
    rejects(
        "axis-on-pin",
        &GOOD.replace(
            "{ kind = \"pin\", vertex = 12 }",
            "{ kind = \"pin\", vertex = 12, axis = [0.0, 0.0, 1.0] }",
        ),
        &["rods[0].supports[1].axis", "only a slider"],
    );
    // A ring whose ends do not meet.
    rejects(
        "ring-open",
        &GOOD.replace("elements = 20", "elements = 20\nclosed = true"),
        &["rods[0].closed", "must meet"],
    );
    // A follower load on a clamped vertex does nothing.
    rejects(
        "follower-on-clamp",
        &GOOD.replace(
            "supports = [",
            "forces = [ { vertex = \"start\", force = [0.0, 1.0, 0.0], follower = true } ]\nsupports = [",
        ),
        &["rods[0].forces[0].follower", "held by a support"],
    );
    // A support both by vertex and by arc length; an arc length past the end.
    rejects(
        "support-vertex-and-at",
        &GOOD.replace(
            "{ kind = \"pin\", vertex = 12 }",
            "{ kind = \"pin\", vertex = 12, at = 0.3 }",
        ),
        &["rods[0].supports[1]", "exactly one of `vertex`"],
    );
    rejects(
        "support-at-beyond",
        &GOOD.replace(
            "{ kind = \"pin\", vertex = 12 }",
            "{ kind = \"pin\", at = 1.5 }",
        ),
        &["rods[0].supports[1].at", "1.5", "0..=1"],
    );
    // Joints: an unknown rod, ends that do not meet.
    let two = format!(
        "{GOOD}\n[[rods]]\nname = \"branch\"\ncenterline = {{ kind = \"straight\", start = [1.0, 0.5, 0.0], direction = [1.0, 0.0, 0.0], length = 0.5 }}\nsection = {{ shape = \"circle\", diameter = 0.005 }}\nmaterial = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}\n"
    );
    rejects(
        "joint-unknown-rod",
        &format!("{two}\n[[joints]]\nends = [ {{ rod = \"cable\", end = \"end\" }}, {{ rod = \"nope\", end = \"start\" }} ]\n"),
        &["joints[0].ends[1].rod", "\"nope\"", "cable, branch"],
    );
    rejects(
        "joint-apart",
        &format!("{two}\n[[joints]]\nends = [ {{ rod = \"cable\", end = \"end\" }}, {{ rod = \"branch\", end = \"start\" }} ]\n"),
        &["joints[0][1]", "must meet"],
    );
    // A line load with a bad interval.
    rejects(
        "line-load-interval",
        &GOOD.replace(
            "supports = [",
            "line_loads = [ { force_per_length = [0.0, 0.0, -1.0], from = 0.8, to = 0.2 } ]\nsupports = [",
        ),
        &["rods[0].line_loads[0]", "from < to"],
    );
}
