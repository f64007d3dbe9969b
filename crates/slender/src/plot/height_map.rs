//! Colour map of a scalar over a log–log parameter plane (counterpart of the
//! seed's Fig. 7: a bend–twist measure over the two dimensionless groups),
//! with a colour bar and overlaid curves such as the master-curve boundaries.
//!
//! This module also holds the pieces shared with the phase diagram: the
//! [`Overlay`] curves, their clipping to the axis box, and the key (legend)
//! drawn outside the plotting area, where it cannot hide data of a plot that
//! is covered edge to edge.

use std::path::Path;

use anyhow::{bail, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;

use super::{
    builder, draw_frame, draw_lines, draw_mesh, draw_no_data_note, draw_sample, drawable_runs,
    extent, label_areas, padded_range, render, style, text_size, titled_area, Axis, Figure, Sample,
    Scale, SeriesStyle, TextFix,
};

/// A curve drawn on top of a height map or phase diagram (e.g. the
/// master-curve stability boundaries, or the cable corridor X·Y = const).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlay {
    /// Legend text; an empty label leaves the overlay out of the key (e.g.
    /// the second boundary of a corridor already named by the first).
    pub label: String,
    /// Points `(x, y)`. Points that cannot be drawn on the log axes
    /// (non-finite or ≤ 0) break the line; parts outside the axis range are
    /// clipped.
    pub points: Vec<(f64, f64)>,
    /// Draw a dashed line instead of a solid one.
    pub dashed: bool,
    /// Line colour; `None` picks one from a cycle that stands out on both
    /// the colour map and the phase backgrounds.
    pub color: Option<RGBColor>,
}

/// Canvas size of the height map (the key goes below the plot).
const CANVAS: (u32, u32) = (1200, 880);

/// Default overlay colours: dark, red, pink and blue read on the dark and
/// the light end of the colour map as well as on the pale phase colours.
const OVERLAY_COLORS: [RGBColor; 4] = [
    RGBColor(0x20, 0x20, 0x20),
    RGBColor(0xD6, 0x27, 0x28),
    RGBColor(0xF7, 0x81, 0xBF),
    RGBColor(0x00, 0x72, 0xB2),
];

/// Stroke width of overlay lines.
const OVERLAY_WIDTH: u32 = 3;

/// Fill of cells without a colour (≤ 0 on a log colour scale, or not a
/// number): a light neutral grey that appears nowhere in the colour map.
const NO_VALUE: RGBColor = RGBColor(0xC8, 0xC8, 0xC8);

/// Viridis (matplotlib's default map, perceptually uniform and readable
/// with colour-vision deficiencies and in grey-scale print) at 16 evenly
/// spaced positions; [`colormap`] interpolates linearly between them.
const VIRIDIS: [(u8, u8, u8); 16] = [
    (0x44, 0x01, 0x54),
    (0x48, 0x1A, 0x6C),
    (0x47, 0x2F, 0x7D),
    (0x41, 0x44, 0x87),
    (0x39, 0x56, 0x8C),
    (0x31, 0x68, 0x8E),
    (0x2A, 0x78, 0x8E),
    (0x23, 0x88, 0x8E),
    (0x1F, 0x98, 0x8B),
    (0x22, 0xA8, 0x84),
    (0x35, 0xB7, 0x79),
    (0x54, 0xC5, 0x68),
    (0x7A, 0xD1, 0x51),
    (0xA5, 0xDB, 0x36),
    (0xD2, 0xE2, 0x1B),
    (0xFD, 0xE7, 0x25),
];

