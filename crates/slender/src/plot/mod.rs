//! Figures of the validation report.
//!
//! Every figure is written twice from the same drawing code: a PNG for quick
//! viewing and an SVG for the report. The drawing code of each figure is a
//! [`Figure`] implementation, generic over the plotters backend, so the two
//! files cannot drift apart.
//!
//! The shared machinery lives here: rendering to both backends, axis layout
//! (tick choice, label-area sizes), filtering of unplottable data, series and
//! legend drawing.

mod boxplot;
mod cantilever_ratio;
mod font;
mod height_map;
mod line_chart;
mod phase_diagram;
mod relative_error;
mod shape_2d;
mod shape_3d;
mod style;

pub use boxplot::{plot_boxplots, BoxPanel, BoxSample};
pub use cantilever_ratio::{plot_cantilever_ratio, Curve};
pub use height_map::{plot_height_map, Overlay};
pub use line_chart::{plot_lines, LineAxes};
pub use phase_diagram::{
    plot_phase_diagram, plot_phase_diagram_labeled, Phase, PhaseLabels, PhasePoint,
};
pub use relative_error::plot_relative_error;
pub use shape_2d::plot_shapes_2d;
pub use shape_3d::{plot_shape_views, Polyline3};

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use style::{MarkerShape, TextFix, Ticks};

/// Drawing code of one figure, written once for every backend.
trait Figure {
    /// Canvas size in pixels (the SVG uses the same size in user units).
    fn size(&self) -> (u32, u32);

    /// Draws the complete figure onto `root`; `fix` corrects text placement
    /// for the backend at hand.
    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static;
}

/// `stem` with `.ext` appended. `Path::with_extension` is not used because
/// it would replace a dot-suffix that is part of the stem ("run.v2").
fn with_suffix(stem: &Path, ext: &str) -> PathBuf {
    let mut s = OsString::from(stem.as_os_str());
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// Writes `<stem>.png` and `<stem>.svg` of `figure`.
fn render(stem: &Path, figure: &impl Figure) -> Result<()> {
    font::ensure_font_registered();
    if let Some(dir) = stem.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating output directory {}", dir.display()))?;
    }

    let png = with_suffix(stem, "png");
    {
        let root = BitMapBackend::new(&png, figure.size()).into_drawing_area();
        figure
            .draw(&root, TextFix::BITMAP)
            .with_context(|| format!("drawing {}", png.display()))?;
        // Explicit present: dropping the backend would swallow write errors.
        root.present()
            .with_context(|| format!("writing {}", png.display()))?;
    }

    let svg = with_suffix(stem, "svg");
    {
        let root = SVGBackend::new(&svg, figure.size()).into_drawing_area();
        figure
            .draw(&root, TextFix::SVG)
            .with_context(|| format!("drawing {}", svg.display()))?;
        root.present()
            .with_context(|| format!("writing {}", svg.display()))?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Data filtering and axis ranges
// ---------------------------------------------------------------------------

/// How an axis maps values to positions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear axis.
    Linear,
    /// Logarithmic axis (positive values only).
    Log,
}

impl Scale {
    /// Can `v` be drawn on this axis at all?
    fn accepts(self, v: f64) -> bool {
        v.is_finite() && (self == Scale::Linear || v > 0.0)
    }

    /// Position of `v` in the axis' own linear space.
    fn forward(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.log10(),
        }
    }

    fn inverse(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log => 10f64.powf(t),
        }
    }
}

