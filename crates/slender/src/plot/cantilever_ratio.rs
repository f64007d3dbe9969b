//! Tip-displacement ratio Δy/Δx of the cantilever under self-weight against
//! the gravito-bending parameter Γ (counterpart of the seed's Fig. 2).

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    builder, draw_curves, draw_frame, draw_legend, draw_lines, draw_mesh, draw_no_data_note,
    drawable_runs, extent, label_areas, occupied_fractions, padded_range, render, style,
    titled_area, Axis, Figure, LegendEntry, Sample, Scale, SeriesStyle, TextFix,
};

/// One data series of a figure.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Data points `(x, y)`. Points that cannot be drawn (non-finite, or
    /// non-positive on a log axis) are skipped and break the line.
    pub points: Vec<(f64, f64)>,
    /// Draw a dashed line instead of a solid one.
    pub dashed: bool,
    /// Mark every data point (e.g. individual runs, or element vertices).
    pub markers: bool,
}

/// Axis description of Γ, shared with the relative-error plot.
pub(super) const GAMMA_DESC: &str = "gravito-bending parameter Γ";

/// Legend text of the shaded Γ band.
pub(super) fn band_label((a, b): (f64, f64)) -> String {
    format!(
        "cable range Γ ∈ [{}, {}]",
        style::format_number(a.min(b)),
        style::format_number(a.max(b))
    )
}

/// Log–log plot of Δy/Δx against Γ: the master curve of the heavy elastica
/// as a thick orange line, each of `curves` on top of it, and optionally the
/// band `Γ ∈ [a, b]` shaded.
///
/// Writes `<stem>.png` and `<stem>.svg` (creating the parent directory if
/// needed). Axis ranges follow the drawable data.
pub fn plot_cantilever_ratio(
    stem: &Path,
    title: &str,
    master: &[(f64, f64)],
    curves: &[Curve],
    band: Option<(f64, f64)>,
) -> Result<()> {
    render(
        stem,
        &RatioFigure {
            title,
            master,
            curves,
            band,
        },
    )
}

struct RatioFigure<'a> {
    title: &'a str,
    master: &'a [(f64, f64)],
    curves: &'a [Curve],
    band: Option<(f64, f64)>,
}