/// Colour of the fraction `t` (0…1, clamped; NaN counts as 0) along the
/// colour map.
pub(super) fn colormap(t: f64) -> RGBColor {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let s = t * (VIRIDIS.len() - 1) as f64;
    let i = (s.floor() as usize).min(VIRIDIS.len() - 2);
    let f = s - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + f * (f64::from(q) - f64::from(p))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Plots `values[iy][ix]`, given at the log-spaced grid points
/// `(xs[ix], ys[iy])`, as a colour map on log–log axes.
///
/// Each grid point is drawn as a cell reaching half-way (in log space) to its
/// neighbours. With `log_values` the colour follows log10(value); values
/// ≤ 0 then, and non-finite values always, are drawn in a neutral grey that
/// is explained below the colour bar. Grid coordinates that cannot be drawn
/// on a log axis (≤ 0, non-finite) drop their column or row; the grid need
/// not be sorted. `overlays` are drawn on top, clipped to the grid, and
/// explained in a key below the plot.
///
/// Writes `<stem>.png` and `<stem>.svg`. Fails if the shape of `values` does
/// not match `ys` × `xs`; empty grids give an empty frame.
#[allow(clippy::too_many_arguments)]
pub fn plot_height_map(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    xs: &[f64],
    ys: &[f64],
    values: &[Vec<f64>],
    value_label: &str,
    log_values: bool,
    overlays: &[Overlay],
) -> Result<()> {
    if values.len() != ys.len() {
        bail!(
            "height map {title:?}: values has {} rows but ys has {} entries",
            values.len(),
            ys.len()
        );
    }
    if let Some((iy, row)) = values.iter().enumerate().find(|(_, r)| r.len() != xs.len()) {
        bail!(
            "height map {title:?}: row {iy} of values has {} entries but xs has {}",
            row.len(),
            xs.len()
        );
    }
    let (cols, x_edges) = log_cells(xs);
    let (rows, y_edges) = log_cells(ys);
    let cells = rows
        .iter()
        .map(|&iy| cols.iter().map(|&ix| values[iy][ix]).collect())
        .collect();
    render(
        stem,
        &HeightMapFigure {
            title,
            x_label,
            y_label,
            value_label,
            value_scale: if log_values {
                Scale::Log
            } else {
                Scale::Linear
            },
            x_edges,
            y_edges,
            cells,
            overlays,
        },
    )
}

struct HeightMapFigure<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    value_label: &'a str,
    value_scale: Scale,
    /// Cell boundaries, ascending: cell `i` spans `edges[i]..edges[i + 1]`.
    x_edges: Vec<f64>,
    y_edges: Vec<f64>,
    /// `cells[row][col]` in ascending coordinate order.
    cells: Vec<Vec<f64>>,
    overlays: &'a [Overlay],
}

/// Indices of the drawable entries of `coords` in ascending order (repeated
/// coordinates keep their first occurrence) and the cell boundaries around
/// them: half-way in log space between neighbours, and as far beyond the
/// outermost points as half the spacing next to them.
fn log_cells(coords: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let mut idx: Vec<usize> = (0..coords.len())
        .filter(|&i| Scale::Log.accepts(coords[i]))
        .collect();
    idx.sort_by(|&a, &b| coords[a].total_cmp(&coords[b]).then(a.cmp(&b)));
    idx.dedup_by(|b, a| coords[*a] == coords[*b]);
    let u: Vec<f64> = idx.iter().map(|&i| coords[i].log10()).collect();
    let edges = match u.len() {
        0 => Vec::new(),
        // A single point: a quarter decade either side.
        1 => vec![u[0] - 0.25, u[0] + 0.25],
        n => {
            let mut e = Vec::with_capacity(n + 1);
            e.push(u[0] - 0.5 * (u[1] - u[0]));
            e.extend(u.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            e.push(u[n - 1] + 0.5 * (u[n - 1] - u[n - 2]));
            e
        }
    };
    (idx, edges.into_iter().map(|e| 10f64.powf(e)).collect())
}

impl HeightMapFigure<'_> {
    /// Values that get a colour.
    fn coloured_values(&self) -> impl Iterator<Item = f64> + '_ {
        self.cells
            .iter()
            .flatten()
            .copied()
            .filter(|&v| self.value_scale.accepts(v))
    }

    /// Is any cell drawn in the "no value" grey?
    fn has_uncoloured(&self) -> bool {
        self.cells
            .iter()
            .flatten()
            .any(|&v| !self.value_scale.accepts(v))
    }
}

