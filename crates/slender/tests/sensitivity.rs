//! `slender sensitivity` end to end on a tiny study: the files are written, the score is the
//! one recomputed here from points.csv and the plate master curve (not from the code's
//! scoring), a rerun with the store recomputes nothing, and bad flags give clear errors.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use slender_validation::lateral_buckling::{critical_gamma, MasterCurve};

fn slender() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slender"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("sensitivity-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

const FACTORS: [f64; 4] = [0.7, 0.9, 1.1, 1.5];
const WIDTHS: [f64; 2] = [0.1, 0.2];
const SIGMAS: [f64; 2] = [0.1, 0.3];
const THRESHOLD: f64 = 1e-4;
/// Ω_shell's Poisson ratio (seed Table 2), written here rather than read from the code.
const NU_SHELL: f64 = 0.35;

/// A tiny study: Ω_shell, n_L = 6, m_ls = 2, σ ∈ {0.1, 0.3}, w/L ∈ {0.1, 0.2}, 4 factors.
fn tiny_args(out: &Path) -> Vec<String> {
    let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    vec![
        "sensitivity".into(),
        "--out".into(),
        out.to_str().unwrap().into(),
        "--materials".into(),
        "shell".into(),
        "--elements".into(),
        "6".into(),
        "--load-steps".into(),
        "2".into(),
        "--sigmas".into(),
        list(&SIGMAS),
        "--width-ratios".into(),
        list(&WIDTHS),
        "--gamma-factors".into(),
        list(&FACTORS),
        // One shell model keeps the study tiny (the model axis is exercised by the store test).
        "--shell-model".into(),
        "midedge".into(),
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

fn read_csv(path: &Path) -> Vec<csv::StringRecord> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().clone();
    let rows: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    // Keep the header as row 0 so that columns are looked up by name.
    std::iter::once(header).chain(rows).collect()
}

fn col(rows: &[csv::StringRecord], name: &str) -> usize {
    rows[0]
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {:?}", rows[0]))
}

#[test]
fn tiny_study_scores_against_the_master_curve_and_reuses_the_store() {
    let dir = scratch("tiny");
    let out = dir.join("out");
    let args = tiny_args(&out);
    let first = run_ok(&args);
    for f in [
        "points.csv",
        "scores.csv",
        "sensitivity.png",
        "sensitivity.svg",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let points = read_csv(&out.join("points.csv"));
    let n_points = SIGMAS.len() * WIDTHS.len() * FACTORS.len();
    assert_eq!(points.len() - 1, n_points);
    let [w_c, g_c, gc_c, f_c, tip_c, conv_c, sig_c] = [
        "width_ratio",
        "gamma",
        "gamma_c",
        "gamma_factor",
        "tip_deviation",
        "converged",
        "sigma",
    ]
    .map(|n| col(&points, n));
    let num = |r: &csv::StringRecord, c: usize| r[c].parse::<f64>().unwrap();

    // The score per σ, recomputed: truth from the plate master curve (no shell), verdict from
    // the tip deviation and the threshold, a non-converged run counted wrong.
    let mut expected = Vec::new();
    let mut decided_3d = 0;
    for &sigma in &SIGMAS {
        let mut correct = 0;
        let mut n = 0;
        for r in points[1..].iter().filter(|r| num(r, sig_c) == sigma) {
            let w = num(r, w_c);
            let gamma = num(r, g_c);
            let gc = critical_gamma(w, NU_SHELL, MasterCurve::KirchhoffPlate).unwrap();
            assert!((num(r, gc_c) / gc - 1.0).abs() < 1e-12, "Γ_c column");
            let f = num(r, f_c);
            assert!(FACTORS.contains(&f));
            assert!(
                (gamma / gc - f).abs() < 1e-12,
                "Γ is not f·Γ_c: {gamma} vs {f}·{gc}"
            );
            let truth_3d = gamma > gc;
            let converged = &r[conv_c] == "true";
            let tip = num(r, tip_c);
            let protocol_3d = tip.abs() > THRESHOLD;
            decided_3d += usize::from(converged && protocol_3d);
            correct += usize::from(converged && tip.is_finite() && protocol_3d == truth_3d);
            n += 1;
        }
        assert_eq!(n, WIDTHS.len() * FACTORS.len());
        expected.push((sigma, 100.0 * correct as f64 / n as f64));
    }
    // A protocol that never leaves the plane would score 50 % here, and the test would still
    // pass; check that the model does buckle above the curve somewhere.
    assert!(decided_3d > 0, "no point decided 3-D");
    let scores = read_csv(&out.join("scores.csv"));
    assert_eq!(scores.len() - 1, SIGMAS.len());
    let [s_sig, s_pct, s_n] = ["sigma", "score_percent", "points"].map(|n| col(&scores, n));
    for r in &scores[1..] {
        let sigma: f64 = r[s_sig].parse().unwrap();
        let want = expected.iter().find(|e| e.0 == sigma).unwrap().1;
        let got: f64 = r[s_pct].parse().unwrap();
        assert!(
            (got - want).abs() < 1e-9,
            "σ = {sigma}: score {got} vs {want}"
        );
        assert_eq!(
            r[s_n].parse::<usize>().unwrap(),
            WIDTHS.len() * FACTORS.len()
        );
    }
    let stdout = String::from_utf8_lossy(&first.stdout);
    assert!(
        stdout.contains(&format!("{n_points} computed, 0 reused")),
        "{stdout}"
    );

    // Rerun: everything comes from the store, same report.
    let csv_before = fs::read(out.join("points.csv")).unwrap();
    let again = run_ok(&args);
    let stdout = String::from_utf8_lossy(&again.stdout);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        stdout.contains(&format!("0 computed, {n_points} reused")),
        "{stdout}"
    );
    assert!(
        stderr.contains(&format!("{n_points} of {n_points} cases found finished")),
        "{stderr}"
    );
    assert_eq!(fs::read(out.join("points.csv")).unwrap(), csv_before);

    // A shard writes records, no report.
    let shard_out = dir.join("shard");
    let mut shard_args = tiny_args(&shard_out);
    shard_args.extend(["--shard".into(), "0/2".into()]);
    let o = run_ok(&shard_args);
    assert!(String::from_utf8_lossy(&o.stdout).contains("merge"));
    assert!(
        !shard_out.join("scores.csv").exists(),
        "a shard writes no report"
    );
}

#[test]
fn bad_flags_name_the_flag_and_the_valid_range() {
    let out = scratch("bad");
    let cases: [(&[&str], &[&str]); 11] = [
        (&["--elements", "0"], &["--elements", ">= 1"]),
        (&["--sigmas", "NaN"], &["--sigmas", "finite"]),
        (&["--sigmas", "inf"], &["--sigmas", "finite"]),
        (&["--gamma-factors", "-1,1.2"], &["--gamma-factors", "> 0"]),
        (&["--gamma-factors", "1.1,1.2"], &["--gamma-factors", "< 1"]),
        (&["--width-ratios", "1.5"], &["--width-ratios", "[0.01, 1]"]),
        (&["--width-ratios", "0"], &["--width-ratios", "[0.01, 1]"]),
        (
            &["--materials", "steel"],
            &["--materials", "shell, combined, ips"],
        ),
        (&["--threshold", "0"], &["--threshold", "> 0"]),
        (&["--sigmas", "-0.1"], &["--sigmas", "> 0"]),
        (&["--load-steps", "3,3"], &["--load-steps", "twice"]),
    ];
    for (flags, needles) in cases {
        let o = slender()
            .args(["sensitivity", "--out", out.to_str().unwrap()])
            .args(flags)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flags:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{flags:?}: `{n}` not in {err}");
        }
    }
    assert!(!out.join("points.csv").exists());
}
