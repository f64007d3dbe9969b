//! Every integration test of the slender binary in one test binary, one module per file of this
//! directory: the library and the solver's generic code are linked and instantiated once
//! instead of once per file, which was most of CI's build time. One file's tests:
//! `cargo test -p slender --release --test integration <file>::` (a substring filter: add
//! `-- --skip` for files whose name ends another's, e.g. `contact::` and `scene_contact::`; or
//! `-- --exact <file>::<test>` for one test).

mod examples;
mod scene_bad_input;
mod scene_fuzz;
mod sensitivity;
mod shape_files;
mod shared_builds;
mod slurm;
mod stick_slip;
mod store;

/// A test file that is not declared as a module of its crate's `tests/integration.rs` would
/// never be compiled or run (`autotests = false` in each Cargo.toml): every one must be. Checked
/// here for the three crates.
#[test]
fn every_test_file_is_a_module_of_its_crates_test_binary() {
    let crates = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    // Files with their own binary ([[test]] in Cargo.toml).
    let apart = [("slender-core", "resolve_allocations")];
    for krate in ["slender-core", "slender-validation", "slender"] {
        let dir = crates.join(krate).join("tests");
        let root = std::fs::read_to_string(dir.join("integration.rs")).unwrap();
        for entry in std::fs::read_dir(&dir).unwrap() {
            let name = entry.unwrap().file_name().into_string().unwrap();
            let Some(stem) = name.strip_suffix(".rs") else {
                continue;
            };
            if stem == "integration" || apart.contains(&(krate, stem)) {
                continue;
            }
            assert!(
                root.lines().any(|l| l == format!("mod {stem};")),
                "crates/{krate}/tests/{name} is not a module of its tests/integration.rs"
            );
        }
    }
}