impl Figure for HeightMapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let overlay_runs: Vec<_> = self
            .overlays
            .iter()
            .map(|o| drawable_runs(&o.points, Scale::Log, Scale::Log))
            .collect();
        let has_cells = !self.cells.is_empty() && !self.x_edges.is_empty();

        // The grid fills the frame exactly; without a grid the overlays
        // decide the range.
        let range =
            |edges: &[f64], pick: fn(&(f64, f64)) -> f64| match (edges.first(), edges.last()) {
                (Some(&a), Some(&b)) if has_cells => (a, b),
                _ => padded_range(
                    extent(overlay_runs.iter().flatten().flatten().map(pick)),
                    Scale::Log,
                    0.03,
                ),
            };
        let x = Axis::new(Scale::Log, range(&self.x_edges, |p| p.0), self.x_label);
        let y = Axis::new(Scale::Log, range(&self.y_edges, |p| p.1), self.y_label);
        let values = Axis::new(
            self.value_scale,
            padded_range(extent(self.coloured_values()), self.value_scale, 0.0),
            self.value_label,
        );
        let has_values = self.coloured_values().next().is_some();
        let no_value_label = match self.value_scale {
            Scale::Log => "≤ 0 / n.a.",
            Scale::Linear => "n.a.",
        };
        let no_value_label = self.has_uncoloured().then_some(no_value_label);

        let area = titled_area(root, self.title)?;
        let styles = overlay_styles(self.overlays);
        let entries: Vec<KeyEntry> = self
            .overlays
            .iter()
            .zip(&styles)
            .filter(|(o, _)| !o.label.is_empty())
            .map(|(o, &st)| KeyEntry::new(&o.label, KeyGlyph::Line(st)))
            .collect();

        // Key strip at the bottom, colour-bar strip on the right.
        let (w, h) = area.dim_in_pixel();
        let key = key_layout(&area, &entries, w as i32 - 2 * style::MARGIN as i32)?;
        let key_strip = key.map_or(0, |k| k.h + style::MARGIN as i32);
        let (upper, lower) = area.split_vertically((h as i32 - key_strip).max(1));
        let bar_w = colour_bar_width(&upper, &values, has_values, no_value_label)?;
        let (plot_area, bar_area) = upper.split_horizontally((w as i32 - bar_w).max(1));

        let mut chart = builder(&plot_area, label_areas(&plot_area, &x, &y)?)
            .build_cartesian_2d(x.coord(), y.coord())?;
        draw_mesh(&mut chart, &x, &y, fix)?;

        // Cells over the grid lines: a heat map reads better without them.
        if has_cells {
            let cells = self
                .cells
                .iter()
                .enumerate()
                .flat_map(|(r, row)| row.iter().enumerate().map(move |(c, &v)| (r, c, v)));
            chart.draw_series(cells.map(|(r, c, v)| {
                let color = if self.value_scale.accepts(v) {
                    colormap(values.fraction(v))
                } else {
                    NO_VALUE
                };
                Rectangle::new(
                    [
                        (self.x_edges[c], self.y_edges[r + 1]),
                        (self.x_edges[c + 1], self.y_edges[r]),
                    ],
                    color.filled(),
                )
            }))?;
        }

        let clipped: Vec<_> = overlay_runs.iter().map(|r| clip_runs(r, &x, &y)).collect();
        draw_overlays(&mut chart, &clipped, &styles)?;
        draw_frame(&plot_area, &chart, &x, &y)?;
        if !has_cells && clipped.iter().all(Vec::is_empty) {
            draw_no_data_note(&chart, fix)?;
        }

        // The colour bar spans the height of the plotting area.
        let (_, bar_top) = bar_area.get_base_pixel();
        let (_, plot_top) = chart.plotting_area().get_base_pixel();
        let (_, plot_h) = chart.plotting_area().dim_in_pixel();
        let top = plot_top - bar_top;
        let bottom = top + plot_h as i32 - 1;
        draw_colour_bar(
            &bar_area,
            (top, bottom),
            &values,
            has_values,
            no_value_label,
            fix,
        )?;

        if let Some(k) = key {
            // Centred under the plotting area.
            let (plot_x, _) = chart.plotting_area().get_base_pixel();
            let (plot_w, _) = chart.plotting_area().dim_in_pixel();
            let (area_x, _) = lower.get_base_pixel();
            let centre = plot_x - area_x + plot_w as i32 / 2;
            let x0 = (centre - k.w / 2).clamp(0, (w as i32 - k.w).max(0));
            draw_key(&lower, &entries, &k, (x0, 0), fix)?;
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// Colour bar
// ---------------------------------------------------------------------------

/// Width of the colour bar itself, in pixels.
const BAR_WIDTH: i32 = 28;
/// Gap between the plotting area's right-hand margin and the bar.
const BAR_GAP: i32 = 4;
/// Height of the "no value" swatch below the bar.
const SWATCH_H: i32 = 26;
/// Gap between the bar and the swatch.
const SWATCH_GAP: i32 = 22;

/// Width of the strip that holds the colour bar, its labels and its
/// description.
fn colour_bar_width<DB>(
    area: &DrawingArea<DB, Shift>,
    values: &Axis,
    has_values: bool,
    no_value_label: Option<&str>,
) -> Result<i32>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let label_w = bar_label_width(area, values, has_values, no_value_label)?;
    let (_, desc_h) = text_size(area, "Δ", style::AXIS_DESC_SIZE)?;
    Ok(BAR_GAP
        + BAR_WIDTH
        + 2 * style::TICK_SIZE
        + label_w
        + style::DESC_GAP as i32
        + desc_h as i32
        + style::MARGIN as i32)
}