/// Splits `points` into runs of drawable points. A point that cannot be
/// drawn (non-finite, or ≤ 0 on a log axis) breaks the line rather than being
/// bridged over, so gaps in the data stay visible as gaps.
fn drawable_runs(points: &[(f64, f64)], sx: Scale, sy: Scale) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut run = Vec::new();
    for &(x, y) in points {
        if sx.accepts(x) && sy.accepts(y) {
            run.push((x, y));
        } else if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// Smallest and largest of `values`, or `None` if there are none.
fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values.into_iter().fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// Axis range covering `data` plus `pad` (fraction of the span, in the
/// axis' own linear space) on each side. Degenerate or missing data get a
/// sensible non-empty range so that drawing never fails.
fn padded_range(data: Option<(f64, f64)>, scale: Scale, pad: f64) -> (f64, f64) {
    // Without data, an arbitrary range (padded like real data, so that the
    // corner ticks of both axes do not collide).
    let (lo, hi) = data.unwrap_or(match scale {
        Scale::Linear => (0.0, 1.0),
        Scale::Log => (0.1, 10.0),
    });
    let (a, b) = (scale.forward(lo), scale.forward(hi));
    let span = b - a;
    let (a, b) = if span > 1e-12 * a.abs().max(b.abs()).max(1e-300) {
        (a - pad * span, b + pad * span)
    } else {
        // A single value: half a decade, or 10 % (at least 1 unit), around it.
        let half = match scale {
            Scale::Log => 0.5,
            Scale::Linear => (0.1 * a.abs()).max(1.0),
        };
        (a - half, a + half)
    };
    (scale.inverse(a), scale.inverse(b))
}

// ---------------------------------------------------------------------------
// Axes
// ---------------------------------------------------------------------------

/// One axis of a chart: scale, range, ticks and description.
#[derive(Debug, Clone)]
struct Axis {
    scale: Scale,
    lo: f64,
    hi: f64,
    ticks: Ticks,
    desc: String,
}

impl Axis {
    /// An axis over `[lo, hi]` with automatically chosen ticks.
    fn new(scale: Scale, (lo, hi): (f64, f64), desc: &str) -> Self {
        let ticks = match scale {
            Scale::Log => style::log_ticks(lo, hi),
            Scale::Linear => style::linear_ticks(lo, hi, 8),
        };
        Self::with_ticks(scale, (lo, hi), ticks, desc)
    }

    fn with_ticks(scale: Scale, (lo, hi): (f64, f64), ticks: Ticks, desc: &str) -> Self {
        Self {
            scale,
            lo,
            hi,
            ticks,
            desc: desc.to_string(),
        }
    }

    /// Tick label text of `v`.
    fn label(&self, v: f64) -> String {
        match self.scale {
            Scale::Log => style::format_log_tick(v),
            Scale::Linear => style::format_linear_tick(v, self.ticks.decimals),
        }
    }

    /// Position of `v` along the axis, 0 at `lo` and 1 at `hi`.
    fn fraction(&self, v: f64) -> f64 {
        let (a, b) = (self.scale.forward(self.lo), self.scale.forward(self.hi));
        (self.scale.forward(v) - a) / (b - a)
    }

    /// The plotters coordinate of this axis.
    fn coord(&self) -> AxisCoord {
        AxisCoord(self.clone())
    }

    /// Clamps `[a, b]` to the axis range; `None` if nothing is left.
    fn clamp(&self, a: f64, b: f64) -> Option<(f64, f64)> {
        let (a, b) = (a.min(b).max(self.lo), a.max(b).min(self.hi));
        (a < b).then_some((a, b))
    }
}

/// plotters coordinate of an [`Axis`]: maps values by the axis' scale and
/// reports exactly our tick positions.
///
/// A custom coordinate instead of plotters' `log_scale()` /
/// `with_key_points()` combinators because those either pick their own
/// (unevenly spaced) minor ticks or lose the ability to format labels for
/// linear `f64` axes.
struct AxisCoord(Axis);

impl Ranged for AxisCoord {
    type ValueType = f64;
    // Labels are always formatted by our own formatter (see `draw_mesh`).
    type FormatOption = DefaultFormatting;

    fn map(&self, v: &f64, (p0, p1): (i32, i32)) -> i32 {
        let t = self.0.fraction(*v);
        // Non-finite or far-out values (never produced by the filtered data)
        // are pinned to the edges instead of overflowing the pixel type.
        let t = if t.is_nan() { 0.0 } else { t.clamp(-4.0, 5.0) };
        p0 + (f64::from(p1 - p0) * t).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.0.ticks.minor.clone()
        } else {
            self.0.ticks.major.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.0.lo..self.0.hi
    }
}

fn text_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
) -> Result<(u32, u32)>
where
    DB::ErrorType: 'static,
{
    let font: TextStyle = (style::FAMILY, size).into_font().into();
    Ok(area.estimate_text_size(text, &font)?)
}

