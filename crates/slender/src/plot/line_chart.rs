//! A plain x–y line chart on linear or log axes, for curves that need no special decoration
//! (e.g. the lateral-buckling master curves Γ_c(w/L)).

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    builder, draw_curves, draw_frame, draw_legend, draw_mesh, draw_no_data_note, drawable_runs,
    extent, label_areas, occupied_fractions, padded_range, render, style, titled_area, Axis, Curve,
    Figure, LegendEntry, Scale, TextFix,
};

/// Axes of a line chart.
#[derive(Clone, Copy, Debug)]
pub struct LineAxes<'a> {
    /// x-axis description.
    pub x_desc: &'a str,
    /// y-axis description.
    pub y_desc: &'a str,
    /// x scale.
    pub x_scale: Scale,
    /// y scale.
    pub y_scale: Scale,
}

/// Plots `curves` on `axes`; writes `<stem>.png` and `<stem>.svg`.
pub fn plot_lines(stem: &Path, title: &str, axes: LineAxes, curves: &[Curve]) -> Result<()> {
    render(
        stem,
        &LineFigure {
            title,
            axes,
            curves,
        },
    )
}

struct LineFigure<'a> {
    title: &'a str,
    axes: LineAxes<'a>,
    curves: &'a [Curve],
}

impl Figure for LineFigure<'_> {
    fn size(&self) -> (u32, u32) {
        style::WIDE_CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let a = self.axes;
        let curves: Vec<_> = self
            .curves
            .iter()
            .map(|c| drawable_runs(&c.points, a.x_scale, a.y_scale))
            .collect();
        let all_runs: Vec<Vec<(f64, f64)>> = curves.iter().flatten().cloned().collect();
        let all_points = || all_runs.iter().flatten();
        let x = Axis::new(
            a.x_scale,
            padded_range(extent(all_points().map(|p| p.0)), a.x_scale, 0.03),
            a.x_desc,
        );
        let y = Axis::new(
            a.y_scale,
            padded_range(extent(all_points().map(|p| p.1)), a.y_scale, 0.05),
            a.y_desc,
        );
        let area = titled_area(root, self.title)?;
        let mut chart =
            builder(&area, label_areas(&area, &x, &y)?).build_cartesian_2d(x.coord(), y.coord())?;
        draw_mesh(&mut chart, &x, &y, fix)?;
        let styles = draw_curves(&mut chart, self.curves, &curves)?;
        draw_frame(&area, &chart, &x, &y)?;
        if all_runs.is_empty() {
            draw_no_data_note(&chart, fix)?;
        }
        let legend: Vec<_> = self
            .curves
            .iter()
            .zip(styles)
            .map(|(c, st)| LegendEntry::line(&c.label, st))
            .collect();
        draw_legend(&chart, &legend, &occupied_fractions(&all_runs, &x, &y), fix)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    #[test]
    fn renders_png_and_svg_on_linear_and_log_axes() {
        let dir = fresh_dir("line-chart");
        let curves = vec![
            Curve {
                label: "x²".into(),
                points: (1..20).map(|i| (i as f64, (i * i) as f64)).collect(),
                dashed: false,
                markers: true,
            },
            Curve {
                label: "limit".into(),
                points: vec![(1.0, 50.0), (19.0, 50.0)],
                dashed: true,
                markers: false,
            },
        ];
        for (name, scale) in [("linear", Scale::Linear), ("log", Scale::Log)] {
            let stem = dir.join(name);
            let title = format!("line chart, {name} axes");
            let axes = LineAxes {
                x_desc: "x",
                y_desc: "y",
                x_scale: scale,
                y_scale: scale,
            };
            plot_lines(&stem, &title, axes, &curves).expect("plot renders");
            assert_rendered(&stem, &title);
        }
    }
}