/// Width of the widest text next to the bar: tick labels and the "no value"
/// label.
fn bar_label_width<DB>(
    area: &DrawingArea<DB, Shift>,
    values: &Axis,
    has_values: bool,
    no_value_label: Option<&str>,
) -> Result<i32>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let mut w = 0;
    if has_values {
        for &v in &values.ticks.major {
            w = w.max(text_size(area, &values.label(v), style::TICK_LABEL_SIZE)?.0);
        }
    }
    if let Some(label) = no_value_label {
        w = w.max(text_size(area, label, style::TICK_LABEL_SIZE)?.0);
    }
    Ok(w as i32)
}

/// Draws the colour bar between the pixel rows `top` and `bottom` of `area`
/// (the plotting area's extent), with ticks, tick labels and the rotated
/// description; the "no value" swatch, if any, takes the bottom end.
fn draw_colour_bar<DB>(
    area: &DrawingArea<DB, Shift>,
    (top, bottom): (i32, i32),
    values: &Axis,
    has_values: bool,
    no_value_label: Option<&str>,
    fix: TextFix,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let left = BAR_GAP;
    let right = left + BAR_WIDTH - 1;
    let stroke = style::AXIS.stroke_width(1);
    let label_x = right + 2 * style::TICK_SIZE;
    let tick_font = (style::FAMILY, style::TICK_LABEL_SIZE)
        .into_font()
        .color(&style::AXIS)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let label_shift = fix.center_shift(style::TICK_LABEL_SIZE);

    let bar_bottom = match no_value_label {
        Some(label) => {
            let s_top = bottom - SWATCH_H + 1;
            area.draw(&Rectangle::new(
                [(left, s_top), (right, bottom)],
                NO_VALUE.filled(),
            ))?;
            area.draw(&Rectangle::new([(left, s_top), (right, bottom)], stroke))?;
            area.draw(&Text::new(
                label,
                (label_x, (s_top + bottom) / 2 + label_shift),
                tick_font.clone(),
            ))?;
            s_top - SWATCH_GAP
        }
        None => bottom,
    };
    let bar_h = bar_bottom - top;
    if !has_values || bar_h < 2 {
        return Ok(());
    }

    // The gradient, one pixel row at a time (each row overlaps the next by a
    // pixel so that SVG viewers show no seams).
    for row in top..=bar_bottom {
        let t = f64::from(bar_bottom - row) / f64::from(bar_h);
        let color = colormap(t);
        area.draw(&Rectangle::new(
            [(left, row), (right + 1, (row + 1).min(bar_bottom + 1))],
            color.filled(),
        ))?;
    }
    area.draw(&Rectangle::new([(left, top), (right, bar_bottom)], stroke))?;

    let y_of = |v: f64| bar_bottom - (values.fraction(v) * f64::from(bar_h)).round() as i32;
    let inside = |v: f64| (-1e-9..=1.0 + 1e-9).contains(&values.fraction(v));
    for &v in values.ticks.minor.iter().filter(|&&v| inside(v)) {
        let ty = y_of(v);
        area.draw(&PathElement::new(
            vec![(right, ty), (right + style::MINOR_TICK_SIZE, ty)],
            stroke,
        ))?;
    }
    for &v in values.ticks.major.iter().filter(|&&v| inside(v)) {
        let ty = y_of(v);
        area.draw(&PathElement::new(
            vec![(right, ty), (right + style::TICK_SIZE, ty)],
            stroke,
        ))?;
        area.draw(&Text::new(
            values.label(v),
            (label_x, ty + label_shift),
            tick_font.clone(),
        ))?;
    }

    // Description, rotated to read upwards like the y axis description.
    let label_w = bar_label_width(area, values, has_values, no_value_label)?;
    let desc_font = (style::FAMILY, style::AXIS_DESC_SIZE)
        .into_font()
        .color(&style::AXIS)
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Top));
    area.draw(&Text::new(
        values.desc.as_str(),
        (
            label_x + label_w + style::DESC_GAP as i32,
            (top + bar_bottom) / 2,
        ),
        desc_font,
    ))?;
    Ok(())
}

// ---------------------------------------------------------------------------
// Overlays (shared with the phase diagram)
// ---------------------------------------------------------------------------