/// Sizes (x label area height, y label area width) that fit the tick labels
/// and the axis description without overlapping. Computed from the actual
/// label texts because log-axis labels ("10⁻³") and signed linear labels
/// ("−12.5") differ a lot in width.
fn label_areas<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    x: &Axis,
    y: &Axis,
) -> Result<(u32, u32)>
where
    DB::ErrorType: 'static,
{
    // plotters keeps tick labels 2 × tick length away from the axis.
    let label_dist = 2 * style::TICK_SIZE.unsigned_abs();
    let (_, desc_h) = text_size(area, "Δ", style::AXIS_DESC_SIZE)?;
    let mut tick_h = 0;
    for &v in &x.ticks.major {
        tick_h = tick_h.max(text_size(area, &x.label(v), style::TICK_LABEL_SIZE)?.1);
    }
    let mut tick_w = 0;
    for &v in &y.ticks.major {
        tick_w = tick_w.max(text_size(area, &y.label(v), style::TICK_LABEL_SIZE)?.0);
    }
    // Superscripts sit higher than the ascent estimate; keep some slack.
    let x_area = label_dist + tick_h + style::DESC_GAP + desc_h + 6;
    let y_area = label_dist + tick_w + style::DESC_GAP + desc_h + 4;
    Ok((x_area, y_area))
}

/// Clears the canvas, draws the title and returns the area below it.
fn titled_area<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<DrawingArea<DB, Shift>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let font = (style::FAMILY, style::TITLE_SIZE)
        .into_font()
        .color(&style::AXIS);
    // plotters puts the title only 5 px below the canvas edge.
    let below_edge = root.margin(style::TITLE_TOP, 0, 0, 0);
    Ok(below_edge.titled(title, font)?)
}

/// Chart builder on `area` with the standard margins and the given label
/// area sizes.
fn builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    (x_area, y_area): (u32, u32),
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    b.margin(style::MARGIN)
        .margin_right(style::MARGIN_RIGHT)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area);
    b
}

/// Grid, axes, ticks, tick labels and axis descriptions.
fn draw_mesh<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    x: &Axis,
    y: &Axis,
    fix: TextFix,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64, FormatOption = DefaultFormatting>,
    Y: Ranged<ValueType = f64, FormatOption = DefaultFormatting>,
{
    let x_fmt = |v: &f64| x.label(*v);
    let y_fmt = |v: &f64| y.label(*v);
    let tick_font = (style::FAMILY, style::TICK_LABEL_SIZE)
        .into_font()
        .color(&style::AXIS);
    let desc_font = (style::FAMILY, style::AXIS_DESC_SIZE)
        .into_font()
        .color(&style::AXIS);
    chart
        .configure_mesh()
        .bold_line_style(style::GRID_MAJOR.stroke_width(1))
        .light_line_style(style::GRID_MINOR.stroke_width(1))
        // Axis lines and ticks come from `draw_frame`; the tick size still
        // sets the distance of the labels from the axis.
        .axis_style(TRANSPARENT)
        .set_all_tick_mark_size(style::TICK_SIZE)
        .y_label_offset(fix.center_shift(style::TICK_LABEL_SIZE))
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .x_label_style(tick_font.clone())
        .y_label_style(tick_font)
        .axis_desc_style(desc_font)
        .x_desc(x.desc.as_str())
        .y_desc(y.desc.as_str())
        .draw()?;
    Ok(())
}

