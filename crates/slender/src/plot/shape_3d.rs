//! Three-dimensional shapes (a buckled rod, a cable) as three orthographic
//! views side by side, all at one scale with equal aspect ratios, plus an
//! isometric view for the overall impression.

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::height_map::{draw_key, key_layout, KeyEntry, KeyGlyph};
use super::{
    builder, draw_frame, draw_lines, draw_markers, draw_mesh, draw_no_data_note, extent,
    label_areas, render, style, text_size, titled_area, Axis, Figure, Scale, SeriesStyle, TextFix,
};

/// A polyline in space.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Polyline3 {
    /// Legend text (an empty label leaves the shape out of the key).
    pub label: String,
    /// Vertices `[x, y, z]`. A vertex with a non-finite coordinate breaks
    /// the line.
    pub points: Vec<[f64; 3]>,
    /// Mark every vertex (e.g. the nodes of a discretisation).
    pub markers: bool,
}

/// Canvas size: four panels in a row, the key below.
const CANVAS: (u32, u32) = (1800, 720);

/// The orthographic views: panel title and the coordinates shown
/// horizontally and vertically.
const VIEWS: [(&str, usize, usize); 3] = [
    ("top (x–y)", 0, 1),
    ("front (x–z)", 0, 2),
    ("side (y–z)", 1, 2),
];
const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// Colour of the bounding box and frame of the isometric view.
const BOX_GREY: RGBColor = RGBColor(0xB8, 0xB8, 0xB8);

/// Plots `shapes` in three orthographic views side by side — top (x–y),
/// front (x–z) and side (y–z) — each with an equal aspect ratio and all at
/// the same scale, so that lengths compare across panels; a fourth panel
/// shows an isometric view (x to the lower left, y to the lower right, z
/// up) inside the bounding box of the data. A shared key below names the
/// shapes. Writes `<stem>.png` and `<stem>.svg`.
pub fn plot_shape_views(stem: &Path, title: &str, shapes: &[Polyline3]) -> Result<()> {
    render(stem, &ShapeViews { title, shapes })
}

struct ShapeViews<'a> {
    title: &'a str,
    shapes: &'a [Polyline3],
}

