//! Empty: it exists so that the build dependencies in Cargo.toml (host-side syn features shared
//! with the proc macros) take part in feature resolution.
fn main() {}