impl Figure for RatioFigure<'_> {
    fn size(&self) -> (u32, u32) {
        style::WIDE_CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let master = drawable_runs(self.master, Scale::Log, Scale::Log);
        let curves: Vec<_> = self
            .curves
            .iter()
            .map(|c| drawable_runs(&c.points, Scale::Log, Scale::Log))
            .collect();
        let all_runs: Vec<Vec<(f64, f64)>> = master
            .iter()
            .chain(curves.iter().flatten())
            .cloned()
            .collect();
        let all_points = || all_runs.iter().flatten();

        let x = Axis::new(
            Scale::Log,
            padded_range(extent(all_points().map(|p| p.0)), Scale::Log, 0.03),
            GAMMA_DESC,
        );
        let y = Axis::new(
            Scale::Log,
            padded_range(extent(all_points().map(|p| p.1)), Scale::Log, 0.05),
            "Δy/Δx",
        );

        let area = titled_area(root, self.title)?;
        let mut chart =
            builder(&area, label_areas(&area, &x, &y)?).build_cartesian_2d(x.coord(), y.coord())?;

        // The band goes first so that grid and data are drawn over it.
        let band = self.band.and_then(|(a, b)| x.clamp(a, b));
        if let Some((a, b)) = band {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, y.lo), (b, y.hi)],
                style::BAND_FILL.filled(),
            )))?;
        }
        draw_mesh(&mut chart, &x, &y, fix)?;

        let master_style = SeriesStyle {
            color: style::MASTER_ORANGE,
            width: style::MASTER_WIDTH,
            dashed: false,
            marker: None,
        };
        draw_lines(&mut chart, &master, &master_style)?;
        let styles = draw_curves(&mut chart, self.curves, &curves)?;
        draw_frame(&area, &chart, &x, &y)?;
        if all_runs.is_empty() {
            draw_no_data_note(&chart, fix)?;
        }

        // Legend order: reference, data, context.
        let mut legend = Vec::new();
        if !self.master.is_empty() {
            legend.push(LegendEntry::line(
                "master curve (heavy elastica)",
                master_style,
            ));
        }
        legend.extend(
            self.curves
                .iter()
                .zip(styles)
                .map(|(c, st)| LegendEntry::line(&c.label, st)),
        );
        if let (Some(original), Some(_)) = (self.band, band) {
            legend.push(LegendEntry {
                label: band_label(original),
                sample: Sample::Band,
            });
        }
        draw_legend(&chart, &legend, &occupied_fractions(&all_runs, &x, &y), fix)?;
        Ok(())
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    /// A smooth stand-in for the heavy-elastica master curve: Γ/8 for small
    /// Γ (linear beam theory), growing like √Γ for large Γ.
    pub fn synthetic_master() -> Vec<(f64, f64)> {
        (0..=120)
            .map(|i| {
                let g = 10f64.powf(-2.0 + 6.0 * f64::from(i) / 120.0);
                (g, g / 8.0 / (1.0 + g / 30.0).sqrt())
            })
            .collect()
    }

    /// Master curve sampled at a few Γ with a relative error that grows with
    /// Γ, like a coarse discretisation would.
    pub fn synthetic_curves() -> Vec<Curve> {
        let master = synthetic_master();
        let mk = |label: &str, n: f64, dashed: bool, markers: bool| Curve {
            label: label.to_string(),
            points: master
                .iter()
                .step_by(10)
                .map(|&(g, r)| (g, r * (1.0 - g.sqrt() / (n * n * 40.0))))
                .collect(),
            dashed,
            markers,
        };
        vec![
            mk("discrete elastic rod, N = 4", 4.0, false, true),
            mk("discrete elastic rod, N = 16", 16.0, false, true),
            mk("Cosserat FEM, 8 elements", 3.0, true, true),
            mk("shell model (ribbon)", 2.0, true, false),
        ]
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("ratio");
        let stem = dir.join("cantilever_ratio");
        let title = "Cantilever under self-weight: Δy/Δx vs Γ";
        plot_cantilever_ratio(
            &stem,
            title,
            &synthetic_master(),
            &synthetic_curves(),
            Some((10.0, 1000.0)),
        )
        .expect("plot renders");
        assert_rendered(&stem, title);
    }

    #[test]
    fn skips_undrawable_points() {
        let dir = fresh_dir("ratio-nonfinite");
        let stem = dir.join("ratio_nonfinite");
        let mut master = synthetic_master();
        master[5].1 = f64::NAN;
        master[6].0 = f64::INFINITY;
        master[7].1 = 0.0;
        let curves = vec![
            Curve {
                label: "holes".into(),
                points: vec![
                    (0.1, 0.01),
                    (1.0, f64::NAN),
                    (10.0, -1.0),
                    (100.0, 2.0),
                    (1000.0, 5.0),
                    (f64::NEG_INFINITY, 1.0),
                ],
                dashed: false,
                markers: true,
            },
            Curve {
                label: "nothing drawable".into(),
                points: vec![(f64::NAN, f64::NAN), (0.0, 1.0), (1.0, -2.0)],
                dashed: true,
                markers: true,
            },
        ];
        plot_cantilever_ratio(&stem, "non-finite data", &master, &curves, Some((1e5, 1e9)))
            .expect("non-finite data is skipped");
        assert_rendered(&stem, "non-finite data");

        // Nothing drawable at all still gives a (empty) figure, not an error.
        let stem = dir.join("ratio_empty");
        plot_cantilever_ratio(&stem, "empty", &[], &curves[1..], None).expect("empty plot");
        assert_rendered(&stem, "empty");
    }
}
