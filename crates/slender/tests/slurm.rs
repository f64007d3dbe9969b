//! The Slurm scripts (scripts/slurm) run end to end against a stand-in `sbatch` that executes
//! each job at once (array tasks one after another): the merged, sharded run must write the
//! same results as an unsharded run.

use std::fs;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs the job immediately; prints a job id like `sbatch --parsable`.
const FAKE_SBATCH: &str = r#"#!/usr/bin/env bash
array=""
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in --array=*) array=${1#--array=} ;; esac
  shift
done
script=$1; shift
if [ -n "$array" ]; then
  for ((i = ${array%-*}; i <= ${array#*-}; i++)); do
    SLURM_ARRAY_TASK_ID=$i bash "$script" "$@" >&2 || exit 1
  done
else
  bash "$script" "$@" >&2 || exit 1
fi
echo 4242
"#;

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("slurm-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn sweep_args() -> Vec<&'static str> {
    vec![
        "cantilever",
        "--gamma-count",
        "9",
        "--elements",
        "10,20",
        "--meshes",
        "graded",
        "--materials",
        "rod",
        "--shell-materials",
        "none",
    ]
}

fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scripts/slurm")
        .join(name)
}

#[test]
fn sharded_slurm_run_equals_the_unsharded_run() {
    let root = scratch("array");
    let bin = root.join("bin");
    fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    fs::write(&sbatch, FAKE_SBATCH).unwrap();
    fs::set_permissions(&sbatch, fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());

    let out = root.join("cluster");
    let status = Command::new("bash")
        .arg(script("submit.sh"))
        .arg("3")
        .arg(&out)
        .args(sweep_args())
        .env("PATH", &path)
        .env("SLENDER_BIN", env!("CARGO_BIN_EXE_slender"))
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "submit.sh failed: {}",
        String::from_utf8_lossy(&status.stderr)
    );
    for i in 0..3 {
        assert!(out.join(format!("shard-{i}/store/cantilever")).is_dir());
    }
    let log = String::from_utf8_lossy(&status.stderr);
    assert!(log.contains("18 of 18 cases found finished"), "{log}");

    let single = root.join("single");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(sweep_args())
        .arg("--out")
        .arg(&single)
        .output()
        .unwrap();
    assert!(o.status.success());
    assert_eq!(
        fs::read(out.join("results.csv")).unwrap(),
        fs::read(single.join("results.csv")).unwrap()
    );
}

#[test]
fn submit_rejects_bad_arguments() {
    for args in [
        vec!["0", "/tmp/x", "cantilever"],
        vec!["two", "/tmp/x", "cantilever"],
        vec!["3"],
    ] {
        let o = Command::new("bash")
            .arg(script("submit.sh"))
            .args(&args)
            .env("SLENDER_BIN", env!("CARGO_BIN_EXE_slender"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(!o.stderr.is_empty());
    }
}
