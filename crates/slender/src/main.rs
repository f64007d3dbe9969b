// Not yet called from `main`; remove the allow once the CLI uses the plots.
#[allow(dead_code, unused_imports)]
mod plot;

fn main() {}
