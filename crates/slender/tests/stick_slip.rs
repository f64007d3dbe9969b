//! `slender stick-slip` end to end on a small grid: the files are written, every decision in
//! results.csv is Coulomb's (recomputed here from tan α and μ, not from the code's scoring),
//! sticking rods do not move, sliding ones accelerate at g (sin α − μ cos α), a rerun with the
//! store recomputes nothing, and bad flags give clear errors.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn slender() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slender"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("stick-slip-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

const RATIOS: [f64; 6] = [0.5, 0.99, 0.995, 1.005, 1.01, 1.3];
const MUS: [f64; 2] = [0.3, 0.8];
const G: f64 = 9.81;

fn small_args(out: &Path) -> Vec<String> {
    let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    vec![
        "stick-slip".into(),
        "--out".into(),
        out.to_str().unwrap().into(),
        "--rods".into(),
        "soft,steel".into(),
        "--mus".into(),
        list(&MUS),
        "--ratios".into(),
        list(&RATIOS),
        "--steps".into(),
        "40".into(),
    ]
}

fn run_ok(args: &[String]) -> Output {
    let out = slender().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "slender {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Rows of a CSV file as maps from column name to text.
fn read_csv(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().clone();
    r.records()
        .map(|x| {
            let x = x.unwrap();
            header
                .iter()
                .zip(x.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn num(row: &std::collections::HashMap<String, String>, name: &str) -> f64 {
    row[name]
        .parse()
        .unwrap_or_else(|e| panic!("{name} = {:?}: {e}", row[name]))
}

#[test]
fn small_sweep_decides_as_coulomb_and_reuses_the_store() {
    let out = scratch("small");
    let first = run_ok(&small_args(&out));
    let stdout = String::from_utf8_lossy(&first.stdout);
    assert!(stdout.contains("24 computed, 0 reused"), "{stdout}");
    for stem in [
        "acceleration",
        "acceleration_error",
        "displacement",
        "phase_gamma",
        "phase_soft",
        "phase_steel",
    ] {
        for ext in ["png", "svg"] {
            let f = out.join(format!("{stem}.{ext}"));
            assert!(
                fs::metadata(&f).map(|m| m.len() > 1000).unwrap_or(false),
                "{} missing or empty",
                f.display()
            );
        }
    }
    let rows = read_csv(&out.join("results.csv"));
    assert_eq!(rows.len(), 2 * MUS.len() * RATIOS.len());
    for r in &rows {
        let (mu, tan) = (num(r, "mu"), num(r, "tan_alpha"));
        let alpha = tan.atan();
        assert_eq!(r["converged"], "true", "{r:?}");
        let coulomb_slides = tan > mu;
        assert_eq!(r["slid"] == "true", coulomb_slides, "{r:?}");
        if coulomb_slides && tan >= 1.01 * mu * (1.0 - 1e-12) {
            let exact = G * (alpha.sin() - mu * alpha.cos());
            let a = num(r, "acceleration");
            assert!(((a - exact) / exact).abs() <= 1e-3, "{r:?}");
            let normalized = num(r, "normalized");
            assert!(
                (normalized - (tan - mu)).abs() <= 1e-3 * (tan - mu),
                "{r:?}"
            );
        }
        if !coulomb_slides {
            assert!(num(r, "displacement_over_length") <= 1e-9, "{r:?}");
        }
    }
    let summary = read_csv(&out.join("summary.csv"));
    assert_eq!(
        summary
            .iter()
            .map(|s| s["rod"].as_str())
            .collect::<Vec<_>>(),
        ["soft", "steel", "all"]
    );
    for s in &summary {
        assert_eq!(num(s, "correct_percent"), 100.0, "{s:?}");
        // 0.995 and 1.005 are in the band: not scored.
        assert_eq!(
            num(s, "scored") as usize,
            if s["rod"] == "all" { 2 } else { 1 } * MUS.len() * (RATIOS.len() - 2)
        );
    }

    let again = run_ok(&small_args(&out));
    let stdout = String::from_utf8_lossy(&again.stdout);
    assert!(stdout.contains("0 computed, 24 reused"), "{stdout}");
}

#[test]
fn bad_flags_name_the_flag() {
    let out = scratch("bad");
    for (flag, value, says) in [
        ("--rods", "rubber", "--rods: unknown rod set `rubber`"),
        ("--mus", "0.5,-1", "--mus"),
        ("--steps", "2", "--steps"),
        ("--dt", "0", "--dt"),
    ] {
        let o = slender()
            .args(["stick-slip", "--out", out.to_str().unwrap(), flag, value])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{flag} {value}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{flag} {value}: {err}");
    }
}