/// How the overlays are drawn. Overlays without a colour of their own take
/// the default colours in turn.
pub(super) fn overlay_styles(overlays: &[Overlay]) -> Vec<SeriesStyle> {
    let mut defaults = OVERLAY_COLORS.iter().copied().cycle();
    overlays
        .iter()
        .map(|o| SeriesStyle {
            color: o.color.or_else(|| defaults.next()).unwrap_or(style::AXIS),
            width: OVERLAY_WIDTH,
            dashed: o.dashed,
            marker: None,
        })
        .collect()
}

/// Draws overlay lines with a thin white halo beneath, so that they stay
/// visible on dark and on busy backgrounds. All halos go first so that no
/// halo cuts through another overlay's line.
pub(super) fn draw_overlays<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    runs: &[Vec<Vec<(f64, f64)>>],
    styles: &[SeriesStyle],
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    for (r, st) in runs.iter().zip(styles) {
        let halo = SeriesStyle {
            color: WHITE,
            width: st.width + 3,
            ..*st
        };
        draw_lines(chart, r, &halo)?;
    }
    for (r, st) in runs.iter().zip(styles) {
        draw_lines(chart, r, st)?;
    }
    Ok(())
}

/// Clips `runs` to the axis box of `x` × `y`, in the axes' own (log or
/// linear) space. A run that leaves and re-enters the box is split.
///
/// Needed because plotters does not clip lines: it pins points outside the
/// plotting area to its edge, which would draw phantom lines along the
/// frame.
pub(super) fn clip_runs(runs: &[Vec<(f64, f64)>], x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    let fwd = |p: (f64, f64)| (x.scale.forward(p.0), y.scale.forward(p.1));
    let inv = |q: (f64, f64)| (x.scale.inverse(q.0), y.scale.inverse(q.1));
    let (x0, x1) = (x.scale.forward(x.lo), x.scale.forward(x.hi));
    let (y0, y1) = (y.scale.forward(y.lo), y.scale.forward(y.hi));
    let bx = (x0.min(x1), x0.max(x1));
    let by = (y0.min(y1), y0.max(y1));
    let inside = |q: (f64, f64)| (bx.0..=bx.1).contains(&q.0) && (by.0..=by.1).contains(&q.1);

    let mut out = Vec::new();
    for run in runs {
        if let [p] = run.as_slice() {
            if inside(fwd(*p)) {
                out.push(vec![*p]);
            }
            continue;
        }
        let mut cur: Vec<(f64, f64)> = Vec::new();
        for pair in run.windows(2) {
            let (a, b) = (fwd(pair[0]), fwd(pair[1]));
            match clip_segment(a, b, bx, by) {
                Some((t0, t1)) => {
                    let at = |t: f64| {
                        if t <= 0.0 {
                            pair[0]
                        } else if t >= 1.0 {
                            pair[1]
                        } else {
                            inv((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)))
                        }
                    };
                    if cur.is_empty() || t0 > 0.0 {
                        if cur.len() > 1 {
                            out.push(std::mem::take(&mut cur));
                        }
                        cur = vec![at(t0)];
                    }
                    cur.push(at(t1));
                    if t1 < 1.0 {
                        out.push(std::mem::take(&mut cur));
                    }
                }
                None => {
                    if cur.len() > 1 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                }
            }
        }
        if cur.len() > 1 {
            out.push(cur);
        }
    }
    out
}

/// Liang–Barsky: the parameter interval `[t0, t1]` ⊂ `[0, 1]` of the
/// segment `a → b` inside the box `bx × by`, if any.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    bx: (f64, f64),
    by: (f64, f64),
) -> Option<(f64, f64)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - bx.0),
        (dx, bx.1 - a.0),
        (-dy, a.1 - by.0),
        (dy, by.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

// ---------------------------------------------------------------------------
// Key outside the plotting area (shared with the phase diagram)
// ---------------------------------------------------------------------------

/// Half-diagonal of the phase-diagram diamonds, in pixels.
pub(super) const DIAMOND: i32 = 8;

/// How a diamond marker is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DiamondStyle {
    /// Fill colour; `None` draws a hollow diamond.
    pub fill: Option<RGBColor>,
    pub edge: RGBColor,
    /// Outline width in pixels; 0 draws no outline.
    pub edge_width: u32,
    /// Draw a black ring around the diamond.
    pub ring: bool,
}