/// Writes a note in the middle of a plot that has no drawable data, so an
/// empty figure is not mistaken for a rendering failure.
fn draw_no_data_note<DB, X, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    fix: TextFix,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let area = chart.plotting_area().strip_coord_spec();
    let (w, h) = area.dim_in_pixel();
    let style = (style::FAMILY, style::AXIS_DESC_SIZE)
        .into_font()
        .color(&style::NOTE)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw(&Text::new(
        "no drawable data",
        (
            w as i32 / 2,
            h as i32 / 2 + fix.center_shift(style::AXIS_DESC_SIZE),
        ),
        style,
    ))?;
    Ok(())
}

/// Frame around the plotting area with outward tick marks (long at labelled
/// ticks, short at minor ones).
///
/// plotters' own axis lines are switched off (see [`draw_mesh`]): it draws
/// only the left and bottom axes, one pixel outside the data area, where they
/// miss each other at the corner. A closed box on the outermost data pixels
/// reads better in print and looks the same in PNG and SVG.
fn draw_frame<DB, X, Y>(
    canvas: &DrawingArea<DB, Shift>,
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    x: &Axis,
    y: &Axis,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    // Drawn on the enclosing canvas in its pixel coordinates: the ticks lie
    // outside the plotting area, which clips what is drawn on it.
    let (cx, cy) = canvas.get_base_pixel();
    let plot = chart.plotting_area();
    let (px, py) = plot.get_base_pixel();
    let (w, h) = plot.dim_in_pixel();
    let (left, top) = (px - cx, py - cy);
    let (right, bottom) = (left + w as i32 - 1, top + h as i32 - 1);
    let stroke = style::AXIS.stroke_width(1);
    canvas.draw(&PathElement::new(
        vec![
            (left, top),
            (right, top),
            (right, bottom),
            (left, bottom),
            (left, top),
        ],
        stroke,
    ))?;

    let x_ticks = |ticks: &[f64], len: i32| -> Result<()> {
        for &v in ticks {
            let tx = chart.backend_coord(&(v, y.lo)).0 - cx;
            if (left..=right).contains(&tx) {
                canvas.draw(&PathElement::new(
                    vec![(tx, bottom), (tx, bottom + len)],
                    stroke,
                ))?;
            }
        }
        Ok(())
    };
    x_ticks(&x.ticks.major, style::TICK_SIZE)?;
    x_ticks(&x.ticks.minor, style::MINOR_TICK_SIZE)?;
    let y_ticks = |ticks: &[f64], len: i32| -> Result<()> {
        for &v in ticks {
            let ty = chart.backend_coord(&(x.lo, v)).1 - cy;
            if (top..=bottom).contains(&ty) {
                canvas.draw(&PathElement::new(
                    vec![(left, ty), (left - len, ty)],
                    stroke,
                ))?;
            }
        }
        Ok(())
    };
    y_ticks(&y.ticks.major, style::TICK_SIZE)?;
    y_ticks(&y.ticks.minor, style::MINOR_TICK_SIZE)?;
    Ok(())
}

// ---------------------------------------------------------------------------
// Series and legend
// ---------------------------------------------------------------------------

/// How one series is drawn; also used for its legend sample.
#[derive(Debug, Clone, Copy)]
struct SeriesStyle {
    color: RGBColor,
    width: u32,
    dashed: bool,
    marker: Option<MarkerShape>,
}

impl SeriesStyle {
    /// Style of the `i`-th ordinary data curve.
    fn for_curve(i: usize, curve: &Curve) -> Self {
        Self {
            color: style::series_color(i),
            width: style::CURVE_WIDTH,
            dashed: curve.dashed,
            marker: curve.markers.then(|| style::series_marker(i)),
        }
    }
}

