//! Every integration test of slender-validation in one test binary, one module per file of this
//! directory: the library and the solver's generic code are linked and instantiated once
//! instead of once per file, which was most of CI's build time. One file's tests:
//! `cargo test -p slender-validation --release --test integration <file>::` (a substring filter: add
//! `-- --skip` for files whose name ends another's, e.g. `contact::` and `scene_contact::`; or
//! `-- --exact <file>::<test>` for one test). A test of the `slender` crate
//! (`every_test_file_is_a_module_of_its_crates_test_binary`) fails if a file here is not declared.

mod bend_twist_discrete;
mod bend_twist_master_curve;
mod cantilever_acceptance;
mod capstan;
mod lateral_buckling_master_curve;
mod lateral_sweep;
mod master_curve;
mod rod_models;
mod scene_stick_slip;
mod shell_cantilever;
mod stick_slip;