/// Draws a diamond centred on the pixel `at` of `area`.
pub(super) fn draw_diamond<DB>(
    area: &DrawingArea<DB, Shift>,
    (x, y): style::Px,
    st: &DiamondStyle,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let h = DIAMOND;
    let corners = [(x, y - h), (x + h, y), (x, y + h), (x - h, y)];
    if let Some(fill) = st.fill {
        area.draw(&Polygon::new(corners.to_vec(), fill.filled()))?;
    }
    if st.edge_width > 0 {
        let mut outline = corners.to_vec();
        outline.push(corners[0]);
        area.draw(&PathElement::new(
            outline,
            st.edge.stroke_width(st.edge_width),
        ))?;
    }
    if st.ring {
        area.draw(&Circle::new((x, y), h + 5, BLACK.stroke_width(2)))?;
    }
    Ok(())
}

/// What is drawn in front of a key label.
#[derive(Debug, Clone, Copy)]
pub(super) enum KeyGlyph {
    /// A piece of line (with its marker, if any).
    Line(SeriesStyle),
    /// A filled, framed rectangle (a background colour).
    Swatch(RGBColor),
    /// A diamond marker.
    Diamond(DiamondStyle),
}

/// One key entry.
#[derive(Debug, Clone)]
pub(super) struct KeyEntry {
    pub label: String,
    pub glyph: KeyGlyph,
}

impl KeyEntry {
    pub fn new(label: &str, glyph: KeyGlyph) -> Self {
        Self {
            label: label.to_string(),
            glyph,
        }
    }
}

/// Size and grid of a key: entries fill the columns one after the other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct KeyLayout {
    rows: usize,
    col_w: i32,
    row_h: i32,
    /// Outer width and height of the box, in pixels.
    pub w: i32,
    pub h: i32,
}

/// Gap between two key columns, in pixels.
const KEY_COLUMN_GAP: i32 = 24;

/// Lays out `entries` in as many columns as fit into `max_w` pixels (one
/// column at least); `None` for no entries.
pub(super) fn key_layout<DB>(
    area: &DrawingArea<DB, Shift>,
    entries: &[KeyEntry],
    max_w: i32,
) -> Result<Option<KeyLayout>>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    if entries.is_empty() {
        return Ok(None);
    }
    let mut text_w = 0;
    for e in entries {
        text_w = text_w.max(text_size(area, &e.label, style::LEGEND_SIZE)?.0 as i32);
    }
    let pad = style::LEGEND_PADDING;
    let col_w = style::LEGEND_SAMPLE + style::LEGEND_GAP + text_w;
    let fit = (max_w - 2 * pad + KEY_COLUMN_GAP) / (col_w + KEY_COLUMN_GAP);
    let n = entries.len();
    let columns = usize::try_from(fit).unwrap_or(1).clamp(1, n);
    // No more columns than the rows need: 4 entries that would fit into 3
    // columns take 2 rows either way, and 2 + 2 looks better than 2 + 2 + 0.
    let rows = n.div_ceil(columns);
    let columns = n.div_ceil(rows);
    let row_h = (style::LEGEND_SIZE * style::LEGEND_LINE_HEIGHT).round() as i32;
    let (c, r) = (columns as i32, rows as i32);
    Ok(Some(KeyLayout {
        rows,
        col_w,
        row_h,
        w: 2 * pad + c * col_w + (c - 1) * KEY_COLUMN_GAP,
        h: 2 * pad + r * row_h,
    }))
}

