//! A warm re-solve of the incremental API allocates nothing (issue: "nothing is allocated per
//! re-solve"): the allocations of whole support drags are counted by a global allocator that
//! counts per thread (the tests of this file run side by side), after two warm-up drags that
//! size every buffer. An edit allocates nothing, its report included (the report's list of
//! re-solved structures is inline for up to four).

use slender_core::geometry::Vec3;
use slender_core::scene::{EditReport, Scene, Session};
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

/// Allocations of each of `edits` warm edits of a session of `scene`, after two warm-up
/// edits; edit k is `edit(session, k)` (alternating edits go back and forth).
fn edit_allocations(
    scene: Scene,
    edits: usize,
    mut edit: impl FnMut(&mut Session, usize) -> EditReport,
) -> Vec<usize> {
    let mut session = Session::new(scene).expect("the scene solves");
    let mut counts = Vec::with_capacity(edits + 2);
    for k in 0..edits + 2 {
        let before = allocations();
        let report = edit(&mut session, k);
        counts.push(allocations() - before);
        assert!(report.converged, "{report:?}");
    }
    counts.split_off(2)
}

/// +1 for even k, −1 for odd k.
fn sign(k: usize) -> f64 {
    if k.is_multiple_of(2) {
        1.0
    } else {
        -1.0
    }
}

/// Allocations of each of `drags` warm 1 cm drags (back and forth) of the cable's end clamp.
fn drag_allocations(scene: Scene, drags: usize) -> Vec<usize> {
    edit_allocations(scene, drags, |session, k| {
        session
            .move_support_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.01 * sign(k), 0.0))
            .expect("a valid move")
    })
}

#[test]
fn warm_drags_of_every_rod_model_allocate_nothing() {
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
            counts.iter().all(|&c| c == 0),
            "{model} (clips: {clips}): allocations per drag {counts:?}, expected none"
        );
    }
}

#[test]
fn warm_gravity_changes_allocate_nothing() {
    let scenes = ["der", "cosserat", "se3"]
        .map(|model| (model, cable(model, true)))
        .into_iter()
        .chain(["midedge", "bspline"].map(|model| (model, flat_cable(model))));
    for (model, scene) in scenes {
        let counts = edit_allocations(scene, 4, |session, k| {
            session
                .set_gravity([0.0, 0.0, -9.81 * (1.0 + 0.01 * (k % 2) as f64)])
                .expect("a valid gravity")
        });
        assert!(
            counts.iter().all(|&c| c == 0),
            "{model}: allocations per gravity change {counts:?}, expected none"
        );
    }
}

/// A flat cable (L = 0.3 m, w = 20 mm, h = 0.3 mm) of shell `model`, clamped at both ends
/// (the second connector moved and turned out of the strip's plane), sagging under gravity.
fn flat_cable(model: &str) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[shells]]
name = "flat_cable"
model = "{model}"
length = 0.3
width = 0.02
thickness = 0.3e-3
material = {{ young = 5.0e9, poisson = 0.0, density = 2000.0 }}
elements = 10
width_elements = 2
clamps = [
    {{ edge = "start" }},
    {{ edge = "end", offset = [-0.08, 0.04, 0.0], rotate = [0.0, 0.0, 0.6] }},
]
"#
    ))
    .expect("the scene parses")
}

#[test]
fn warm_drags_of_shell_strips_allocate_nothing() {
    for model in ["midedge", "bspline"] {
        let counts = edit_allocations(flat_cable(model), 4, |session, k| {
            session
                .move_shell_clamp_by(0, 1, Vec3::zeros(), Vec3::new(0.0, 0.002 * sign(k), 0.0))
                .expect("a valid move")
        });
        assert!(
            counts.iter().all(|&c| c == 0),
            "{model}: allocations per drag {counts:?}, expected none"
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
