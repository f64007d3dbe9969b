//! A warm re-solve of the incremental API allocates nothing (issue: "nothing is allocated per
//! re-solve"): the allocations of whole support drags are counted by a global allocator that
//! counts per thread (the tests of this file run side by side), after two warm-up drags that
//! size every buffer. The one allocation an edit may make is its report's list of re-solved
//! structures ([`EditReport::structures`](slender_core::scene::EditReport)), returned to the
//! caller.
//!
//! Shell strips are not covered: a drag of a mid-edge strip still allocates nine times (the
//! both-ends first guess's short vectors, and the report), a B-spline strip's 36 times (also
//! its step cap and a buffer per assembly); their factorization, solves, spectrum slicing and
//! state copies no longer allocate.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting the allocations (and reallocations) of each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: every call is forwarded to the system allocator unchanged; the counter is a
// const-initialized thread-local without a destructor, so touching it never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

fn allocations() -> usize {
    ALLOCATIONS.with(|c| c.get())
}

/// A 20-element cable of `model` clamped at both ends, with three clips if `clips`, under
/// gravity.
fn cable(model: &str, clips: bool) -> Scene {
    let mut supports =
        String::from(r#"{ kind = "clamp", vertex = "start" }, { kind = "clamp", vertex = "end" }"#);
    if clips {
        for v in [5, 10, 15] {
            supports.push_str(&format!(r#", {{ kind = "clip", vertex = {v} }}"#));
        }
    }
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
model = "{model}"
elements = 20
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {supports} ]
"#
    ))
    .expect("the scene parses")
}

/// Allocations of each of `drags` warm 1 cm drags (back and forth) of the cable's end clamp,
/// after two warm-up drags.
fn drag_allocations(scene: Scene, drags: usize) -> Vec<usize> {
    let mut session = Session::new(scene).expect("the scene solves");
    let mut sign = 1.0;
    let mut counts = Vec::with_capacity(drags + 2);
    for _ in 0..drags + 2 {
        let before = allocations();
        let report = session
            .move_support_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.01 * sign, 0.0))
            .expect("a valid move");
        counts.push(allocations() - before);
        assert!(report.converged, "{report:?}");
        sign = -sign;
    }
    counts.split_off(2)
}

#[test]
fn warm_drags_of_every_rod_model_allocate_only_their_report() {
    for (model, clips) in [
        ("der", false),
        ("der", true),
        ("cosserat", false),
        ("cosserat", true),
        ("se3", false),
        ("se3", true),
    ] {
        let counts = drag_allocations(cable(model, clips), 4);
        assert!(
            counts.iter().all(|&c| c <= 1),
            "{model} (clips: {clips}): allocations per drag {counts:?}, expected at most 1 \
             (the report)"
        );
    }
}

#[test]
fn warm_gravity_changes_allocate_only_their_report() {
    for model in ["der", "cosserat", "se3"] {
        let mut session = Session::new(cable(model, true)).expect("the scene solves");
        let mut counts = Vec::with_capacity(6);
        for k in 0..6 {
            let before = allocations();
            let report = session
                .set_gravity([0.0, 0.0, -9.81 * (1.0 + 0.01 * (k % 2) as f64)])
                .expect("a valid gravity");
            counts.push(allocations() - before);
            assert!(report.converged, "{report:?}");
        }
        assert!(
            counts[2..].iter().all(|&c| c <= 1),
            "{model}: allocations per gravity change {counts:?}, expected at most 1 (the report)"
        );
    }
}

/// The counter sees allocations: without this, a counter that never counts would pass the
/// test above.
#[test]
fn the_counter_counts() {
    let before = allocations();
    let v = std::hint::black_box(vec![1.0_f64; 16]);
    assert_eq!(allocations() - before, 1);
    drop(v);
}
