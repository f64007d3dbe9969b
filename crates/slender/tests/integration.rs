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
mod slurm;
mod stick_slip;
mod store;

/// A file of this directory that is not declared above would never be compiled or run
/// (`autotests = false` in Cargo.toml): every one must be.
#[test]
fn every_test_file_is_a_module_of_this_binary() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let root = std::fs::read_to_string(dir.join("integration.rs")).unwrap();
    let apart: &[&str] = &[];
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let Some(stem) = name.strip_suffix(".rs") else {
            continue;
        };
        if stem == "integration" || apart.contains(&stem) {
            continue;
        }
        assert!(
            root.lines().any(|l| l == format!("mod {stem};")),
            "tests/{name} is not a module of tests/integration.rs"
        );
    }
}
