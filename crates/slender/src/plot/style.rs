//! Shared look of all figures: palette, marker shapes, sizes, and the tick
//! and number formatting used on axes and in legends.
//!
//! Everything that decides how a figure *looks* lives here so that the
//! individual plots stay consistent with each other.

use plotters::coord::Shift;
use plotters::prelude::{
    Circle, Color, DrawingArea, DrawingAreaErrorKind, DrawingBackend, Polygon, RGBColor, Rectangle,
};

use super::font::FONT_FAMILY;

/// Font family used for all text (registered by [`super::font`]).
pub const FAMILY: &str = FONT_FAMILY;

/// Canvas size of the Γ-sweep plots (ratio and relative error), in pixels.
pub const WIDE_CANVAS: (u32, u32) = (1200, 800);
/// Canvas size of the shape plots; closer to square because deformed rods
/// usually span comparable extents in both directions.
pub const SHAPE_CANVAS: (u32, u32) = (1000, 800);

/// Figure title.
pub const TITLE_SIZE: f64 = 30.0;
/// Axis descriptions ("gravito-bending parameter Γ", …).
pub const AXIS_DESC_SIZE: f64 = 25.0;
/// Tick labels.
pub const TICK_LABEL_SIZE: f64 = 21.0;
/// Legend entries.
pub const LEGEND_SIZE: f64 = 19.0;

/// Per-backend correction for vertically centred text.
///
/// The two backends centre text differently: plotters' ab_glyph rasteriser
/// puts `VPos::Center` text about a fifth of the font size above the anchor
/// (measured on DejaVu Sans digits), while the SVG backend leaves it to the
/// viewer (`dy="0.5ex"`), which lands slightly high as well. Without this,
/// y tick labels and legend labels float above their ticks and samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextFix {
    /// Downward shift of centred text, as a fraction of the font size.
    center_shift: f64,
}

impl TextFix {
    /// Correction for `BitMapBackend` (ab_glyph rasteriser).
    pub const BITMAP: Self = Self { center_shift: 0.2 };
    /// Correction for `SVGBackend`: ex ≈ 0.55 em and digits of cap height
    /// ≈ 0.73 em put the digit centre 0.09 em (of the SVG font size, which is
    /// the plotters size / 1.24) above the anchor.
    pub const SVG: Self = Self {
        center_shift: 0.075,
    };

    /// Downward shift in pixels for centred text of `font_size`.
    pub fn center_shift(self, font_size: f64) -> i32 {
        (self.center_shift * font_size).round() as i32
    }
}

/// Outer margin between the canvas edge and the chart, in pixels.
pub const MARGIN: u32 = 18;
/// Space above the title, in pixels.
pub const TITLE_TOP: u32 = 12;
/// Extra space to the right of the plotting area so the last x tick label is
/// not cut off at the canvas edge.
pub const MARGIN_RIGHT: u32 = 36;
/// Length of the (outward) major tick marks, in pixels.
pub const TICK_SIZE: i32 = 7;
/// Length of the minor (unlabelled) tick marks, in pixels.
pub const MINOR_TICK_SIZE: i32 = 4;
/// Gap between tick labels and axis description, in pixels.
pub const DESC_GAP: u32 = 14;

/// Width of the sample line drawn in front of each legend entry, in pixels.
pub const LEGEND_SAMPLE: i32 = 40;
/// Gap between legend sample and label, in pixels.
pub const LEGEND_GAP: i32 = 10;
/// Padding inside the legend box, in pixels.
pub const LEGEND_PADDING: i32 = 10;
/// Distance of the legend box from the plot frame, in pixels.
pub const LEGEND_INSET: i32 = 12;
/// Legend row height as a multiple of the legend font size.
pub const LEGEND_LINE_HEIGHT: f64 = 1.45;
/// Colour of the note shown on a plot without drawable data.
pub const NOTE: RGBColor = RGBColor(0x80, 0x80, 0x80);
/// Legend frame colour.
pub const LEGEND_BORDER: RGBColor = RGBColor(0xB0, 0xB0, 0xB0);

/// Stroke width of an ordinary data curve.
pub const CURVE_WIDTH: u32 = 2;
/// Stroke width of the master (reference) curve: thicker so the numerical
/// curves drawn over it stay visible while it remains the visual backbone.
pub const MASTER_WIDTH: u32 = 6;
/// Marker radius in pixels.
pub const MARKER_SIZE: i32 = 5;
/// Dash length and gap of dashed curves, in pixels.
pub const DASH: (u32, u32) = (12, 7);

