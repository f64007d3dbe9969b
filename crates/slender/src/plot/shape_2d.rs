//! Deformed shapes in a plane (counterpart of the seed's Figs. 3–5), drawn
//! with equal scales on both axes so that the geometry is not distorted.

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    builder, draw_frame, draw_legend, draw_lines, draw_markers, draw_mesh, draw_no_data_note,
    drawable_runs, extent, label_areas, occupied_fractions, render, style, titled_area, Axis,
    Curve, Figure, LegendEntry, Scale, SeriesStyle, TextFix,
};

/// Plots deformed shapes `(x, y)` in a plane with an equal aspect ratio: one
/// data unit has the same pixel length on both axes.
///
/// `reference` (e.g. the exact elastica) is drawn as a thin dark dashed line
/// on top of the shapes if its `dashed` flag is set, otherwise as a grey line
/// beneath them. Shapes with `markers` show their vertices, so that coarse
/// discretisations are recognisable. Writes `<stem>.png` and `<stem>.svg`.
pub fn plot_shapes_2d(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    reference: Option<&Curve>,
    shapes: &[Curve],
) -> Result<()> {
    render(
        stem,
        &ShapeFigure {
            title,
            x_label,
            y_label,
            reference,
            shapes,
        },
    )
}

struct ShapeFigure<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    reference: Option<&'a Curve>,
    shapes: &'a [Curve],
}

/// Grey of a solid (non-dashed) reference line.
const REFERENCE_GREY: RGBColor = RGBColor(0xA0, 0xA0, 0xA0);

