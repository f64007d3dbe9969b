//! No code. Depending on this crate makes a build resolve the same dependency features as
//! `cargo test --workspace`, so that the binary and the Python module reuse the test build's
//! compiled faer, nalgebra and slender-core instead of compiling them again (see Cargo.toml).