/// Okabe–Ito orange, reserved for the master curve.
pub const MASTER_ORANGE: RGBColor = RGBColor(0xE6, 0x9F, 0x00);
/// Fill of the highlighted Γ band: a pale tint of [`MASTER_ORANGE`] (drawn
/// opaque so PNG and SVG look identical).
pub const BAND_FILL: RGBColor = RGBColor(0xFC, 0xE9, 0xC4);
/// Colour of the exact/reference shape.
pub const REFERENCE: RGBColor = RGBColor(0x20, 0x20, 0x20);
/// Axis, frame and tick colour.
pub const AXIS: RGBColor = RGBColor(0x20, 0x20, 0x20);
/// Grid lines at labelled ticks.
pub const GRID_MAJOR: RGBColor = RGBColor(0xDC, 0xDC, 0xDC);
/// Grid lines at unlabelled (minor) ticks.
pub const GRID_MINOR: RGBColor = RGBColor(0xF3, 0xF3, 0xF3);

/// Series colours, chosen to be distinguishable with the common forms of
/// colour blindness: the Okabe–Ito set and the darker members of Paul Tol's
/// "muted" scheme. Orange belongs to the master curve and black to reference
/// shapes, so neither is used here; vermillion comes late because next to
/// the orange master curve it is the hardest to tell apart, and yellow is
/// unreadable on white. Series beyond ten reuse the colours with a different
/// marker shape (see [`series_marker`]).
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0x88, 0x22, 0x55), // wine
    RGBColor(0x99, 0x99, 0x33), // olive
    RGBColor(0x33, 0x22, 0x88), // indigo
    RGBColor(0x44, 0xAA, 0x99), // teal
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x6E, 0x6E, 0x6E), // grey
];

/// Colour of the `i`-th series.
pub fn series_color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Marker shapes, cycled per series so that series stay distinguishable in
/// grey-scale print and for readers who cannot tell the colours apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerShape {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
}

const MARKERS: [MarkerShape; 5] = [
    MarkerShape::Circle,
    MarkerShape::Square,
    MarkerShape::TriangleUp,
    MarkerShape::Diamond,
    MarkerShape::TriangleDown,
];

/// Marker shape of the `i`-th series. The marker cycle is shifted by one
/// each time the palette wraps around, so a (colour, marker) pair repeats
/// only after 50 series.
pub fn series_marker(i: usize) -> MarkerShape {
    MARKERS[(i + i / PALETTE.len()) % MARKERS.len()]
}

/// A pixel position on a drawing area.
pub type Px = (i32, i32);

/// Draws a filled marker of the given shape centred on the pixel `at` of
/// `area`.
///
/// Markers are drawn in pixel space rather than as plotters composed
/// elements: composed elements carry the backend type, and plotters' series
/// API then demands a `'static` backend, which a `BitMapBackend` writing to
/// a runtime path is not.
pub fn draw_marker<DB>(
    area: &DrawingArea<DB, Shift>,
    (x, y): Px,
    shape: MarkerShape,
    color: RGBColor,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    DB: DrawingBackend,
{
    let fill = color.filled();
    let r = MARKER_SIZE;
    // Triangles and diamonds are drawn one pixel larger than the circle so
    // that all shapes look about equally heavy.
    let h = r + 1;
    let t = h * 2 / 3;
    let poly = |pts: &[Px]| {
        Polygon::new(
            pts.iter()
                .map(|&(dx, dy)| (x + dx, y + dy))
                .collect::<Vec<_>>(),
            fill,
        )
    };
    match shape {
        MarkerShape::Circle => area.draw(&Circle::new((x, y), r, fill)),
        MarkerShape::Square => {
            // Same area as the circle.
            let s = (f64::from(r) * 0.886).round() as i32;
            area.draw(&Rectangle::new([(x - s, y - s), (x + s, y + s)], fill))
        }
        MarkerShape::TriangleUp => area.draw(&poly(&[(0, -h), (h, t), (-h, t)])),
        MarkerShape::TriangleDown => area.draw(&poly(&[(0, h), (h, -t), (-h, -t)])),
        MarkerShape::Diamond => area.draw(&poly(&[(0, -h), (h, 0), (0, h), (-h, 0)])),
    }
}

// ---------------------------------------------------------------------------
// Ticks and number formatting
// ---------------------------------------------------------------------------

/// Tick positions of one axis: labelled (major) ticks and unlabelled minor
/// grid positions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Ticks {
    pub major: Vec<f64>,
    pub minor: Vec<f64>,
    /// Number of decimals to print for linear ticks (unused for log axes).
    pub decimals: usize,
}

