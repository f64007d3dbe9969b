//! The valid inputs of the master curve and their checks: `Y = L/(2πR)`, `c = GJ/EI`, `X > 0`,
//! the load `Γ`, and the integration tolerance.

use super::error::BendTwistError;
use super::types::Settings;

/// Smallest accepted `Y = L/(2πR)`.
pub const Y_MIN: f64 = 0.01;
/// Largest accepted `Y` (the cost grows like `Y^{3/2}` through `√Γ` at the upper boundary).
pub const Y_MAX: f64 = 20.0;
/// Smallest accepted torsion ratio `c = GJ/EI` (a round section has `1/(1 + ν)`).
pub const C_MIN: f64 = 0.5;
/// Largest accepted torsion ratio `c = GJ/EI`. Above 1 (twisting stiffer than bending) the
/// first instability of the loaded coil can be an in-plane snap onto a stable hanging sheet
/// (observed at `c = 2`), and the two-boundary description no longer holds.
pub const C_MAX: f64 = 1.0;
/// Largest load parameter `Γ = (2πXY)³` at which [`super::stability_function`] is evaluated.
pub const GAMMA_MAX: f64 = 1e10;

pub(super) fn check_y(y: f64) -> Result<(), BendTwistError> {
    if y.is_finite() && (Y_MIN..=Y_MAX).contains(&y) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "y",
            value: y,
            range: format!("finite and in [{Y_MIN}, {Y_MAX}]"),
        })
    }
}

pub(super) fn check_c(c: f64) -> Result<(), BendTwistError> {
    if c.is_finite() && (C_MIN..=C_MAX).contains(&c) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "c",
            value: c,
            range: format!("finite and in [{C_MIN}, {C_MAX}] (c = GJ/EI)"),
        })
    }
}

pub(super) fn check_x_positive(x: f64) -> Result<(), BendTwistError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "x",
            value: x,
            range: "finite and > 0".into(),
        })
    }
}

pub(super) fn check_settings(s: &Settings) -> Result<(), BendTwistError> {
    if s.rtol.is_finite() && (1e-13..=1e-6).contains(&s.rtol) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "rtol",
            value: s.rtol,
            range: "in [1e-13, 1e-6]".into(),
        })
    }
}
