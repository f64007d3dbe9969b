//! The warm-drag loop of `benches/session_edit.rs` (a 100-element cable, both ends clamped,
//! the end dragged by ±1 cm per call) as a plain program, for profilers: criterion's timing
//! loop and the bench file's shell set-ups would otherwise dominate a profile.
//!
//! `N=300 valgrind --tool=callgrind target/release/examples/drag_loop` counts instructions
//! (deterministic, unlike times on a shared machine); `drag_loop clips` adds three clips.
//! Prints the mean wall time and Newton iterations per drag.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};
fn main() {
    let clips = std::env::args().nth(1).is_some_and(|s| s == "clips");
    let mut supports =
        String::from(r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }"#);
    if clips {
        for v in [25, 50, 75] {
            supports.push_str(&format!(r#", {{ kind = "clip", vertex = {v} }}"#));
        }
    }
    let scene: Scene = toml::from_str(&format!(r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 100
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {supports} ]
"#)).unwrap();
    let mut session = Session::new(scene).unwrap();
    let mut sign = 1.0;
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20000);
    let t = std::time::Instant::now();
    let mut its = 0;
    // Round-off fingerprint of the whole run: two builds that take the same steps print the
    // same sum of final residuals, bit for bit.
    let mut residuals = 0.0;
    for _ in 0..n {
        let r = session
            .move_support_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.01 * sign, 0.0))
            .unwrap();
        assert!(r.converged);
        its += r.iterations;
        residuals += r.relative_residual;
        sign = -sign;
    }
    println!(
        "{:.1} us per drag, {:.2} iterations, residual fingerprint {:e}",
        t.elapsed().as_secs_f64() / n as f64 * 1e6,
        its as f64 / n as f64,
        residuals
    );
}