/// Splits a polyline into runs of drawable vertices.
fn runs3(points: &[[f64; 3]]) -> Vec<Vec<[f64; 3]>> {
    let mut runs = Vec::new();
    let mut run = Vec::new();
    for p in points {
        if p.iter().all(|c| c.is_finite()) {
            run.push(*p);
        } else if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// Projects runs with `f`.
fn project(runs: &[Vec<[f64; 3]>], f: impl Fn(&[f64; 3]) -> (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    runs.iter().map(|r| r.iter().map(&f).collect()).collect()
}

/// Isometric projection: viewed from the direction (1, 1, 1), z up.
fn isometric(p: &[f64; 3]) -> (f64, f64) {
    let s2 = std::f64::consts::SQRT_2;
    let s6 = 6f64.sqrt();
    ((p[1] - p[0]) / s2, (2.0 * p[2] - p[0] - p[1]) / s6)
}

/// Expands `(lo, hi)` about its centre to `span`.
fn centred((lo, hi): (f64, f64), span: f64) -> (f64, f64) {
    let c = 0.5 * (lo + hi);
    (c - 0.5 * span, c + 0.5 * span)
}

/// Data ranges `(lo, hi)` per coordinate, padded by the same absolute amount
/// on all sides so that a flat shape still gets room across it.
fn padded_box(runs: &[Vec<[f64; 3]>]) -> [(f64, f64); 3] {
    let ext: Vec<(f64, f64)> = (0..3)
        .map(|k| extent(runs.iter().flatten().map(|p| p[k])).unwrap_or((0.0, 1.0)))
        .collect();
    let span = ext.iter().map(|e| e.1 - e.0).fold(0.0, f64::max);
    let pad = if span > 0.0 {
        0.06 * span
    } else {
        0.5 * ext.iter().map(|e| e.0.abs()).fold(1.0, f64::max)
    };
    [0, 1, 2].map(|k| (ext[k].0 - pad, ext[k].1 + pad))
}

/// Smallest width of a plotting area, in pixels: a view of a flat shape
/// still gets room for a few tick labels.
const MIN_PLOT_W: f64 = 130.0;

/// Horizontal placement of the four panels at one common scale.
#[derive(Debug, Clone, PartialEq)]
struct RowLayout {
    /// Pixels per data unit, in every panel.
    scale: f64,
    /// Right edges of the first three panels (split points of the row).
    breaks: [i32; 3],
}

/// Places panels whose plotting areas must show `spans[i] = (horizontal,
/// vertical)` data extents at one scale, side by side in `width` pixels.
/// `overhead[i]` is the width of panel `i` outside its plotting area,
/// `plot_h` the height of every plotting area. The scale is the largest that
/// fits both the height and the total width (narrow views widened to
/// [`MIN_PLOT_W`]); spare width is shared out evenly.
fn row_layout(spans: &[(f64, f64); 4], overhead: &[f64; 4], width: f64, plot_h: f64) -> RowLayout {
    let avail = (width - overhead.iter().sum::<f64>()).max(4.0);
    let total = |s: f64| -> f64 { spans.iter().map(|sp| (s * sp.0).max(MIN_PLOT_W)).sum() };
    let tallest = spans.iter().map(|sp| sp.1).fold(0.0, f64::max);
    let mut scale = plot_h.max(1.0) / tallest;
    if total(scale) > avail {
        // `total` is monotonic in the scale: bisect for the widest fit.
        let (mut lo, mut hi) = (0.0, scale);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if total(mid) > avail {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        scale = lo.max(f64::MIN_POSITIVE);
    }
    let spare = ((avail - total(scale)) / 4.0).max(0.0);
    let mut x = 0.0;
    let mut breaks = [0; 3];
    for (i, b) in breaks.iter_mut().enumerate() {
        x += (scale * spans[i].0).max(MIN_PLOT_W) + spare + overhead[i];
        *b = x.round() as i32;
    }
    RowLayout { scale, breaks }
}

impl Figure for ShapeViews<'_> {
    fn size(&self) -> (u32, u32) {
        CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let runs: Vec<_> = self.shapes.iter().map(|s| runs3(&s.points)).collect();
        let all: Vec<Vec<[f64; 3]>> = runs.iter().flatten().cloned().collect();
        let has_data = !all.is_empty();
        let bounds = padded_box(&all);
        let styles: Vec<SeriesStyle> = self
            .shapes
            .iter()
            .enumerate()
            .map(|(i, s)| SeriesStyle {
                color: style::series_color(i),
                width: style::CURVE_WIDTH,
                dashed: false,
                marker: s.markers.then(|| style::series_marker(i)),
            })
            .collect();

        let area = titled_area(root, self.title)?;
        let (w, h) = area.dim_in_pixel();
        let entries: Vec<KeyEntry> = self
            .shapes
            .iter()
            .zip(&styles)
            .filter(|(s, _)| !s.label.is_empty())
            .map(|(s, &st)| KeyEntry::new(&s.label, KeyGlyph::Line(st)))
            .collect();
        let key = key_layout(&area, &entries, w as i32 - 2 * style::MARGIN as i32)?;
        let key_strip = key.map_or(0, |k| k.h + style::MARGIN as i32);
        let (upper, lower) = area.split_vertically((h as i32 - key_strip).max(1));

        // Panel titles get a strip of their own above the panels.
        let (_, desc_h) = text_size(&upper, "Δ", style::AXIS_DESC_SIZE)?;
        let title_h = desc_h as i32 + 8;
        let (title_strip, body) = upper.split_vertically(title_h);
        let (_, body_h) = body.dim_in_pixel();

        // Extents of the four views: three orthographic, one isometric.
        let span = |k: usize| bounds[k].1 - bounds[k].0;
        let corners: Vec<(f64, f64)> = (0..8).map(|i| isometric(&box_corner(&bounds, i))).collect();
        // The box drawn with a little room around it.
        let widen = |(lo, hi): (f64, f64)| centred((lo, hi), 1.04 * (hi - lo));
        let ue = widen(extent(corners.iter().map(|c| c.0)).unwrap_or((0.0, 1.0)));
        let ve = widen(extent(corners.iter().map(|c| c.1)).unwrap_or((0.0, 1.0)));
        let spans = [
            (span(VIEWS[0].1), span(VIEWS[0].2)),
            (span(VIEWS[1].1), span(VIEWS[1].2)),
            (span(VIEWS[2].1), span(VIEWS[2].2)),
            (ue.1 - ue.0, ve.1 - ve.0),
        ];

        // The label areas depend on the tick labels, which depend on the
        // ranges, which depend on the layout, which depends on the label
        // areas. The label areas only grow, so a few rounds settle it.
        let margins = f64::from(style::MARGIN + style::MARGIN_RIGHT);
        let layout_for = |(x_area, y_area): (u32, u32)| {
            let ortho = margins + f64::from(y_area);
            let plot_h = f64::from(body_h) - f64::from(2 * style::MARGIN + x_area);
            let layout = row_layout(
                &spans,
                &[ortho, ortho, ortho, f64::from(2 * style::MARGIN)],
                f64::from(w),
                plot_h,
            );
            // A labelled tick every 70 px or so (nice_step rounds the step up).
            let target = ((plot_h / 70.0).round() as usize).clamp(3, 10);
            let step = style::nice_step(plot_h / layout.scale, target);
            (layout, step)
        };
        let axes_for = |panels: &[DrawingArea<DB, Shift>],
                        areas: (u32, u32),
                        layout: &RowLayout,
                        step: (f64, usize)|
         -> Result<Vec<(Axis, Axis)>> {
            let mut axes = Vec::with_capacity(3);
            for (panel, &(_, a, b)) in panels.iter().zip(&VIEWS) {
                let probe = builder(panel, areas).build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
                let (pw, ph) = probe.plotting_area().dim_in_pixel();
                let axis = |k: usize, px: u32| {
                    let r = centred(bounds[k], f64::from(px.max(1)) / layout.scale);
                    let ticks = style::linear_ticks_with_step(r.0, r.1, step);
                    Axis::with_ticks(Scale::Linear, r, ticks, AXIS_NAMES[k])
                };
                axes.push((axis(a, pw), axis(b, ph)));
            }
            Ok(axes)
        };
        let split = |layout: &RowLayout| body.split_by_breakpoints(layout.breaks, [] as [i32; 0]);
        let mut areas = (0, 0);
        for _ in 0..3 {
            let (layout, step) = layout_for(areas);
            let panels = split(&layout);
            for (panel, (xa, ya)) in panels.iter().zip(axes_for(&panels, areas, &layout, step)?) {
                let needed = label_areas(panel, &xa, &ya)?;
                areas = (areas.0.max(needed.0), areas.1.max(needed.1));
            }
        }
        let (layout, step) = layout_for(areas);
        let panels = split(&layout);
        let axes = axes_for(&panels, areas, &layout, step)?;

        let title_font = (style::FAMILY, style::AXIS_DESC_SIZE)
            .into_font()
            .color(&style::AXIS)
            .pos(Pos::new(HPos::Center, VPos::Top));
        let (strip_x, _) = title_strip.get_base_pixel();
        let panel_title = |name: &str, plot: (i32, u32)| -> Result<()> {
            let centre = plot.0 - strip_x + plot.1 as i32 / 2;
            title_strip.draw(&Text::new(name, (centre, 2), title_font.clone()))?;
            Ok(())
        };

        for ((panel, (x, y)), &(name, h_k, v_k)) in panels.iter().zip(&axes).zip(&VIEWS) {
            let mut chart = builder(panel, areas).build_cartesian_2d(x.coord(), y.coord())?;
            draw_mesh(&mut chart, x, y, fix)?;
            let views: Vec<_> = runs
                .iter()
                .map(|r| project(r, |p| (p[h_k], p[v_k])))
                .collect();
            for (r, st) in views.iter().zip(&styles) {
                draw_lines(&mut chart, r, st)?;
            }
            for (r, st) in views.iter().zip(&styles) {
                draw_markers(&chart, r, st)?;
            }
            draw_frame(panel, &chart, x, y)?;
            if !has_data {
                draw_no_data_note(&chart, fix)?;
            }
            let plot = chart.plotting_area();
            panel_title(name, (plot.get_base_pixel().0, plot.dim_in_pixel().0))?;
        }

        let iso = Isometric {
            runs: &runs,
            styles: &styles,
            corners: &corners,
            extent: (ue, ve),
            scale: layout.scale,
            bottom: style::MARGIN + areas.0,
            has_data,
        };
        let plot = iso.draw(&panels[3], fix)?;
        panel_title("isometric", plot)?;

        if let Some(k) = key {
            let x0 = ((w as i32 - k.w) / 2).max(0);
            draw_key(&lower, &entries, &k, (x0, 0), fix)?;
        }
        Ok(())
    }
}

/// Corner `i` (bit 0: x, bit 1: y, bit 2: z at its maximum) of a box.
fn box_corner(bounds: &[(f64, f64); 3], i: usize) -> [f64; 3] {
    [0, 1, 2].map(|k| {
        if i & (1 << k) == 0 {
            bounds[k].0
        } else {
            bounds[k].1
        }
    })
}

/// The isometric panel: the shapes inside the (padded) bounding box of the
/// data, hidden box edges dashed, and an axis triad below.
struct Isometric<'a> {
    runs: &'a [Vec<Vec<[f64; 3]>>],
    styles: &'a [SeriesStyle],
    /// Projected corners of the bounding box, indexed as in [`box_corner`].
    corners: &'a [(f64, f64)],
    /// Projected extent of the box.
    extent: ((f64, f64), (f64, f64)),
    /// Pixels per data unit.
    scale: f64,
    /// Space below the plotting area (the triad goes there).
    bottom: u32,
    has_data: bool,
}

impl Isometric<'_> {
    /// Draws the panel; returns the plotting area's left edge (absolute)
    /// and width, for the panel title.
    fn draw<DB>(&self, area: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<(i32, u32)>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let build = |u: (f64, f64), v: (f64, f64)| {
            ChartBuilder::on(area)
                .margin(style::MARGIN)
                .margin_bottom(self.bottom)
                .build_cartesian_2d(u.0..u.1, v.0..v.1)
        };
        let probe = build((0.0, 1.0), (0.0, 1.0))?;
        let (pw, ph) = probe.plotting_area().dim_in_pixel();
        let ur = centred(self.extent.0, f64::from(pw.max(1)) / self.scale);
        let vr = centred(self.extent.1, f64::from(ph.max(1)) / self.scale);
        let mut chart = build(ur, vr)?;

        // Bounding box: the edges at the corner farthest from the viewer
        // (all minima, corner 0) are hidden and drawn dashed.
        let thin = BOX_GREY.stroke_width(1);
        for i in 0..8usize {
            for bit in [1usize, 2, 4] {
                let j = i | bit;
                if j == i {
                    continue;
                }
                let seg = vec![self.corners[i], self.corners[j]];
                if i == 0 {
                    chart.draw_series(std::iter::once(DashedPathElement::new(seg, 6, 5, thin)))?;
                } else {
                    chart.draw_series(std::iter::once(PathElement::new(seg, thin)))?;
                }
            }
        }

        let views: Vec<_> = self.runs.iter().map(|r| project(r, isometric)).collect();
        for (r, st) in views.iter().zip(self.styles) {
            draw_lines(&mut chart, r, st)?;
        }
        for (r, st) in views.iter().zip(self.styles) {
            draw_markers(&chart, r, st)?;
        }
        if !self.has_data {
            draw_no_data_note(&chart, fix)?;
        }

        // Axis triad below the plotting area, in the panel's pixel space.
        let (ax, ay) = area.get_base_pixel();
        let (px, py) = chart.plotting_area().get_base_pixel();
        let origin = (
            px - ax + 36,
            py - ay + ph as i32 + self.bottom as i32 / 2 - 6,
        );
        let len = 30.0;
        let font = (style::FAMILY, style::TICK_LABEL_SIZE)
            .into_font()
            .color(&style::AXIS)
            .pos(Pos::new(HPos::Center, VPos::Center));
        let stroke = style::AXIS.stroke_width(2);
        for (k, name) in AXIS_NAMES.iter().enumerate() {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            let (u, v) = isometric(&e);
            let at = |f: f64| {
                (
                    origin.0 + (f * len * u).round() as i32,
                    origin.1 - (f * len * v).round() as i32,
                )
            };
            area.draw(&PathElement::new(vec![origin, at(1.0)], stroke))?;
            let (lx, ly) = at(1.5);
            area.draw(&Text::new(
                *name,
                (lx, ly + fix.center_shift(style::TICK_LABEL_SIZE)),
                font.clone(),
            ))?;
        }
        Ok((px, pw))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    /// A naturally curved rod that has buckled out of plane: a ring of
    /// radius `r` lying in the x–z plane, twisted by `amp` out of it.
    fn buckled_ring(r: f64, amp: f64, n: usize) -> Vec<[f64; 3]> {
        (0..=n)
            .map(|i| {
                let t = std::f64::consts::PI * 1.6 * i as f64 / n as f64;
                [
                    r * t.sin(),
                    amp * (t / 2.0).sin().powi(2),
                    -r * (1.0 - t.cos()),
                ]
            })
            .collect()
    }

    #[test]
    fn isometric_axes() {
        let (u, v) = isometric(&[0.0, 0.0, 1.0]);
        assert!(u.abs() < 1e-12 && v > 0.0);
        let (ux, vx) = isometric(&[1.0, 0.0, 0.0]);
        let (uy, vy) = isometric(&[0.0, 1.0, 0.0]);
        assert!(ux < 0.0 && uy > 0.0 && (vx - vy).abs() < 1e-12 && vx < 0.0);
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("shape3d");
        let stem = dir.join("shape_views");
        let title = "Bend–twist: buckled rod, X = 10, Y = 0.5";
        let shapes = vec![
            Polyline3 {
                label: "planar (unstable) equilibrium".into(),
                points: buckled_ring(0.3, 0.0, 80),
                markers: false,
            },
            Polyline3 {
                label: "3-D equilibrium, 12 elements".into(),
                points: buckled_ring(0.3, 0.25, 12),
                markers: true,
            },
            Polyline3 {
                label: "3-D equilibrium, 96 elements".into(),
                points: buckled_ring(0.3, 0.27, 96),
                markers: false,
            },
        ];
        plot_shape_views(&stem, title, &shapes).expect("plot renders");
        assert_rendered(&stem, title);
    }

    #[test]
    fn degenerate_shapes() {
        let dir = fresh_dir("shape3d-degenerate");
        let stem = dir.join("shape_views_nan");
        let mut pts = buckled_ring(1.0, 0.5, 30);
        pts[5][1] = f64::NAN;
        pts[9][2] = f64::INFINITY;
        let shapes = vec![
            Polyline3 {
                label: "with holes".into(),
                points: pts,
                markers: true,
            },
            Polyline3 {
                label: "nothing drawable".into(),
                points: vec![[f64::NAN, 0.0, 0.0]],
                markers: true,
            },
        ];
        plot_shape_views(&stem, "shape with holes", &shapes).expect("holes are skipped");
        assert_rendered(&stem, "shape with holes");

        // A straight cable along x: zero extent in y and z.
        let stem = dir.join("shape_views_straight");
        let straight = vec![Polyline3 {
            label: "straight cable".into(),
            points: vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            markers: true,
        }];
        plot_shape_views(&stem, "straight cable", &straight).expect("straight");
        assert_rendered(&stem, "straight cable");

        // A single point, and nothing at all.
        let stem = dir.join("shape_views_point");
        let point = vec![Polyline3 {
            label: String::new(),
            points: vec![[1.0, 2.0, 3.0]],
            markers: true,
        }];
        plot_shape_views(&stem, "single point", &point).expect("point");
        assert_rendered(&stem, "single point");
        let stem = dir.join("shape_views_empty");
        plot_shape_views(&stem, "no shapes", &[]).expect("empty");
        assert_rendered(&stem, "no shapes");
    }
}
