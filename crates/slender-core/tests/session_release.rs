//! A support removed from a slack cable: the cable has far to fall, with no load path to split
//! the change, and must still settle where the scene without that support settles.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};

/// The 1 m cable of the drag benchmark (d = 6 mm, E = 1 GPa), clamped at both ends along x,
/// hanging under gravity, with a clip at mid-length when `clip`.
fn cable(clip: bool) -> Scene {
    let extra = if clip {
        r#", { kind = "clip", vertex = 50 }"#
    } else {
        ""
    };
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
elements = 100
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1e9, poisson = 0.4, density = 1400.0 }}
supports = [ {{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }}{extra} ]
"#
    ))
    .unwrap()
}

fn positions(session: &Session) -> Vec<Vec3> {
    session.results(0, None, 1.0, 1).rods[0]
        .positions
        .iter()
        .map(|p| Vec3::from(*p))
        .collect()
}

#[test]
fn a_clip_removed_from_a_slack_cable_lets_it_fall_to_the_equilibrium_without_it() {
    // The ends 0.5 m apart and the clip lifted 0.3 m: without the clip the cable drops about
    // half a metre, far more than one Newton solve's 30 iterations take it (measured: that
    // removal was refused as not converging).
    let mut session = Session::new(cable(true)).unwrap();
    for (support, by) in [
        (1, Vec3::new(-0.5, 0.0, 0.0)),
        (2, Vec3::new(-0.25, 0.0, 0.3)),
    ] {
        let r = session
            .move_support_by(0, support, Vec3::zeros(), by)
            .unwrap();
        assert!(r.converged, "{:?}", r.reason);
    }
    let released = session.remove_support(0, 2).unwrap();
    assert!(
        released.converged && released.stable,
        "{:?}",
        released.reason
    );
    let mut cold = Session::new(cable(false)).unwrap();
    let r = cold
        .move_support_by(0, 1, Vec3::zeros(), Vec3::new(-0.5, 0.0, 0.0))
        .unwrap();
    assert!(r.converged);
    let gap = positions(&session)
        .iter()
        .zip(&positions(&cold))
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!(
        "released after {} iterations: {gap:.2e} m from the cold solve",
        released.iterations
    );
    assert!(
        gap < 1e-6,
        "{gap:e} m from the cable solved without the clip"
    );
}
