//! Invalid shell input is rejected with an error naming the field and its valid range —
//! never a panic, never silent clamping.

use nalgebra::Vector3;
use slender_core::rod::Grading;
use slender_core::shell::{ShellBuilder, ShellProperties};
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

#[test]
fn valid_input_builds() {
    assert!(ShellBuilder::new(good()).elements(3, 1).build().is_ok());
}

#[test]
fn each_bad_property_names_its_field() {
    let cases: Vec<(&str, ShellProperties)> = vec![
        (
            "length",
            ShellProperties {
                length: 0.0,
                ..good()
            },
        ),
        (
            "length",
            ShellProperties {
                length: f64::NAN,
                ..good()
            },
        ),
        (
            "width",
            ShellProperties {
                width: -0.1,
                ..good()
            },
        ),
        (
            "width",
            ShellProperties {
                width: 0.0,
                ..good()
            },
        ),
        (
            "thickness",
            ShellProperties {
                thickness: 0.0,
                ..good()
            },
        ),
        (
            "thickness",
            ShellProperties {
                thickness: f64::INFINITY,
                ..good()
            },
        ),
        (
            "young",
            ShellProperties {
                young: -1.0,
                ..good()
            },
        ),
        (
            "young",
            ShellProperties {
                young: f64::NAN,
                ..good()
            },
        ),
        (
            "density",
            ShellProperties {
                density: 0.0,
                ..good()
            },
        ),
        (
            "poisson",
            ShellProperties {
                poisson: 0.5,
                ..good()
            },
        ),
        (
            "poisson",
            ShellProperties {
                poisson: -1.0,
                ..good()
            },
        ),
        (
            "poisson",
            ShellProperties {
                poisson: f64::NAN,
                ..good()
            },
        ),
    ];
    for (field, p) in cases {
        let err = ShellBuilder::new(p).build().expect_err(field);
        let msg = err.to_string();
        assert_eq!(field_of(err), field, "{msg}");
        assert!(msg.contains(field), "{msg}");
    }
}

#[test]
fn bad_mesh_and_loads_name_their_field() {
    let err = ShellBuilder::new(good())
        .elements(0, 2)
        .build()
        .unwrap_err();
    assert_eq!(field_of(err), "n_length");
    let err = ShellBuilder::new(good())
        .elements(4, 0)
        .build()
        .unwrap_err();
    assert_eq!(field_of(err), "n_width");
    let err = ShellBuilder::new(good())
        .grading(Grading::Power { exponent: 0.5 })
        .build()
        .unwrap_err();
    assert_eq!(field_of(err), "exponent");
    let err = ShellBuilder::new(good())
        .gravity(Vector3::new(0.0, f64::NAN, 0.0))
        .build()
        .unwrap_err();
    assert_eq!(field_of(err), "gravity.y");
}
