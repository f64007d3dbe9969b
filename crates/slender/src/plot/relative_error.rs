//! Relative error (in %) of each model against Γ, on a linear scale that is
//! symmetric about zero so that over- and under-prediction read alike.

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::cantilever_ratio::{band_label, GAMMA_DESC};
use super::{
    builder, draw_curves, draw_frame, draw_legend, draw_mesh, draw_no_data_note, drawable_runs,
    extent, label_areas, occupied_fractions, padded_range, render, style, titled_area, Axis, Curve,
    Figure, LegendEntry, Sample, Scale, TextFix,
};

/// Plots relative errors in % (`curves[i].points = (Γ, error %)`) against Γ
/// on a log axis, with a zero line and the optional band `Γ ∈ [a, b]`
/// shaded.
///
/// The y range is symmetric about zero and ends on a labelled tick. Writes
/// `<stem>.png` and `<stem>.svg`.
pub fn plot_relative_error(
    stem: &Path,
    title: &str,
    curves: &[Curve],
    band: Option<(f64, f64)>,
) -> Result<()> {
    render(
        stem,
        &ErrorFigure {
            title,
            curves,
            band,
        },
    )
}

struct ErrorFigure<'a> {
    title: &'a str,
    curves: &'a [Curve],
    band: Option<(f64, f64)>,
}

/// Symmetric y axis `[-m, m]` covering `max_abs`, with `m` on a tick.
fn symmetric_axis(max_abs: Option<f64>, desc: &str) -> Axis {
    // Small headroom only: the range is rounded up to the next tick anyway.
    let m = max_abs.filter(|m| *m > 0.0).unwrap_or(1.0) * 1.03;
    // Ten intervals keep the rounding-up small (±40 stays ±40, not ±60).
    let (step, decimals) = style::nice_step(2.0 * m, 10);
    let m = (m / step).ceil() * step;
    let ticks = style::linear_ticks_with_step(-m, m, (step, decimals));
    Axis::with_ticks(Scale::Linear, (-m, m), ticks, desc)
}

impl Figure for ErrorFigure<'_> {
    fn size(&self) -> (u32, u32) {
        style::WIDE_CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let curves: Vec<_> = self
            .curves
            .iter()
            .map(|c| drawable_runs(&c.points, Scale::Log, Scale::Linear))
            .collect();
        let all_runs: Vec<Vec<(f64, f64)>> = curves.iter().flatten().cloned().collect();
        let all_points = || all_runs.iter().flatten();

        let x = Axis::new(
            Scale::Log,
            padded_range(extent(all_points().map(|p| p.0)), Scale::Log, 0.03),
            GAMMA_DESC,
        );
        let max_abs = all_points().map(|p| p.1.abs()).reduce(f64::max);
        let y = symmetric_axis(max_abs, "relative error (%)");

        let area = titled_area(root, self.title)?;
        let mut chart =
            builder(&area, label_areas(&area, &x, &y)?).build_cartesian_2d(x.coord(), y.coord())?;

        let band = self.band.and_then(|(a, b)| x.clamp(a, b));
        if let Some((a, b)) = band {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, y.lo), (b, y.hi)],
                style::BAND_FILL.filled(),
            )))?;
        }
        draw_mesh(&mut chart, &x, &y, fix)?;
        // Zero line: the target every curve should lie on.
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(x.lo, 0.0), (x.hi, 0.0)],
            style::AXIS.stroke_width(1),
        )))?;

        let styles = draw_curves(&mut chart, self.curves, &curves)?;
        draw_frame(&area, &chart, &x, &y)?;
        if all_runs.is_empty() {
            draw_no_data_note(&chart, fix)?;
        }

        let mut legend: Vec<_> = self
            .curves
            .iter()
            .zip(styles)
            .map(|(c, st)| LegendEntry::line(&c.label, st))
            .collect();
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
mod tests {
    use super::*;
    use crate::plot::cantilever_ratio::tests::{synthetic_curves, synthetic_master};
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    fn synthetic_errors() -> Vec<Curve> {
        let master = synthetic_master();
        synthetic_curves()
            .into_iter()
            .map(|c| {
                let points = c
                    .points
                    .iter()
                    .map(|&(g, r)| {
                        // Exact value at the same Γ, from the dense master.
                        let exact = master
                            .iter()
                            .min_by(|a, b| (a.0 - g).abs().total_cmp(&(b.0 - g).abs()))
                            .map_or(r, |m| m.1);
                        (g, 100.0 * (r - exact) / exact)
                    })
                    .collect();
                Curve { points, ..c }
            })
            .collect()
    }

    #[test]
    fn symmetric_axis_ends_on_ticks() {
        let y = symmetric_axis(Some(3.7), "e");
        assert!(y.lo < -3.7 && y.hi > 3.7);
        assert_eq!(y.lo, -y.hi);
        assert_eq!(y.ticks.major.last().copied(), Some(y.hi));
        let y = symmetric_axis(None, "e");
        assert!(y.hi > 0.0);
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("relerr");
        let stem = dir.join("relative_error");
        let title = "Relative error of Δy/Δx against the heavy elastica";
        let mut curves = synthetic_errors();
        // One model that overshoots, so the symmetric range is exercised.
        curves[3].points.iter_mut().for_each(|p| p.1 *= -0.6);
        plot_relative_error(&stem, title, &curves, Some((10.0, 1000.0))).expect("plot renders");
        assert_rendered(&stem, title);
    }

    #[test]
    fn skips_undrawable_points() {
        let dir = fresh_dir("relerr-nonfinite");
        let stem = dir.join("relerr_nonfinite");
        let curves = vec![Curve {
            label: "holes".into(),
            points: vec![
                (0.1, 0.5),
                (1.0, f64::NAN),
                (-10.0, 1.0),
                (100.0, f64::INFINITY),
                (1000.0, -2.0),
                (1e4, -3.0),
            ],
            dashed: false,
            markers: true,
        }];
        plot_relative_error(&stem, "errors with holes", &curves, None)
            .expect("non-finite data is skipped");
        assert_rendered(&stem, "errors with holes");
    }
}
