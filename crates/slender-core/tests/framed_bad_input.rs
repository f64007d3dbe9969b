//! Bad input to the Cosserat rod and the SE(3) beam gives an error naming the field, never a
//! panic: zero or non-finite shear stiffness, non-unit quaternions, degenerate elements,
//! states that do not fit the rod, and the input both share with the discrete elastic rod.

use nalgebra::Quaternion;
use slender_core::cosserat::CosseratBuilder;
use slender_core::framed::{FramedCore, ShearStiffness};
use slender_core::geometry::Vec3;
use slender_core::rod::{RestCurve, RodProperties, SectionStiffness};
use slender_core::se3::Se3Builder;
use slender_core::ModelError;

fn props() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(1e6, 1.0, 0.8),
        linear_density: 0.1,
    }
}

fn line(length: f64) -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length,
    }
}

fn shear() -> ShearStiffness {
    ShearStiffness::isotropic(1e5)
}

/// Builds both models from the same input, modified by `f`; both must fail naming `field`.
fn expect_both(
    field: &str,
    f: impl Fn(CosseratBuilder) -> CosseratBuilder,
    g: impl Fn(Se3Builder) -> Se3Builder,
) {
    let c = f(CosseratBuilder::new(line(1.0), props(), shear()).clamp_start())
        .build()
        .expect_err("cosserat must reject")
        .to_string();
    assert!(c.contains(field), "cosserat: `{c}` should name `{field}`");
    let s = g(Se3Builder::new(line(1.0), props(), shear()).clamp_start())
        .build()
        .expect_err("se3 must reject")
        .to_string();
    assert!(s.contains(field), "se3: `{s}` should name `{field}`");
}

#[test]
fn shear_stiffness_must_be_finite_and_positive() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        for (field, sh) in [
            ("ga1", ShearStiffness { ga1: bad, ga2: 1.0 }),
            ("ga2", ShearStiffness { ga1: 1.0, ga2: bad }),
        ] {
            let c = CosseratBuilder::new(line(1.0), props(), sh)
                .clamp_start()
                .build()
                .unwrap_err()
                .to_string();
            assert!(c.contains(field), "{c}");
            let s = Se3Builder::new(line(1.0), props(), sh)
                .clamp_start()
                .build()
                .unwrap_err()
                .to_string();
            assert!(s.contains(field), "{s}");
        }
    }
}

#[test]
fn shared_input_is_checked_with_the_field_name() {
    expect_both("n_elements", |b| b.elements(0), |b| b.elements(0));
    expect_both("pins", |b| b.pin(99), |b| b.pin(99));
    expect_both(
        "point_forces.force",
        |b| b.point_force(1, Vec3::new(f64::NAN, 0.0, 0.0)),
        |b| b.point_force(1, Vec3::new(f64::NAN, 0.0, 0.0)),
    );
    expect_both(
        "point_moments.vertex",
        |b| b.point_moment(50, Vec3::x()),
        |b| b.point_moment(50, Vec3::x()),
    );
    expect_both(
        "gravity.y",
        |b| b.gravity(Vec3::new(0.0, f64::INFINITY, 0.0)),
        |b| b.gravity(Vec3::new(0.0, f64::INFINITY, 0.0)),
    );
    expect_both(
        "first_director",
        |b| b.first_director(Vec3::x()),
        |b| b.first_director(Vec3::x()),
    );
    expect_both(
        "planar_axis",
        |b| b.planar_motion(3),
        |b| b.planar_motion(3),
    );
    expect_both(
        "node_arclengths",
        |b| b.nodes_at(vec![0.0, 0.5, 0.5, 1.0]),
        |b| b.nodes_at(vec![0.0, 0.5, 0.5, 1.0]),
    );
    expect_both(
        "natural_twist",
        |b| b.natural_twist(f64::NAN),
        |b| b.natural_twist(f64::NAN),
    );
    // No support: a rigid-body mode.
    let e = CosseratBuilder::new(line(1.0), props(), shear())
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("supports"));
    let e = Se3Builder::new(line(1.0), props(), shear())
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("supports"));
}

#[test]
fn section_stiffnesses_are_checked() {
    let mut p = props();
    p.stiffness.ei1 = 0.0;
    let e = CosseratBuilder::new(line(1.0), p, shear())
        .clamp_start()
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("ei1"));
    let e = Se3Builder::new(line(1.0), p, shear())
        .clamp_start()
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("ei1"));
    // A section whose stiffnesses imply an impossible Poisson ratio has no circular shear.
    let s = SectionStiffness::isotropic(1.0, 1.0, 0.1);
    assert!(ShearStiffness::solid_circle(&s)
        .unwrap_err()
        .to_string()
        .contains("gj"));
}

