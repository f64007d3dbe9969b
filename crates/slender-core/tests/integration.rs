//! Every integration test of slender-core in one test binary, one module per file of this
//! directory: the library and the solver's generic code are linked and instantiated once
//! instead of once per file, which was most of CI's build time. One file's tests:
//! `cargo test -p slender-core --release --test integration <file>::` (a substring filter: add
//! `-- --skip` for files whose name ends another's, e.g. `contact::` and `scene_contact::`; or
//! `-- --exact <file>::<test>` for one test). A test of the `slender` crate
//! (`every_test_file_is_a_module_of_its_crates_test_binary`) fails if a file here is not declared.
//! Apart: `resolve_allocations` (a counting global allocator, which would count every other test).

mod bad_input;
mod banded_ldlt;
mod bspline_shell;
mod bspline_shell_bad_input;
mod common;
mod contact;
mod cosserat_derivatives;
mod derivatives;
mod dynamics;
mod follower;
mod framed_bad_input;
mod framed_dynamics;
mod framed_physics;
mod lagged_hessian;
mod routing;
mod scene;
mod scene_contact;
mod scene_contact_radii;
mod scene_precision;
mod scene_ring;
mod scene_rod_models;
mod scene_segment_contact;
mod scene_shell_contact;
mod scene_time;
mod scene_time_contact;
mod scene_time_framed;
mod scene_time_framed_contact;
mod se3_derivatives;
mod session_force_edit;
mod session_gravity_edit;
mod session_length;
mod session_moment_edit;
mod session_obstacle_move;
mod session_release;
mod session_shell_force_edit;
mod session_thin_wire;
mod shell_bad_input;
mod shell_contact;
mod shell_derivatives;
mod shell_scene_clamps;
mod solver;
mod sparse_ldlt;
mod structure;