/// Is `v` (> 0) an integer power of ten? Returns the exponent if so.
fn decade_exponent(v: f64) -> Option<i32> {
    if !(v.is_finite() && v > 0.0) {
        return None;
    }
    let k = v.log10().round();
    ((v / 10f64.powf(k) - 1.0).abs() < 1e-9).then_some(k as i32)
}

/// Ticks for a logarithmic axis over `[lo, hi]` (both > 0).
///
/// Spanning two or more decades, only the decades are labelled (thinned out
/// if there are many) and 2…9 × 10ᵏ become minor grid lines. Within less than
/// two decades a decade-only axis would carry one label or none, so the
/// 1–2–5 sequence (or, if still too sparse, every integer mantissa) is
/// labelled instead.
pub fn log_ticks(lo: f64, hi: f64) -> Ticks {
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
    let k_lo = lo.log10().floor() as i32;
    let k_hi = hi.log10().ceil() as i32;
    let decades: Vec<i32> = (k_lo..=k_hi).filter(|&k| inside(10f64.powi(k))).collect();
    let with_mantissas = |ms: &[f64]| -> Vec<f64> {
        (k_lo..=k_hi)
            .flat_map(|k| ms.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|&v| inside(v))
            .collect()
    };
    let all_mantissas = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];

    if decades.len() >= 2 {
        // Keep at most ~8 labelled decades; with a stride the skipped decades
        // become minor lines and the 2…9 lines are dropped (too dense).
        let stride = decades.len().div_ceil(8) as i32;
        let (major, minor): (Vec<f64>, Vec<f64>) = if stride == 1 {
            let minor = with_mantissas(&all_mantissas[1..]);
            (decades.iter().map(|&k| 10f64.powi(k)).collect(), minor)
        } else {
            let (maj, min): (Vec<i32>, Vec<i32>) =
                decades.iter().partition(|&&k| k.rem_euclid(stride) == 0);
            (
                maj.into_iter().map(|k| 10f64.powi(k)).collect(),
                min.into_iter().map(|k| 10f64.powi(k)).collect(),
            )
        };
        return Ticks {
            major,
            minor,
            decimals: 0,
        };
    }

    let mut major = with_mantissas(&[1.0, 2.0, 5.0]);
    if major.len() < 3 {
        major = with_mantissas(&all_mantissas);
    }
    let minor = with_mantissas(&all_mantissas)
        .into_iter()
        .filter(|v| !major.iter().any(|m| (m / v - 1.0).abs() < 1e-9))
        .collect();
    Ticks {
        major,
        minor,
        decimals: 0,
    }
}

/// A "nice" step (1, 2, 2.5 or 5 × 10ᵏ) giving about `target` intervals over
/// `span`, together with the number of decimals needed to print multiples of
/// it exactly.
pub fn nice_step(span: f64, target: usize) -> (f64, usize) {
    let span = if span.is_finite() && span > 0.0 {
        span
    } else {
        1.0
    };
    let raw = span / target.max(1) as f64;
    let k = raw.log10().floor();
    let base = 10f64.powf(k);
    let (m, extra) = [(1.0, 0), (2.0, 0), (2.5, 1), (5.0, 0), (10.0, 0)]
        .into_iter()
        .find(|(m, _)| m * base >= raw * (1.0 - 1e-9))
        .unwrap_or((10.0, 0));
    let step = m * base;
    // Decimals of the step itself: 0.25 needs 2, 0.5 needs 1, 5 needs 0.
    let decimals = (-(step.log10().floor()) as i32 + extra).max(0) as usize;
    (step, decimals)
}

/// Linear ticks over `[lo, hi]` with about `target` intervals; minor lines
/// halve each interval.
pub fn linear_ticks(lo: f64, hi: f64, target: usize) -> Ticks {
    linear_ticks_with_step(lo, hi, nice_step(hi - lo, target))
}

