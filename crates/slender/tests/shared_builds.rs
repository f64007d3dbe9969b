//! The binary (`cargo build -p slender`, `cargo run -- validate`) and the Python module
//! (maturin's `-p slender-py`) must resolve the same dependency features as `cargo test
//! --workspace`: then they reuse the test build's compiled faer, nalgebra, slender-core and
//! slender-validation instead of compiling them again (about 7 minutes of CI on two cores; see
//! crates/workspace-hack/Cargo.toml). A dependency added or updated with other features fails
//! here and names the package, before CI gets slow.

use std::collections::BTreeMap;
use std::process::Command;

/// `cargo tree` of one build: package (name, version, source) → its features.
fn resolved_features(args: &[&str]) -> BTreeMap<String, Vec<String>> {
    let workspace = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(&workspace)
        .args(["tree", "--locked", "--prefix", "none", "-f", "{p}|{f}"])
        .args(args)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree {args:?} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let mut packages: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for line in String::from_utf8(output.stdout).unwrap().lines() {
        let line = line.trim_end_matches(" (*)");
        let Some((package, features)) = line.split_once('|') else {
            continue;
        };
        let features = features.to_string();
        let sets = packages.entry(package.to_string()).or_default();
        if !sets.contains(&features) {
            sets.push(features);
        }
    }
    packages
}

#[test]
fn the_binary_and_python_builds_resolve_the_test_builds_features() {
    let test_build = resolved_features(&["--workspace"]);
    for (build, args) in [
        (
            "the binary (cargo build -p slender)",
            ["-p", "slender", "-e", "no-dev"],
        ),
        (
            "the Python module (maturin, -p slender-py)",
            ["-p", "slender-py", "-e", "no-dev"],
        ),
    ] {
        let mut differing = Vec::new();
        for (package, sets) in resolved_features(&args) {
            let in_test = test_build.get(&package);
            for features in sets {
                if !in_test.is_some_and(|t| t.contains(&features)) {
                    differing.push(format!(
                        "{package}: [{features}] here, {:?} in the test build",
                        in_test.cloned().unwrap_or_default()
                    ));
                }
            }
        }
        assert!(
            differing.is_empty(),
            "{build} compiles these packages with other features than `cargo test --workspace` \
             (declare the test build's features in crates/workspace-hack/Cargo.toml):\n{}",
            differing.join("\n")
        );
    }
}