/// Expands the ranges `xr`, `yr` about their centres so that both axes have
/// the same data units per pixel on a plotting area of `px` pixels.
fn equal_aspect(xr: (f64, f64), yr: (f64, f64), (pw, ph): (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (pw, ph) = (f64::from(pw.max(1)), f64::from(ph.max(1)));
    let per_px = ((xr.1 - xr.0) / pw).max((yr.1 - yr.0) / ph);
    let expand = |(lo, hi): (f64, f64), px: f64| {
        let c = 0.5 * (lo + hi);
        let half = 0.5 * per_px * px;
        (c - half, c + half)
    };
    (expand(xr, pw), expand(yr, ph))
}

/// Both axes with one common tick step, so that the grid is made of squares.
fn square_axes(xr: (f64, f64), yr: (f64, f64), px: (u32, u32), desc: (&str, &str)) -> (Axis, Axis) {
    // About eight labelled ticks along the longer side.
    let long = if px.0 >= px.1 {
        xr.1 - xr.0
    } else {
        yr.1 - yr.0
    };
    let step = style::nice_step(long, 8);
    (
        Axis::with_ticks(
            Scale::Linear,
            xr,
            style::linear_ticks_with_step(xr.0, xr.1, step),
            desc.0,
        ),
        Axis::with_ticks(
            Scale::Linear,
            yr,
            style::linear_ticks_with_step(yr.0, yr.1, step),
            desc.1,
        ),
    )
}

impl Figure for ShapeFigure<'_> {
    fn size(&self) -> (u32, u32) {
        style::SHAPE_CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let reference = self
            .reference
            .map(|r| drawable_runs(&r.points, Scale::Linear, Scale::Linear))
            .unwrap_or_default();
        let shapes: Vec<_> = self
            .shapes
            .iter()
            .map(|c| drawable_runs(&c.points, Scale::Linear, Scale::Linear))
            .collect();
        let all_runs: Vec<Vec<(f64, f64)>> = reference
            .iter()
            .chain(shapes.iter().flatten())
            .cloned()
            .collect();
        let all_points = || all_runs.iter().flatten();

        // Data extents, padded by the same absolute amount on all sides (a
        // fraction of the larger span) so that a straight rod lying along
        // one axis still gets some room across it.
        let xe = extent(all_points().map(|p| p.0)).unwrap_or((0.0, 1.0));
        let ye = extent(all_points().map(|p| p.1)).unwrap_or((0.0, 1.0));
        let span = (xe.1 - xe.0).max(ye.1 - ye.0);
        let pad = if span > 0.0 {
            0.06 * span
        } else {
            0.5 * xe.0.abs().max(ye.0.abs()).max(1.0)
        };
        let xd = (xe.0 - pad, xe.1 + pad);
        let yd = (ye.0 - pad, ye.1 + pad);
        let desc = (self.x_label, self.y_label);

        let area = titled_area(root, self.title)?;

        // The plotting-area size depends on the label areas, which depend on
        // the tick labels, which depend on the ranges, which depend on the
        // plotting-area size. Two rounds settle it; the label areas only ever
        // grow, so the final ranges are computed for the final area size.
        let plot_px = |areas: (u32, u32)| -> Result<(u32, u32)> {
            let probe = builder(&area, areas).build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
            Ok(probe.plotting_area().dim_in_pixel())
        };
        let (x0, y0) = square_axes(xd, yd, area.dim_in_pixel(), desc);
        let mut areas = label_areas(&area, &x0, &y0)?;
        let mut px = plot_px(areas)?;
        for _ in 0..2 {
            let (xr, yr) = equal_aspect(xd, yd, px);
            let (xa, ya) = square_axes(xr, yr, px, desc);
            let needed = label_areas(&area, &xa, &ya)?;
            areas = (areas.0.max(needed.0), areas.1.max(needed.1));
            px = plot_px(areas)?;
        }
        let (xr, yr) = equal_aspect(xd, yd, px);
        let (x, y) = square_axes(xr, yr, px, desc);

        let mut chart = builder(&area, areas).build_cartesian_2d(x.coord(), y.coord())?;
        draw_mesh(&mut chart, &x, &y, fix)?;

        let ref_style = self.reference.map(|r| SeriesStyle {
            color: if r.dashed {
                style::REFERENCE
            } else {
                REFERENCE_GREY
            },
            width: if r.dashed { 2 } else { 4 },
            dashed: r.dashed,
            marker: r.markers.then_some(style::MarkerShape::Circle),
        });
        let styles: Vec<_> = self
            .shapes
            .iter()
            .enumerate()
            .map(|(i, c)| SeriesStyle::for_curve(i, c))
            .collect();

        // A solid grey reference is a backdrop; a dashed one goes on top so
        // that it stays visible where a shape coincides with it.
        let ref_on_top = ref_style.is_some_and(|s| s.dashed);
        if let (Some(st), false) = (&ref_style, ref_on_top) {
            draw_lines(&mut chart, &reference, st)?;
        }
        for (runs, st) in shapes.iter().zip(&styles) {
            draw_lines(&mut chart, runs, st)?;
        }
        if let (Some(st), true) = (&ref_style, ref_on_top) {
            draw_lines(&mut chart, &reference, st)?;
        }
        if let Some(st) = &ref_style {
            draw_markers(&chart, &reference, st)?;
        }
        for (runs, st) in shapes.iter().zip(&styles) {
            draw_markers(&chart, runs, st)?;
        }
        draw_frame(&area, &chart, &x, &y)?;
        if all_runs.is_empty() {
            draw_no_data_note(&chart, fix)?;
        }

        let mut legend = Vec::new();
        if let (Some(r), Some(st)) = (self.reference, ref_style) {
            legend.push(LegendEntry::line(&r.label, st));
        }
        legend.extend(
            self.shapes
                .iter()
                .zip(styles)
                .map(|(c, st)| LegendEntry::line(&c.label, st)),
        );
        draw_legend(&chart, &legend, &occupied_fractions(&all_runs, &x, &y), fix)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    /// A cantilever-like shape clamped horizontally at the origin and
    /// bending down to a tip angle of `tip` (rad), sampled at `n + 1`
    /// vertices: θ(s) = −tip·(1 − (1 − s)³), integrated with the midpoint
    /// rule on a fine grid.
    fn hanging_shape(tip: f64, n: usize) -> Vec<(f64, f64)> {
        let fine = 2000;
        let mut pts = vec![(0.0, 0.0)];
        let (mut x, mut y) = (0.0, 0.0);
        for k in 0..fine {
            let s = (k as f64 + 0.5) / fine as f64;
            let th = -tip * (1.0 - (1.0 - s).powi(3));
            x += th.cos() / fine as f64;
            y += th.sin() / fine as f64;
            if (k + 1) % (fine / n) == 0 {
                pts.push((x, y));
            }
        }
        pts
    }

    #[test]
    fn equal_aspect_gives_equal_scales() {
        let (xr, yr) = equal_aspect((0.0, 1.0), (-1.0, 0.0), (800, 400));
        let sx = (xr.1 - xr.0) / 800.0;
        let sy = (yr.1 - yr.0) / 400.0;
        assert!((sx - sy).abs() < 1e-12);
        assert!(xr.0 <= 0.0 && xr.1 >= 1.0 && yr.0 <= -1.0 && yr.1 >= 0.0);
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("shape");
        let stem = dir.join("shapes");
        let title = "Deformed cantilever, Γ = 100 (θ_tip ≈ 1.2 rad)";
        let reference = Curve {
            label: "exact (heavy elastica)".into(),
            points: hanging_shape(1.2, 200),
            dashed: true,
            markers: false,
        };
        let shapes = vec![
            Curve {
                label: "2 elements".into(),
                points: hanging_shape(1.0, 2),
                dashed: false,
                markers: true,
            },
            Curve {
                label: "4 elements".into(),
                points: hanging_shape(1.12, 4),
                dashed: false,
                markers: true,
            },
            Curve {
                label: "16 elements".into(),
                points: hanging_shape(1.19, 16),
                dashed: false,
                markers: true,
            },
        ];
        plot_shapes_2d(&stem, title, "x / L", "y / L", Some(&reference), &shapes)
            .expect("plot renders");
        assert_rendered(&stem, title);
    }

    #[test]
    fn skips_undrawable_points_and_handles_degenerate_data() {
        let dir = fresh_dir("shape-nonfinite");
        let stem = dir.join("shape_nonfinite");
        let shapes = vec![Curve {
            label: "holes".into(),
            points: vec![
                (0.0, 0.0),
                (0.5, f64::NAN),
                (1.0, -0.2),
                (f64::INFINITY, 0.0),
            ],
            dashed: true,
            markers: true,
        }];
        plot_shapes_2d(&stem, "shape with holes", "x", "y", None, &shapes)
            .expect("non-finite data is skipped");
        assert_rendered(&stem, "shape with holes");

        // A straight horizontal rod (zero height) and a single point.
        let stem = dir.join("shape_straight");
        let straight = vec![Curve {
            label: "straight".into(),
            points: vec![(0.0, 0.0), (1.0, 0.0)],
            dashed: false,
            markers: true,
        }];
        plot_shapes_2d(&stem, "straight rod", "x", "z", None, &straight).expect("straight");
        assert_rendered(&stem, "straight rod");
        let stem = dir.join("shape_point");
        let point = vec![Curve {
            label: "point".into(),
            points: vec![(2.0, 3.0)],
            dashed: false,
            markers: true,
        }];
        plot_shapes_2d(&stem, "single point", "x", "z", None, &point).expect("point");
        assert_rendered(&stem, "single point");
    }
}