/// Linear ticks over `[lo, hi]` at multiples of a given step.
pub fn linear_ticks_with_step(lo: f64, hi: f64, (step, decimals): (f64, usize)) -> Ticks {
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    let eps = step * 1e-9;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let mut major = Vec::new();
    let mut minor = Vec::new();
    // Bounded loop: the range holds at most a few dozen steps by construction.
    for i in first.saturating_sub(1)..=last.saturating_add(1) {
        let v = i as f64 * step;
        if v >= lo - eps && v <= hi + eps {
            major.push(v);
        }
        let half = v + step / 2.0;
        if half >= lo - eps && half <= hi + eps {
            minor.push(half);
        }
    }
    Ticks {
        major,
        minor,
        decimals,
    }
}

/// Superscript form of an integer exponent, e.g. `-3` → `⁻³`.
fn superscript(k: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if k < 0 {
        s.push('⁻');
    }
    for c in k.unsigned_abs().to_string().chars() {
        if let Some(d) = c.to_digit(10) {
            s.push(DIGITS[d as usize]);
        }
    }
    s
}

/// Replaces the ASCII hyphen of negative numbers by a typographic minus.
fn typographic_minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(rest) => format!("\u{2212}{rest}"),
        None => s,
    }
}

/// Label of a log-axis tick: decades as 10ᵏ, other values as plain numbers.
pub fn format_log_tick(v: f64) -> String {
    match decade_exponent(v) {
        Some(k) => format!("10{}", superscript(k)),
        None => format_number(v),
    }
}

/// Label of a linear-axis tick printed with a fixed number of decimals.
pub fn format_linear_tick(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    // "-0.0" would suggest a sign where there is none.
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        return s.trim_start_matches('-').to_string();
    }
    typographic_minus(s)
}

/// Compact human-readable number for legends: "10", "10³", "0.5", "2.5×10⁻⁴".
///
/// Powers of ten with |exponent| ≥ 2 use the superscript form, small ones
/// are printed plainly (reads better: "[10, 10³]" rather than "[10¹, 10³]").
pub fn format_number(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    if let Some(k) = decade_exponent(v.abs()) {
        if k.abs() >= 2 {
            let sign = if v < 0.0 { "\u{2212}" } else { "" };
            return format!("{sign}10{}", superscript(k));
        }
    }
    let k = v.abs().log10().floor() as i32;
    if (-3..=4).contains(&k) {
        // Three significant digits, trailing zeros removed.
        let decimals = (2 - k).max(0) as usize;
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        typographic_minus(s)
    } else {
        let m = v / 10f64.powi(k);
        let ms = format!("{m:.2}");
        let ms = ms.trim_end_matches('0').trim_end_matches('.').to_string();
        typographic_minus(format!("{ms}×10{}", superscript(k)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_formatting() {
        assert_eq!(format_number(10.0), "10");
        assert_eq!(format_number(1000.0), "10³");
        assert_eq!(format_number(0.001), "10⁻³");
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(2.5e-4), "2.5×10⁻⁴");
        assert_eq!(format_number(-12.5), "\u{2212}12.5");
        assert_eq!(format_log_tick(1.0), "10⁰");
        assert_eq!(format_log_tick(100.0), "10²");
        assert_eq!(format_linear_tick(-0.0, 1), "0.0");
        assert_eq!(format_linear_tick(-2.5, 1), "\u{2212}2.5");
    }

    #[test]
    fn log_ticks_many_decades_label_decades_only() {
        let t = log_ticks(0.05, 2e4);
        assert_eq!(t.major, vec![0.1, 1.0, 10.0, 100.0, 1000.0, 10000.0]);
        assert!(t.minor.iter().any(|v| (v - 0.06).abs() < 1e-12));
    }

    #[test]
    fn log_ticks_narrow_range_uses_mantissas() {
        let t = log_ticks(2.0, 30.0);
        assert!(t.major.len() >= 3, "{:?}", t.major);
        let t = log_ticks(1e-12, 1e12);
        assert!(t.major.len() <= 9, "{:?}", t.major);
    }

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(10.0, 5), (2.0, 0));
        assert_eq!(nice_step(1.0, 4), (0.25, 2));
        let t = linear_ticks(-1.0, 1.0, 4);
        assert_eq!(t.major, vec![-1.0, -0.5, 0.0, 0.5, 1.0]);
    }
}