/// Draws the lines of a series (no markers, no legend entry).
fn draw_lines<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    runs: &[Vec<(f64, f64)>],
    st: &SeriesStyle,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let stroke = st.color.stroke_width(st.width);
    for run in runs {
        if st.dashed {
            chart.draw_series(DashedLineSeries::new(
                run.iter().copied(),
                style::DASH.0,
                style::DASH.1,
                stroke,
            ))?;
        } else {
            chart.draw_series(LineSeries::new(run.iter().copied(), stroke))?;
        }
    }
    Ok(())
}

/// Draws the markers of a series, if it has any.
/// Draws `curves` (their drawable `runs`) in the standard series styles: all lines first, then
/// all markers, so that no line hides a data point. Returns the styles for the legend.
fn draw_curves<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    curves: &[Curve],
    runs: &[Vec<Vec<(f64, f64)>>],
) -> Result<Vec<SeriesStyle>>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let styles: Vec<_> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| SeriesStyle::for_curve(i, c))
        .collect();
    for (r, st) in runs.iter().zip(&styles) {
        draw_lines(chart, r, st)?;
    }
    for (r, st) in runs.iter().zip(&styles) {
        draw_markers(chart, r, st)?;
    }
    Ok(styles)
}

fn draw_markers<DB, X, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    runs: &[Vec<(f64, f64)>],
    st: &SeriesStyle,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let Some(shape) = st.marker else {
        return Ok(());
    };
    // Markers are placed in pixel space (see `style::draw_marker`), relative
    // to the plotting area.
    let plot = chart.plotting_area();
    let (bx, by) = plot.get_base_pixel();
    let area = plot.strip_coord_spec();
    for p in runs.iter().flatten() {
        let (px, py) = chart.backend_coord(p);
        style::draw_marker(&area, (px - bx, py - by), shape, st.color)?;
    }
    Ok(())
}

/// What is drawn in front of a legend label.
#[derive(Debug, Clone, Copy)]
enum Sample {
    /// A short piece of the series' line, with its marker.
    Line(SeriesStyle),
    /// A swatch of the band fill.
    Band,
}

/// One legend line.
#[derive(Debug, Clone)]
struct LegendEntry {
    label: String,
    sample: Sample,
}

impl LegendEntry {
    fn line(label: &str, st: SeriesStyle) -> Self {
        Self {
            label: label.to_string(),
            sample: Sample::Line(st),
        }
    }
}

/// Draws a legend sample with its left end at `(x, y)` (vertical centre).
fn draw_sample<DB>(area: &DrawingArea<DB, Shift>, (x, y): style::Px, sample: &Sample) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let len = style::LEGEND_SAMPLE;
    match sample {
        Sample::Band => {
            area.draw(&Rectangle::new(
                [(x, y - 9), (x + len, y + 9)],
                style::BAND_FILL.filled(),
            ))?;
        }
        Sample::Line(st) => {
            let stroke = st.color.stroke_width(st.width);
            if st.dashed {
                // Shorter dashes than in the plot so that several fit.
                area.draw(&DashedPathElement::new(
                    vec![(x, y), (x + len, y)],
                    8,
                    5,
                    stroke,
                ))?;
            } else {
                area.draw(&PathElement::new(vec![(x, y), (x + len, y)], stroke))?;
            }
            if let Some(shape) = st.marker {
                style::draw_marker(area, (x + len / 2, y), shape, st.color)?;
            }
        }
    }
    Ok(())
}

/// Corner of the plotting area that holds the legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Corner {
    UpperLeft,
    UpperRight,
    LowerRight,
    LowerLeft,
}