/// Draws the key box with its upper left corner at `origin` of `area`.
pub(super) fn draw_key<DB>(
    area: &DrawingArea<DB, Shift>,
    entries: &[KeyEntry],
    layout: &KeyLayout,
    (x0, y0): style::Px,
    fix: TextFix,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let corners = [(x0, y0), (x0 + layout.w, y0 + layout.h)];
    area.draw(&Rectangle::new(corners, WHITE.filled()))?;
    area.draw(&Rectangle::new(
        corners,
        style::LEGEND_BORDER.stroke_width(1),
    ))?;
    let font = (style::FAMILY, style::LEGEND_SIZE)
        .into_font()
        .color(&style::AXIS)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let pad = style::LEGEND_PADDING;
    for (i, e) in entries.iter().enumerate() {
        // Column by column, so that related entries stay together.
        let (row, col) = (i % layout.rows, i / layout.rows);
        let x = x0 + pad + col as i32 * (layout.col_w + KEY_COLUMN_GAP);
        let y = y0 + pad + row as i32 * layout.row_h + layout.row_h / 2;
        let len = style::LEGEND_SAMPLE;
        match e.glyph {
            KeyGlyph::Line(st) => draw_sample(area, (x, y), &Sample::Line(st))?,
            KeyGlyph::Swatch(color) => {
                let r = [(x, y - 9), (x + len, y + 9)];
                area.draw(&Rectangle::new(r, color.filled()))?;
                area.draw(&Rectangle::new(r, style::LEGEND_BORDER.stroke_width(1)))?;
            }
            KeyGlyph::Diamond(st) => draw_diamond(area, (x + len / 2, y), &st)?,
        }
        area.draw(&Text::new(
            e.label.as_str(),
            (
                x + len + style::LEGEND_GAP,
                y + fix.center_shift(style::LEGEND_SIZE),
            ),
            font.clone(),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    /// `n` log-spaced values from `10^a` to `10^b`.
    pub fn log_grid(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1).max(1) as f64))
            .collect()
    }

    /// Synthetic stability boundaries in the (X, Y) plane: two power laws
    /// Y = a·X^p enclosing a wedge, like the master-curve boundaries.
    pub fn synthetic_overlays() -> Vec<Overlay> {
        let xs = log_grid(-1.5, 2.5, 60);
        let boundary = |a: f64, p: f64| xs.iter().map(|&x| (x, a * x.powf(p))).collect();
        vec![
            Overlay {
                label: "master curve: lower boundary".into(),
                points: boundary(0.3, -0.5),
                dashed: false,
                color: Some(RGBColor(0xD6, 0x27, 0x28)),
            },
            Overlay {
                label: "master curve: upper boundary".into(),
                points: boundary(3.0, -0.5),
                dashed: false,
                color: Some(RGBColor(0xD6, 0x27, 0x28)),
            },
            Overlay {
                label: "cable corridor X·Y = 0.1".into(),
                points: xs.iter().map(|&x| (x, 0.1 / x)).collect(),
                dashed: true,
                color: None,
            },
            Overlay {
                label: "cable corridor X·Y = 10".into(),
                points: xs.iter().map(|&x| (x, 10.0 / x)).collect(),
                dashed: true,
                color: None,
            },
        ]
    }

    /// A smooth bump over the log plane that is 0 (2-D state) below a
    /// boundary and grows beyond it, like an out-of-plane deflection.
    fn synthetic_values(xs: &[f64], ys: &[f64]) -> Vec<Vec<f64>> {
        ys.iter()
            .map(|&y| {
                xs.iter()
                    .map(|&x| {
                        let s = (x * y.powi(2)).log10();
                        if s < -1.0 {
                            0.0
                        } else {
                            1e-3 * 10f64.powf(1.5 * (s + 1.0)).min(1e3)
                        }
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn colormap_ends_and_clamping() {
        assert_eq!(colormap(0.0), RGBColor(0x44, 0x01, 0x54));
        assert_eq!(colormap(1.0), RGBColor(0xFD, 0xE7, 0x25));
        assert_eq!(colormap(-3.0), colormap(0.0));
        assert_eq!(colormap(f64::NAN), colormap(0.0));
        assert_eq!(colormap(7.0), colormap(1.0));
        assert_eq!(colormap(1.0 / 15.0), RGBColor(0x48, 0x1A, 0x6C));
    }

    #[test]
    fn log_cells_sort_filter_and_bracket() {
        let (idx, edges) = log_cells(&[10.0, 1.0, f64::NAN, 100.0, -1.0, 10.0]);
        assert_eq!(idx, vec![1, 0, 3]);
        let expect = [
            10f64.powf(-0.5),
            10f64.powf(0.5),
            10f64.powf(1.5),
            10f64.powf(2.5),
        ];
        assert_eq!(edges.len(), 4);
        for (e, x) in edges.iter().zip(expect) {
            assert!((e / x - 1.0).abs() < 1e-12, "{edges:?}");
        }
        assert_eq!(log_cells(&[]).1, Vec::<f64>::new());
        assert_eq!(log_cells(&[2.0]).1.len(), 2);
    }

    #[test]
    fn clipping_splits_and_cuts_runs() {
        let x = Axis::new(Scale::Log, (1.0, 100.0), "x");
        let y = Axis::new(Scale::Linear, (0.0, 1.0), "y");
        // Inside, out above, back in.
        let run = vec![(2.0, 0.5), (10.0, 2.0), (50.0, 0.5)];
        let out = clip_runs(&[run], &x, &y);
        assert_eq!(out.len(), 2, "{out:?}");
        assert_eq!(out[0][0], (2.0, 0.5));
        assert!((out[0][1].1 - 1.0).abs() < 1e-9);
        assert!((out[1][0].1 - 1.0).abs() < 1e-9);
        assert_eq!(out[1][1], (50.0, 0.5));
        // Entirely outside.
        assert!(clip_runs(&[vec![(0.1, 0.5), (0.5, 0.5)]], &x, &y).is_empty());
        // Crossing the whole box.
        let out = clip_runs(&[vec![(0.1, 0.5), (1000.0, 0.5)]], &x, &y);
        assert_eq!(out.len(), 1);
        assert!((out[0][0].0 - 1.0).abs() < 1e-9 && (out[0][1].0 - 100.0).abs() < 1e-6);
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("height-map");
        let stem = dir.join("height_map");
        let title = "Bend–twist: out-of-plane tip deflection";
        let xs = log_grid(-1.0, 2.0, 31);
        let ys = log_grid(-2.0, 1.0, 25);
        let values = synthetic_values(&xs, &ys);
        plot_height_map(
            &stem,
            title,
            "X (gravity / bending)",
            "Y (curvature × length)",
            &xs,
            &ys,
            &values,
            "out-of-plane deflection z_max / L",
            true,
            &synthetic_overlays(),
        )
        .expect("plot renders");
        assert_rendered(&stem, title);

        // Linear colour scale, unsorted coordinates, no overlays.
        let stem = dir.join("height_map_linear");
        let xs = vec![3.0, 0.5, 1.0, 20.0];
        let ys = vec![0.2, 2.0, 0.02];
        let values: Vec<Vec<f64>> = ys
            .iter()
            .map(|&y| xs.iter().map(|&x: &f64| (x * y).ln()).collect())
            .collect();
        plot_height_map(
            &stem,
            "linear colours",
            "X",
            "Y",
            &xs,
            &ys,
            &values,
            "ln(X·Y)",
            false,
            &[],
        )
        .expect("plot renders");
        assert_rendered(&stem, "linear colours");
    }

    #[test]
    fn nan_values_and_bad_coordinates() {
        let dir = fresh_dir("height-map-nan");
        let stem = dir.join("height_map_nan");
        let mut xs = log_grid(-1.0, 2.0, 12);
        let ys = log_grid(-2.0, 1.0, 10);
        let mut values = synthetic_values(&xs, &ys);
        values[3][4] = f64::NAN;
        values[5][6] = f64::INFINITY;
        values[7][2] = -1.0;
        xs[11] = f64::NAN; // drops the last column
        let mut overlays = synthetic_overlays();
        overlays[0].points[3].1 = f64::NAN;
        plot_height_map(
            &stem,
            "height map with holes",
            "X",
            "Y",
            &xs,
            &ys,
            &values,
            "deflection",
            true,
            &overlays,
        )
        .expect("non-finite data is drawn grey");
        assert_rendered(&stem, "height map with holes");

        // Nothing but undrawable values: all grey, no colour gradient.
        let stem = dir.join("height_map_all_nan");
        let values = vec![vec![f64::NAN; xs.len()]; ys.len()];
        plot_height_map(
            &stem,
            "all NaN",
            "X",
            "Y",
            &xs,
            &ys,
            &values,
            "v",
            false,
            &[],
        )
        .expect("all-NaN map renders");
        assert_rendered(&stem, "all NaN");
    }

    #[test]
    fn empty_and_mismatched_inputs() {
        let dir = fresh_dir("height-map-empty");
        let stem = dir.join("height_map_empty");
        plot_height_map(&stem, "empty map", "X", "Y", &[], &[], &[], "v", true, &[])
            .expect("empty map renders an empty frame");
        assert_rendered(&stem, "empty map");

        // Overlays alone still make a plot.
        let stem = dir.join("height_map_overlays_only");
        plot_height_map(
            &stem,
            "overlays only",
            "X",
            "Y",
            &[],
            &[],
            &[],
            "v",
            true,
            &synthetic_overlays(),
        )
        .expect("overlay-only map renders");
        assert_rendered(&stem, "overlays only");

        let err = plot_height_map(
            &stem,
            "bad",
            "X",
            "Y",
            &[1.0, 2.0],
            &[1.0],
            &[vec![1.0]],
            "v",
            true,
            &[],
        )
        .expect_err("shape mismatch is an error");
        assert!(err.to_string().contains("row 0"), "{err}");
        let err = plot_height_map(
            &stem,
            "bad",
            "X",
            "Y",
            &[1.0],
            &[1.0, 2.0],
            &[],
            "v",
            true,
            &[],
        )
        .expect_err("shape mismatch is an error");
        assert!(err.to_string().contains("rows"), "{err}");
    }
}
