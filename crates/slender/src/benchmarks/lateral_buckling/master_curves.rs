//! The lateral-buckling master curves Γ_c(w/L) (design.md §1.3; the ground truth of the
//! seed's Figs. 10–11): the Kirchhoff plate's linear buckling load and the Vlasov beam with
//! both weak-axis stiffness conventions, computed in code, written as a table and a figure,
//! and their self-checks.

use std::path::Path;

use anyhow::Result;
use serde::Serialize;
use slender_validation::cantilever::Check;
use slender_validation::lateral_buckling::master_curve::{linear_samples, master_curves};
use slender_validation::lateral_buckling::master_curve_checks;

use crate::output::write_csv;
use crate::plot::{plot_lines, Curve, LineAxes, Scale};

/// Poisson's ratio of the seed's flat cable (design.md §1.3 tables).
pub(super) const NU: f64 = 0.35;

/// One row of `master_curves.csv`.
#[derive(Serialize)]
struct Row {
    w_over_l: f64,
    gamma_c_kirchhoff_plate: f64,
    gamma_c_vlasov_beam_stiffness: f64,
    gamma_c_vlasov_plate_stiffness: f64,
}

/// Computes the curves on w/L ∈ [0.02, 1], writes `master_curves.csv` and
/// `master_curves.{png,svg}` under `out`, and returns the master-curve checks.
pub(super) fn write_and_check(out: &Path) -> Result<Vec<Check>> {
    let grid = linear_samples(0.02, 1.0, 50);
    let m = master_curves(NU, &grid)?;
    let rows: Vec<Row> = (0..grid.len())
        .map(|i| Row {
            w_over_l: grid[i],
            gamma_c_kirchhoff_plate: m.kirchhoff_plate[i],
            gamma_c_vlasov_beam_stiffness: m.vlasov_beam_stiffness[i],
            gamma_c_vlasov_plate_stiffness: m.vlasov_plate_stiffness[i],
        })
        .collect();
    write_csv(&out.join("master_curves.csv"), &rows)?;
    let curve = |label: &str, ys: &[f64], dashed: bool| Curve {
        label: label.into(),
        points: grid.iter().copied().zip(ys.iter().copied()).collect(),
        dashed,
        markers: false,
    };
    let flat = |label: String, y: f64| Curve {
        label,
        points: vec![(grid[0], y), (grid[grid.len() - 1], y)],
        dashed: true,
        markers: false,
    };
    let curves = vec![
        curve(
            "Kirchhoff plate (Ritz): the shell's ground truth",
            &m.kirchhoff_plate,
            false,
        ),
        curve(
            "Vlasov beam, B = E w h³/12",
            &m.vlasov_beam_stiffness,
            false,
        ),
        curve("Vlasov beam, B = D w", &m.vlasov_plate_stiffness, false),
        flat(
            format!(
                "plain rod (no warping), B = E w h³/12: {:.2}",
                m.narrow_strip_beam_stiffness
            ),
            m.narrow_strip_beam_stiffness,
        ),
    ];
    plot_lines(
        &out.join("master_curves"),
        &format!("Lateral buckling of a heavy clamped strip: critical Γ_shell, ν = {NU}"),
        LineAxes {
            x_desc: "aspect ratio w/L",
            y_desc: "critical Γ_shell = ρ h g L³ / D",
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
        },
        &curves,
    )?;
    Ok(master_curve_checks()?)
}