/// Picks the plot corner where a legend of `legend_px` pixels covers the
/// fewest data points. `occupied` are data positions as axis fractions
/// (0…1, y upwards). Ties prefer the upper left, then the upper right.
fn legend_corner(plot_px: (u32, u32), legend_px: (i32, i32), occupied: &[(f64, f64)]) -> Corner {
    // Slack around the box so that lines just outside it do not touch it.
    let slack = 2 * style::LEGEND_INSET + 6;
    let w = f64::from(legend_px.0 + slack) / f64::from(plot_px.0.max(1));
    let h = f64::from(legend_px.1 + slack) / f64::from(plot_px.1.max(1));
    let inside = |corner: Corner, &(u, v): &(f64, f64)| match corner {
        Corner::UpperLeft => u <= w && v >= 1.0 - h,
        Corner::UpperRight => u >= 1.0 - w && v >= 1.0 - h,
        Corner::LowerRight => u >= 1.0 - w && v <= h,
        Corner::LowerLeft => u <= w && v <= h,
    };
    [
        Corner::UpperLeft,
        Corner::UpperRight,
        Corner::LowerRight,
        Corner::LowerLeft,
    ]
    .into_iter()
    .enumerate()
    .min_by_key(|&(rank, corner)| (occupied.iter().filter(|p| inside(corner, p)).count(), rank))
    .map_or(Corner::UpperLeft, |(_, corner)| corner)
}

/// Axis-fraction positions along all runs, densified so that a line passing
/// through a corner counts as occupying it even between its vertices.
fn occupied_fractions(runs: &[Vec<(f64, f64)>], x: &Axis, y: &Axis) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for run in runs {
        let pts: Vec<(f64, f64)> = run
            .iter()
            .map(|&(a, b)| (x.fraction(a), y.fraction(b)))
            .collect();
        if let Some(&first) = pts.first() {
            out.push(first);
        }
        for pair in pts.windows(2) {
            let ((u0, v0), (u1, v1)) = (pair[0], pair[1]);
            let len = (u1 - u0).hypot(v1 - v0);
            // One sample per 1 % of the plot size, capped for long segments.
            let n = ((len / 0.01).ceil() as usize).clamp(1, 200);
            out.extend((1..=n).map(|k| {
                let t = k as f64 / n as f64;
                (u0 + t * (u1 - u0), v0 + t * (v1 - v0))
            }));
        }
    }
    out
}

