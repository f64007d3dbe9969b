//! The result store end to end, through the binary: a sweep killed with SIGKILL and rerun
//! gives the records of an uninterrupted run; --jobs 1 and --jobs 2 give identical records;
//! shards 0/3, 1/3, 2/3 merged equal the unsharded run; torn and edited records are
//! recomputed; records of different rod models never mix.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn slender() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slender"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("store-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// A cantilever sweep of `cases` cases (Ω_rod, uniform and graded meshes, N = 20).
fn cantilever_args(out: &Path, gammas: usize) -> Vec<String> {
    [
        "cantilever",
        "--out",
        out.to_str().unwrap(),
        "--gamma-count",
        &gammas.to_string(),
        "--elements",
        "20",
        "--meshes",
        "uniform,graded",
        "--materials",
        "rod",
        // Rods only: the store is what is tested here.
        "--shell-materials",
        "none",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

fn run_ok(args: &[String], extra: &[&str]) -> Output {
    let out = slender().args(args).args(extra).output().unwrap();
    assert!(
        out.status.success(),
        "slender {args:?} {extra:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Record files of a store: name → content without the header (checksum) and the wall
/// time, the two parts that legitimately differ between runs.
fn records(store: &Path) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    let dir = store.join("cantilever");
    for e in fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        let text = fs::read_to_string(&p).unwrap();
        let body: String = text
            .lines()
            .filter(|l| !l.starts_with("# slender record") && !l.starts_with("seconds ="))
            .collect::<Vec<_>>()
            .join("\n");
        m.insert(name, body);
    }
    m
}

fn count_records(store: &Path) -> usize {
    fs::read_dir(store.join("cantilever"))
        .map(|it| {
            it.flatten()
                .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
                .count()
        })
        .unwrap_or(0)
}

#[test]
fn jobs_and_shards_give_identical_records() {
    let root = scratch("jobs-shards");
    let gammas = 30;
    let total = 2 * gammas;
    let one = root.join("jobs1");
    run_ok(&cantilever_args(&one, gammas), &["--jobs", "1"]);
    let two = root.join("jobs2");
    run_ok(&cantilever_args(&two, gammas), &["--jobs", "2"]);
    let reference = records(&one.join("store"));
    assert_eq!(reference.len(), total);
    assert_eq!(records(&two.join("store")), reference, "--jobs 1 vs 2");
    let csv = fs::read(one.join("results.csv")).unwrap();
    assert_eq!(fs::read(two.join("results.csv")).unwrap(), csv);

    // Three shards: disjoint, together complete, and no report of their own.
    let mut shard_stores = Vec::new();
    let mut seen = BTreeMap::new();
    for i in 0..3 {
        let out = root.join(format!("shard{i}"));
        let o = run_ok(
            &cantilever_args(&out, gammas),
            &["--shard", &format!("{i}/3")],
        );
        assert!(String::from_utf8_lossy(&o.stdout).contains("merge"));
        assert!(
            !out.join("results.csv").exists(),
            "a shard writes no report"
        );
        let r = records(&out.join("store"));
        assert_eq!(r.len(), total / 3);
        for (k, v) in r {
            assert!(seen.insert(k, v).is_none(), "shards overlap");
        }
        shard_stores.push(out.join("store"));
    }
    assert_eq!(seen, reference);
    let merged = root.join("merged");
    let mut merge = vec![
        "merge".to_string(),
        "--into".into(),
        merged.join("store").to_str().unwrap().into(),
    ];
    merge.extend(shard_stores.iter().map(|p| p.to_str().unwrap().to_string()));
    run_ok(&merge, &[]);
    assert_eq!(records(&merged.join("store")), reference, "merged shards");
    // Merging again changes nothing; the report from the merged store recomputes nothing.
    let again = run_ok(&merge, &[]);
    assert!(String::from_utf8_lossy(&again.stdout).contains("0 records copied"));
    let report = run_ok(&cantilever_args(&merged, gammas), &[]);
    let log = String::from_utf8_lossy(&report.stderr);
    assert!(
        log.contains(&format!("{total} of {total} cases found finished")),
        "{log}"
    );
    assert_eq!(fs::read(merged.join("results.csv")).unwrap(), csv);
}

#[test]
fn killed_sweep_resumes_to_the_records_of_an_uninterrupted_run() {
    let root = scratch("kill");
    let gammas = 1000;
    let total = 2 * gammas;
    let whole = root.join("whole");
    run_ok(&cantilever_args(&whole, gammas), &[]);
    let reference = records(&whole.join("store"));
    assert_eq!(reference.len(), total);

    // Kill a one-thread run once a few records exist.
    let killed = root.join("killed");
    let store = killed.join("store");
    let mut child = slender()
        .args(cantilever_args(&killed, gammas))
        .args(["--jobs", "1"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let clock = Instant::now();
    while count_records(&store) < 20 {
        assert!(
            clock.elapsed() < Duration::from_secs(120),
            "no records appeared"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let partial = count_records(&store);
    assert!(
        partial < total,
        "the run finished before the kill ({partial} records); the test needs a longer sweep"
    );
    assert!(!killed.join("results.csv").exists());

    // Damage two finished records as a crash or an editor could.
    let mut files: Vec<PathBuf> = fs::read_dir(store.join("cantilever"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    let torn = fs::read(&files[0]).unwrap();
    fs::write(&files[0], &torn[..torn.len() / 2]).unwrap();
    let edited = fs::read_to_string(&files[1]).unwrap();
    fs::write(&files[1], edited.replacen("ratio = ", "ratio = 1", 1)).unwrap();
    fs::write(
        store.join("cantilever").join(".partial-leftover"),
        b"half a rec",
    )
    .unwrap();

    let rerun = run_ok(&cantilever_args(&killed, gammas), &[]);
    let log = String::from_utf8_lossy(&rerun.stderr);
    assert!(log.contains("computing it again"), "{log}");
    assert!(!store.join("cantilever").join(".partial-leftover").exists());
    assert_eq!(records(&store), reference);
    assert_eq!(
        fs::read(killed.join("results.csv")).unwrap(),
        fs::read(whole.join("results.csv")).unwrap()
    );
}

#[test]
fn merge_refuses_two_different_results_for_one_case() {
    use sha2::{Digest, Sha256};
    let root = scratch("conflict");
    let a = root.join("a");
    run_ok(&cantilever_args(&a, 2), &[]);
    let b = root.join("b");
    run_ok(&cantilever_args(&b, 2), &[]);
    // Forge a well-formed record of b with another result (valid checksum).
    let dir = b.join("store").join("cantilever");
    let mut files: Vec<PathBuf> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let text = fs::read_to_string(&files[0]).unwrap();
    let (_, body) = text.split_once('\n').unwrap();
    let body = body.replacen("iterations = ", "iterations = 9", 1);
    let sum: String = Sha256::digest(body.as_bytes())
        .iter()
        .map(|x| format!("{x:02x}"))
        .collect();
    fs::write(&files[0], format!("# slender record sha256={sum}\n{body}")).unwrap();
    let out = slender()
        .args(["merge", "--into"])
        .arg(root.join("m"))
        .arg(a.join("store"))
        .arg(b.join("store"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("different results"), "{err}");
}

/// The shell strips of `slender cantilever` go through the store like the rods: a rerun
/// computes nothing and writes the same shell_results.csv (wall times included: they are
/// the stored ones), and shards split them.
#[test]
fn shell_cantilever_cases_are_stored_reused_and_sharded() {
    let root = scratch("shells");
    let args = |out: &Path| -> Vec<String> {
        let mut a = cantilever_args(out, 3);
        let at = a.iter().position(|s| s == "--shell-materials").unwrap();
        a.truncate(at);
        a.extend(
            [
                "--shell-materials",
                "shell,combined",
                "--shell-elements",
                "8",
            ]
            .iter()
            .map(|s| s.to_string()),
        );
        a
    };
    let shells = |store: &Path| {
        fs::read_dir(store.join("cantilever-shell"))
            .map(|it| it.flatten().count())
            .unwrap_or(0)
    };
    let whole = root.join("whole");
    let first = run_ok(&args(&whole), &[]);
    // Both shell models by default: 2 models × 2 sets × 3 Γ.
    assert_eq!(shells(&whole.join("store")), 12, "2 models × 2 sets × 3 Γ");
    let csv = fs::read(whole.join("shell_results.csv")).unwrap();
    assert!(!String::from_utf8_lossy(&first.stderr).contains("found finished"));
    let again = run_ok(&args(&whole), &[]);
    let log = String::from_utf8_lossy(&again.stderr);
    assert!(
        log.contains("cantilever-shell: 12 of 12 cases found finished"),
        "{log}"
    );
    assert_eq!(fs::read(whole.join("shell_results.csv")).unwrap(), csv);
    // Shards: 0/2 computes every other case of the shell list (6 of 12) and writes no report.
    let shard = root.join("shard");
    let o = run_ok(&args(&shard), &["--shard", "0/2"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("merge"));
    assert_eq!(shells(&shard.join("store")), 6);
    assert!(!shard.join("shell_results.csv").exists());
}

#[test]
fn records_of_different_rod_models_never_mix() {
    let root = scratch("models");
    let gammas = 4;
    let der = root.join("der");
    run_ok(&cantilever_args(&der, gammas), &[]);
    let reference = records(&der.join("store"));
    assert_eq!(reference.len(), 2 * gammas);
    // The SE(3) beam into the same store: its own records, none of the DER's reused.
    let se3 = run_ok(
        &cantilever_args(&der, gammas),
        &[
            "--model",
            "se3",
            "--store",
            der.join("store").to_str().unwrap(),
        ],
    );
    let log = String::from_utf8_lossy(&se3.stderr);
    assert!(!log.contains("found finished"), "{log}");
    let both = records(&der.join("store"));
    assert_eq!(both.len(), 4 * gammas);
    for (k, v) in &reference {
        assert_eq!(both.get(k), Some(v), "a DER record changed");
    }
    // `--model der` is the default: the same keys, everything reused.
    let again = run_ok(&cantilever_args(&der, gammas), &["--model", "der"]);
    let log = String::from_utf8_lossy(&again.stderr);
    assert!(
        log.contains(&format!("{0} of {0} cases found finished", 2 * gammas)),
        "{log}"
    );
}
