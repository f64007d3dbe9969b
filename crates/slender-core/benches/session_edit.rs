//! Speed of interactive editing (issue 11): a warm re-solve through `Session` after a 1 cm
//! drag of a cable's end, one core, against the ≤ 200 µs target for a 100-element rod, and
//! of a flat cable's end clamp (a shell strip, n_L = 30, both models) against ≤ 100 ms.
//!
//! Run with `cargo bench -p slender-core --bench session_edit`; figures in BENCHMARKS.md.
//!
//! Each timed call is one `move_support_by` of ±1 cm (alternating, so the cable swings between
//! two poses and every call is a real re-solve from the previous equilibrium), exactly what
//! `slender view` does per drag update.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};

/// A 1 m cable (d = 6 mm, E = 1 GPa), clamped at both ends, sagging under gravity; `clips`
/// clips along it (none: a plain span).
fn scene(clips: &[usize]) -> Scene {
    let mut supports =
        String::from(r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }"#);
    for v in clips {
        supports.push_str(&format!(r#", {{ kind = "clip", vertex = {v} }}"#));
    }
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 100
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {supports} ]
"#
    ))
    .expect("scene")
}

fn drag(c: &mut Criterion, name: &str, clips: &[usize]) {
    let mut session = Session::new(scene(clips)).expect("session");
    // The end clamp is support 1; drag it along y (across the span) by ±1 cm.
    let mut sign = 1.0;
    c.bench_function(name, |b| {
        b.iter(|| {
            let r = session
                .move_support_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.01 * sign, 0.0))
                .expect("edit");
            assert!(r.converged, "{r:?}");
            sign = -sign;
            black_box(r.iterations)
        })
    });
}

/// A flat cable as a shell strip (L = 0.3 m, w = 20 mm, h = 0.3 mm, E = 5 GPa), n_L = 30
/// uniform elements, both end edges clamped, sagging under gravity across its thickness.
fn flat_cable(model: &str) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[shells]]
name = "flat"
model = "{model}"
length = 0.3
width = 0.02
thickness = 3.0e-4
material = {{ young = 5.0e9, poisson = 0.3, density = 2000.0 }}
elements = 30
grading = {{ kind = "uniform" }}
clamps = [ {{ edge = "start" }}, {{ edge = "end" }} ]
"#
    ))
    .expect("scene")
}

/// Drags the end clamp of the flat cable by ±1 cm along `axis` (alternating), as `slender
/// view` does per drag update; prints the Newton iterations per drag once.
fn drag_shell(c: &mut Criterion, name: &str, model: &str, axis: Vec3) {
    let mut session = Session::new(flat_cable(model)).expect("session");
    // Push first (−x for the axial drag): the harder direction, from the loaded state.
    let mut sign = if axis.x != 0.0 { -1.0 } else { 1.0 };
    let mut iterations = Vec::new();
    let mut last = None;
    for _ in 0..6 {
        let r = session
            .move_shell_clamp_by(0, 1, Vec3::zeros(), axis * (0.01 * sign))
            .expect("edit");
        assert!(r.converged, "{r:?}");
        iterations.push(r.iterations);
        last = Some((r.load_steps, r.relative_residual));
        sign = -sign;
    }
    eprintln!(
        "{name}: Newton iterations per drag {iterations:?}; load steps, relative residual of the last: {last:?}"
    );
    c.bench_function(name, |b| {
        b.iter(|| {
            let r = session
                .move_shell_clamp_by(0, 1, Vec3::zeros(), axis * (0.01 * sign))
                .expect("edit");
            assert!(r.converged, "{r:?}");
            sign = -sign;
            black_box(r.iterations)
        })
    });
}

fn benches(c: &mut Criterion) {
    drag_shell(c, "warm_drag_1cm/shell_n30_midedge", "midedge", Vec3::y());
    drag_shell(c, "warm_drag_1cm/shell_n30_bspline", "bspline", Vec3::y());
    drag_shell(
        c,
        "warm_drag_1cm/shell_n30_midedge_axial",
        "midedge",
        Vec3::x(),
    );
    drag_shell(
        c,
        "warm_drag_1cm/shell_n30_bspline_axial",
        "bspline",
        Vec3::x(),
    );
    drag(c, "warm_drag_1cm/n100_two_clamps", &[]);
    drag(
        c,
        "warm_drag_1cm/n100_two_clamps_three_clips",
        &[25, 50, 75],
    );
}

criterion_group! {
    name = session;
    config = Criterion::default()
        .sample_size(30)
        .measurement_time(Duration::from_secs(5));
    targets = benches
}
criterion_main!(session);