/// Draws the legend box in the least crowded corner of the plotting area.
///
/// Drawn by hand rather than with plotters' series labels: those need the
/// sample as a composed element, which plotters only accepts for `'static`
/// backends, and they cannot choose a corner by themselves.
fn draw_legend<DB, X, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    entries: &[LegendEntry],
    occupied: &[(f64, f64)],
    fix: TextFix,
) -> Result<()>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    if entries.is_empty() {
        return Ok(());
    }
    let area = chart.plotting_area().strip_coord_spec();
    let font = (style::FAMILY, style::LEGEND_SIZE)
        .into_font()
        .color(&style::AXIS);
    let mut text_w = 0;
    for e in entries {
        text_w = text_w.max(area.estimate_text_size(&e.label, &font)?.0 as i32);
    }
    let row = (style::LEGEND_SIZE * style::LEGEND_LINE_HEIGHT).round() as i32;
    let pad = style::LEGEND_PADDING;
    let gap = style::LEGEND_GAP;
    let n = i32::try_from(entries.len()).unwrap_or(i32::MAX);
    let box_w = pad + style::LEGEND_SAMPLE + gap + text_w + pad;
    let box_h = pad + n.saturating_mul(row) + pad;

    let (pw, ph) = area.dim_in_pixel();
    let (pw, ph) = (pw as i32, ph as i32);
    let inset = style::LEGEND_INSET;
    let (x0, y0) = match legend_corner(area.dim_in_pixel(), (box_w, box_h), occupied) {
        Corner::UpperLeft => (inset, inset),
        Corner::UpperRight => (pw - inset - box_w, inset),
        Corner::LowerRight => (pw - inset - box_w, ph - inset - box_h),
        Corner::LowerLeft => (inset, ph - inset - box_h),
    };

    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        WHITE.filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        style::LEGEND_BORDER.stroke_width(1),
    ))?;
    let text_style = font.pos(Pos::new(HPos::Left, VPos::Center));
    for (i, e) in entries.iter().enumerate() {
        let i = i32::try_from(i).unwrap_or(i32::MAX);
        let cy = y0 + pad + i.saturating_mul(row) + row / 2;
        draw_sample(&area, (x0 + pad, cy), &e.sample)?;
        area.draw(&Text::new(
            e.label.as_str(),
            (
                x0 + pad + style::LEGEND_SAMPLE + gap,
                cy + fix.center_shift(style::LEGEND_SIZE),
            ),
            text_style.clone(),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod test_util {
    //! Helpers shared by the plot tests.

    use std::path::{Path, PathBuf};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A fresh, empty directory under the system temp dir, unique per process
    /// and call, so that parallel tests never share output files.
    pub fn fresh_dir(name: &str) -> PathBuf {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!(
            "slender-plot-test-{}-{n}-{name}",
            std::process::id()
        ));
        // A stale directory from an earlier run with the same pid is harmless
        // to remove; failure to create is a test failure anyway.
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create test output dir");
        dir
    }

    /// Asserts that both files of `stem` exist, the PNG is non-empty and the
    /// SVG contains `title` (as text, which requires the font to work).
    pub fn assert_rendered(stem: &Path, title: &str) {
        let png = super::with_suffix(stem, "png");
        let svg = super::with_suffix(stem, "svg");
        let png_len = std::fs::metadata(&png).expect("png exists").len();
        assert!(png_len > 0, "{} is empty", png.display());
        let bytes = std::fs::read(&png).expect("read png");
        assert_eq!(&bytes[1..4], b"PNG", "{} is not a PNG", png.display());
        let svg_text = std::fs::read_to_string(&svg).expect("svg exists");
        assert!(
            svg_text.contains(title),
            "{} does not contain the title {title:?}",
            svg.display()
        );
        // Optional copy for eyeballing: SLENDER_PLOT_SAMPLES=/some/dir.
        if let Some(dir) = std::env::var_os("SLENDER_PLOT_SAMPLES") {
            let dir = PathBuf::from(dir);
            if std::fs::create_dir_all(&dir).is_ok() {
                for f in [&png, &svg] {
                    if let Some(name) = f.file_name() {
                        let _ = std::fs::copy(f, dir.join(name));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffix_keeps_dots_in_stem() {
        assert_eq!(
            with_suffix(Path::new("out/run.v2"), "png"),
            PathBuf::from("out/run.v2.png")
        );
    }

    #[test]
    fn runs_break_at_undrawable_points() {
        let pts = [
            (1.0, 1.0),
            (2.0, f64::NAN),
            (3.0, 3.0),
            (4.0, 4.0),
            (-1.0, 1.0),
        ];
        let runs = drawable_runs(&pts, Scale::Log, Scale::Linear);
        assert_eq!(runs, vec![vec![(1.0, 1.0)], vec![(3.0, 3.0), (4.0, 4.0)]]);
    }

    #[test]
    fn degenerate_ranges_are_widened() {
        let (a, b) = padded_range(Some((5.0, 5.0)), Scale::Log, 0.05);
        assert!(a < 5.0 && b > 5.0);
        let (a, b) = padded_range(None, Scale::Linear, 0.05);
        assert!(a < b);
    }

    #[test]
    fn legend_avoids_crowded_corner() {
        // Points crowd the upper left; the legend must go elsewhere.
        let occ: Vec<_> = (0..50).map(|i| (i as f64 / 200.0, 0.95)).collect();
        assert_eq!(
            legend_corner((1000, 600), (200, 100), &occ),
            Corner::UpperRight
        );
        assert_eq!(
            legend_corner((1000, 600), (200, 100), &[]),
            Corner::UpperLeft
        );
    }
}