#[test]
fn degenerate_elements_are_rejected() {
    // A polyline with a repeated point gives a zero-length element.
    let curve = RestCurve::Polyline {
        points: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
    };
    let c = CosseratBuilder::new(curve.clone(), props(), shear())
        .clamp_start()
        .build();
    assert!(c.is_err());
    let s = Se3Builder::new(curve, props(), shear())
        .clamp_start()
        .build();
    assert!(s.is_err());
    // A coil meshed so coarsely that an SE(3) element would turn by π.
    let coil = RestCurve::Circle {
        start: [0.0; 3],
        tangent: [1.0, 0.0, 0.0],
        normal: [0.0, 1.0, 0.0],
        radius: 1.0 / std::f64::consts::PI,
        length: 2.0,
    };
    let e = Se3Builder::new(coil, props(), shear())
        .elements(2)
        .clamp_start()
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("n_elements"), "{e}");
}

fn state_error(
    core: &FramedCore,
    positions: Vec<Vec3>,
    frames: Vec<Quaternion<f64>>,
) -> ModelError {
    core.state_from(positions, frames)
        .expect_err("must be rejected")
}

#[test]
fn states_must_fit_the_rod_and_hold_unit_quaternions() {
    let rod = Se3Builder::new(line(1.0), props(), shear())
        .elements(3)
        .clamp_start()
        .build()
        .unwrap();
    let rest = rod.rest_state();
    let positions = rest.positions().to_vec();
    let frames: Vec<Quaternion<f64>> = rest.frames().iter().map(|q| q.into_inner()).collect();
    assert!(rod.state_from(positions.clone(), frames.clone()).is_ok());
    // A non-unit quaternion is an error, not silently normalized.
    let mut scaled = frames.clone();
    scaled[2] *= 1.001;
    let e = state_error(&rod, positions.clone(), scaled);
    assert!(
        e.to_string().contains("frames") && e.to_string().contains("norm"),
        "{e}"
    );
    let mut nan = frames.clone();
    nan[1].coords[0] = f64::NAN;
    assert!(state_error(&rod, positions.clone(), nan)
        .to_string()
        .contains("frames"));
    // Wrong counts.
    assert!(state_error(&rod, positions[..3].to_vec(), frames.clone())
        .to_string()
        .contains("positions"));
    assert!(state_error(&rod, positions.clone(), frames[..3].to_vec())
        .to_string()
        .contains("frames"));
    // A degenerate element (two coincident vertices).
    let mut collapsed = positions.clone();
    collapsed[3] = collapsed[2];
    assert!(state_error(&rod, collapsed, frames.clone())
        .to_string()
        .contains("degenerate"));
    // The clamped node must keep its pose.
    let mut moved = positions.clone();
    moved[0].y += 0.1;
    assert!(state_error(&rod, moved, frames.clone())
        .to_string()
        .contains("support"));
    let mut turned = frames.clone();
    turned[0] = (nalgebra::UnitQuaternion::from_scaled_axis(Vec3::new(0.3, 0.0, 0.0))
        * nalgebra::UnitQuaternion::new_normalize(turned[0]))
    .into_inner();
    assert!(state_error(&rod, positions, turned)
        .to_string()
        .contains("clamp"));
}

#[test]
fn load_paths_are_checked() {
    let mut rod = CosseratBuilder::new(line(1.0), props(), shear())
        .elements(4)
        .clamp_start()
        .build()
        .unwrap();
    let bad =
        slender_core::rod::RodLoadPath::support_motion(vec![slender_core::rod::SupportMotion {
            vertices: vec![3],
            pivot: Vec3::zeros(),
            rotation: Vec3::zeros(),
            translation: Vec3::x(),
        }]);
    assert!(rod
        .set_load_path(bad)
        .unwrap_err()
        .to_string()
        .contains("support_motion.vertices"));
    let bad = slender_core::rod::RodLoadPath {
        loads: [0.0, f64::NAN],
        motions: Vec::new(),
        gravity_from: None,
        force_change: None,
        follower_change: None,
        follower_moment_change: None,
        moment_change: None,
    };
    assert!(rod
        .set_load_path(bad)
        .unwrap_err()
        .to_string()
        .contains("loads[1]"));
    let bad = slender_core::rod::RodLoadPath {
        follower_change: Some((0, nalgebra::Vector3::new(0.0, 1.0, 0.0))),
        ..Default::default()
    };
    assert!(rod
        .set_load_path(bad)
        .unwrap_err()
        .to_string()
        .contains("follower_change"));
}
