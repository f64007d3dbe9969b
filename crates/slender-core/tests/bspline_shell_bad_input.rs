//! Invalid B-spline shell input is rejected with an error naming the field and its valid
//! range — never a panic, never silent clamping.

use nalgebra::Vector3;
use slender_core::bspline_shell::{
    BsplineLoadPath, BsplineShellBuilder, ClampMotion, PointLoad, StripEnd,
};
use slender_core::rod::Grading;
use slender_core::shell::{Clamp, ShellProperties};
use slender_core::ModelError;

fn good() -> ShellProperties {
    ShellProperties {
        length: 1.0,
        width: 0.1,
        thickness: 1e-3,
        young: 1e9,
        poisson: 0.3,
        density: 1000.0,
    }
}

fn field_of(err: ModelError) -> String {
    match err {
        ModelError::InvalidParameter { field, valid, .. } => {
            assert!(!valid.is_empty());
            field
        }
        ModelError::InvalidStructure { field, reason } => {
            assert!(!reason.is_empty());
            field
        }
    }
}

fn rejects(b: BsplineShellBuilder) -> String {
    field_of(b.build().expect_err("must be rejected"))
}

#[test]
fn valid_input_builds() {
    assert!(BsplineShellBuilder::new(good()).build().is_ok());
    assert!(BsplineShellBuilder::new(good())
        .degree(2)
        .elements(1, 1)
        .build()
        .is_ok());
}

#[test]
fn each_bad_value_names_its_field() {
    let with = |f: fn(&mut ShellProperties)| {
        let mut p = good();
        f(&mut p);
        BsplineShellBuilder::new(p)
    };
    assert_eq!(rejects(with(|p| p.length = 0.0)), "length");
    assert_eq!(rejects(with(|p| p.width = f64::NAN)), "width");
    assert_eq!(rejects(with(|p| p.thickness = -1.0)), "thickness");
    assert_eq!(rejects(with(|p| p.young = 0.0)), "young");
    assert_eq!(rejects(with(|p| p.density = f64::INFINITY)), "density");
    assert_eq!(rejects(with(|p| p.poisson = 0.5)), "poisson");
    let b = || BsplineShellBuilder::new(good());
    assert_eq!(rejects(b().degree(1)), "degree");
    assert_eq!(rejects(b().degree(5)), "degree");
    assert_eq!(rejects(b().elements(0, 1)), "n_length");
    assert_eq!(rejects(b().elements(3, 0)), "n_width");
    assert_eq!(
        rejects(b().gravity(Vector3::new(0.0, f64::NAN, 0.0))),
        "gravity.y"
    );
    assert_eq!(
        rejects(b().grading(Grading::Power { exponent: 0.5 })),
        "exponent"
    );
    assert_eq!(rejects(b().free(StripEnd::Start)), "clamps");
    assert_eq!(
        rejects(
            b().degree(2)
                .elements(1, 1)
                .clamp(StripEnd::End, Clamp::default())
        ),
        "n_length"
    );
    let mut bad_pose = Clamp::default();
    bad_pose.translation.x = f64::NAN;
    assert_eq!(rejects(b().clamp(StripEnd::End, bad_pose)), "clamp");
    let load = |u: f64, v: f64, f: f64| PointLoad {
        u,
        v,
        force: [0.0, f, 0.0],
    };
    assert_eq!(
        rejects(b().point_load(load(1.5, 0.0, 1.0))),
        "point_loads[0].u"
    );
    assert_eq!(
        rejects(b().point_load(load(0.5, 0.2, 1.0))),
        "point_loads[0].v"
    );
    assert_eq!(
        rejects(
            b().point_load(load(0.5, 0.0, 1.0))
                .point_load(load(0.5, 0.0, f64::NAN))
        ),
        "point_loads[1].force[1]"
    );
}

#[test]
fn bad_load_paths_and_clamp_poses_are_refused() {
    let mut shell = BsplineShellBuilder::new(good()).build().unwrap();
    let err = shell
        .set_load_path(BsplineLoadPath::clamp_motion(vec![ClampMotion::about_x(
            StripEnd::End,
            0.1,
        )]))
        .unwrap_err();
    assert_eq!(field_of(err), "clamp_motion.end");
    let mut m = ClampMotion::about_x(StripEnd::Start, 0.1);
    m.translation[2] = f64::NAN;
    let err = shell
        .set_load_path(BsplineLoadPath::clamp_motion(vec![m]))
        .unwrap_err();
    assert_eq!(field_of(err), "clamp_motion");
    let err = shell
        .set_load_path(BsplineLoadPath {
            loads: [0.0, f64::NAN],
            motions: Vec::new(),
        })
        .unwrap_err();
    assert_eq!(field_of(err), "loads[1]");
    let mut s = shell.rest_state();
    let err = shell
        .set_clamp(StripEnd::End, Clamp::default(), &mut s)
        .unwrap_err();
    assert_eq!(field_of(err), "clamp");
}
