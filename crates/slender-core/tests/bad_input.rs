//! Bad input gives an error that names the field and the valid range, never a panic.

use slender_core::geometry::Vec3;
use slender_core::rod::{
    CrossSection, Grading, Material, RestCurve, RodBuilder, RodProperties, SectionStiffness,
};
use slender_core::solver::SolverParams;

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

fn expect_err(b: RodBuilder, field: &str) {
    let err = b.build().expect_err("must be rejected").to_string();
    assert!(err.contains(field), "message `{err}` should name `{field}`");
}

#[test]
fn stiffnesses_must_be_finite_and_positive() {
    for bad in [f64::NAN, 0.0, -1.0, f64::INFINITY] {
        for field in ["ea", "ei1", "ei2", "gj"] {
            let mut p = props();
            match field {
                "ea" => p.stiffness.ea = bad,
                "ei1" => p.stiffness.ei1 = bad,
                "ei2" => p.stiffness.ei2 = bad,
                _ => p.stiffness.gj = bad,
            }
            expect_err(RodBuilder::new(line(1.0), p).clamp_start(), field);
        }
        let mut p = props();
        p.linear_density = bad;
        expect_err(
            RodBuilder::new(line(1.0), p).clamp_start(),
            "linear_density",
        );
        expect_err(RodBuilder::new(line(bad), props()).clamp_start(), "length");
    }
}

#[test]
fn element_counts_and_meshes_are_checked() {
    expect_err(
        RodBuilder::new(line(1.0), props())
            .elements(0)
            .clamp_start(),
        "n_elements",
    );
    expect_err(
        RodBuilder::new(line(1.0), props())
            .grading(Grading::Power { exponent: f64::NAN })
            .clamp_start(),
        "exponent",
    );
    expect_err(
        RodBuilder::new(line(1.0), props())
            .grading(Grading::BoundaryLayer { gamma: -3.0 })
            .clamp_start(),
        "gamma",
    );
}

#[test]
fn supports_and_loads_are_checked() {
    expect_err(RodBuilder::new(line(1.0), props()), "supports");
    expect_err(
        RodBuilder::new(line(1.0), props()).elements(4).pin(9),
        "pins",
    );
    expect_err(
        RodBuilder::new(line(1.0), props())
            .clamp_start()
            .point_force(11, Vec3::x()),
        "point_forces",
    );
    expect_err(
        RodBuilder::new(line(1.0), props())
            .clamp_start()
            .gravity(Vec3::new(0.0, f64::NAN, 0.0)),
        "gravity",
    );
    expect_err(
        RodBuilder::new(line(1.0), props())
            .clamp_start()
            .first_director(Vec3::x()),
        "first_director",
    );
}

#[test]
fn materials_and_sections_are_checked() {
    let m = Material {
        young: 1e9,
        poisson: 0.7,
        density: 1000.0,
    };
    let e = CrossSection::Circle { diameter: 1e-3 }
        .properties(&m)
        .unwrap_err();
    assert!(e.to_string().contains("poisson"), "{e}");
    let m = Material { poisson: 0.3, ..m };
    let e = CrossSection::Rectangle {
        width: 0.0,
        height: 1e-3,
    }
    .properties(&m)
    .unwrap_err();
    assert!(e.to_string().contains("width"), "{e}");
}

#[test]
fn degenerate_curves_are_rejected() {
    let c = RestCurve::Circle {
        start: [0.0; 3],
        tangent: [0.0, 0.0, 1.0],
        normal: [0.0, 0.0, 2.0],
        radius: 1.0,
        length: 1.0,
    };
    expect_err(RodBuilder::new(c, props()).clamp_start(), "normal");
}

#[test]
fn solver_parameters_are_checked() {
    let p = SolverParams {
        force_tolerance: -1.0,
        ..Default::default()
    };
    assert!(p
        .validate()
        .unwrap_err()
        .to_string()
        .contains("force_tolerance"));
    let p = SolverParams {
        initial_load_step: 2.0,
        ..Default::default()
    };
    assert!(p
        .validate()
        .unwrap_err()
        .to_string()
        .contains("initial_load_step"));
}
