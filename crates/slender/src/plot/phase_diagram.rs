//! 2-D / 3-D phase diagram over a log–log parameter plane (counterpart of the
//! seed's Fig. 8b: the ground truth in the background and simulations as
//! diamonds, green for 3-D and orange for 2-D states).

use std::path::Path;

use anyhow::{bail, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::height_map::{
    clip_runs, draw_diamond, draw_key, draw_overlays, key_layout, overlay_styles, DiamondStyle,
    KeyEntry, KeyGlyph, Overlay,
};
use super::{
    builder, draw_frame, draw_mesh, drawable_runs, label_areas, render, style, titled_area, Axis,
    Figure, Scale, TextFix,
};

/// State of the rod at one parameter point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Planar (in-plane) equilibrium.
    TwoD,
    /// Out-of-plane (bend–twist) equilibrium.
    ThreeD,
    /// The simulation gave no verdict.
    NotConverged,
}

/// One simulated parameter point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhasePoint {
    pub x: f64,
    pub y: f64,
    pub phase: Phase,
    /// The protocol's verdict disagrees with the stability analysis: drawn
    /// with a black ring around the marker.
    pub disagrees: bool,
}

/// Canvas size (the key goes to the right of the plot).
const CANVAS: (u32, u32) = (1400, 860);
/// Number of background cells along each axis.
const BACKGROUND_CELLS: usize = 150;

/// Background of the 3-D region: a pale green.
const BG_3D: RGBColor = RGBColor(0xCF, 0xEB, 0xC6);
/// Background of the 2-D region: a pale orange.
const BG_2D: RGBColor = RGBColor(0xFD, 0xDD, 0xB4);
/// Markers: a dark green and a bright orange, so that the two also differ in
/// lightness (for readers who cannot tell green from orange).
const POINT_3D: RGBColor = RGBColor(0x1B, 0x78, 0x37);
const POINT_2D: RGBColor = RGBColor(0xF5, 0x8A, 0x07);
const POINT_EDGE: RGBColor = RGBColor(0x20, 0x20, 0x20);
const POINT_NONE: RGBColor = RGBColor(0x80, 0x80, 0x80);

/// Plots a 2-D / 3-D phase diagram on log–log axes over `x_range` ×
/// `y_range`.
///
/// The background shows `truth_3d` sampled at the centres of a 150 × 150
/// grid of cells (log-spaced): pale green where it says 3-D, pale orange for
/// 2-D, white where it is unknown (`None`). `points` are drawn as diamonds
/// (green 3-D, orange 2-D, hollow grey not converged), with a black ring
/// where `disagrees` is set; points outside the ranges or not finite are
/// left out. `overlays` are drawn on top of the background, clipped to the
/// ranges. A key to the right explains everything.
///
/// Writes `<stem>.png` and `<stem>.svg`. Fails if a range is not a positive,
/// finite, non-empty interval.
#[allow(clippy::too_many_arguments)]
pub fn plot_phase_diagram(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x_range: (f64, f64),
    y_range: (f64, f64),
    truth_3d: &dyn Fn(f64, f64) -> Option<bool>,
    points: &[PhasePoint],
    overlays: &[Overlay],
) -> Result<()> {
    plot_phase_diagram_labeled(
        stem,
        title,
        (x_label, y_label),
        (x_range, y_range),
        truth_3d,
        points,
        overlays,
        &PhaseLabels::BEND_TWIST,
    )
}

/// What the two phases and a ringed point mean, in the key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseLabels {
    /// The phase drawn green ([`Phase::ThreeD`], `true` in the ground truth).
    pub yes: &'static str,
    /// The phase drawn orange ([`Phase::TwoD`], `false` in the ground truth).
    pub no: &'static str,
    /// A ringed point (`disagrees`).
    pub ring: &'static str,
}

impl PhaseLabels {
    /// 3-D / 2-D, rings where the protocol disagrees with stability.
    pub const BEND_TWIST: PhaseLabels = PhaseLabels {
        yes: "3-D",
        no: "2-D",
        ring: "protocol disagrees with stability",
    };
}

/// [`plot_phase_diagram`] with the phases named by `labels` (e.g. slide / stick).
#[allow(clippy::too_many_arguments)]
pub fn plot_phase_diagram_labeled(
    stem: &Path,
    title: &str,
    (x_label, y_label): (&str, &str),
    (x_range, y_range): ((f64, f64), (f64, f64)),
    truth_3d: &dyn Fn(f64, f64) -> Option<bool>,
    points: &[PhasePoint],
    overlays: &[Overlay],
    labels: &PhaseLabels,
) -> Result<()> {
    let x_range = log_range(x_range, "x", title)?;
    let y_range = log_range(y_range, "y", title)?;
    // Sampled once here, not per backend: the ground truth may be costly.
    let centres = |(lo, hi): (f64, f64)| -> Vec<f64> {
        let (a, b) = (lo.log10(), hi.log10());
        (0..BACKGROUND_CELLS)
            .map(|i| 10f64.powf(a + (b - a) * (i as f64 + 0.5) / BACKGROUND_CELLS as f64))
            .collect()
    };
    let (xc, yc) = (centres(x_range), centres(y_range));
    let truth = yc
        .iter()
        .map(|&y| xc.iter().map(|&x| truth_3d(x, y)).collect())
        .collect();
    render(
        stem,
        &PhaseFigure {
            title,
            x_label,
            y_label,
            x_range,
            y_range,
            truth,
            points,
            overlays,
            labels: *labels,
        },
    )
}

/// Checks a log-axis range and puts it in ascending order.
fn log_range((a, b): (f64, f64), which: &str, title: &str) -> Result<(f64, f64)> {
    if !(Scale::Log.accepts(a) && Scale::Log.accepts(b)) {
        bail!(
            "phase diagram {title:?}: the {which} range [{a}, {b}] is not an interval of \
             positive finite numbers (the axes are logarithmic)"
        );
    }
    if a == b {
        // One column or row of points (e.g. a grid with a single X): a quarter decade either
        // side, as the height maps draw a single cell.
        let pad = 10f64.powf(0.25);
        return Ok((a / pad, a * pad));
    }
    Ok((a.min(b), a.max(b)))
}

struct PhaseFigure<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    x_range: (f64, f64),
    y_range: (f64, f64),
    /// `truth[row][col]` at the background cell centres, rows upwards.
    truth: Vec<Vec<Option<bool>>>,
    points: &'a [PhasePoint],
    overlays: &'a [Overlay],
    labels: PhaseLabels,
}

/// Just the ring that marks a disagreeing point.
const RING_ONLY: DiamondStyle = DiamondStyle {
    fill: None,
    edge: WHITE,
    edge_width: 0,
    ring: true,
};

/// Marker of a point.
fn point_style(p: &PhasePoint) -> DiamondStyle {
    let (fill, edge, edge_width) = match p.phase {
        Phase::ThreeD => (Some(POINT_3D), POINT_EDGE, 1),
        Phase::TwoD => (Some(POINT_2D), POINT_EDGE, 1),
        Phase::NotConverged => (Some(WHITE), POINT_NONE, 2),
    };
    DiamondStyle {
        fill,
        edge,
        edge_width,
        ring: p.disagrees,
    }
}

impl PhaseFigure<'_> {
    /// Key entries: background, points, overlays. Categories that do not
    /// occur are left out, except the four main ones.
    fn key_entries(&self) -> Vec<KeyEntry> {
        let cells = || self.truth.iter().flatten();
        let mut e = vec![
            KeyEntry::new(
                &format!("{} (ground truth)", self.labels.yes),
                KeyGlyph::Swatch(BG_3D),
            ),
            KeyEntry::new(
                &format!("{} (ground truth)", self.labels.no),
                KeyGlyph::Swatch(BG_2D),
            ),
        ];
        if cells().any(Option::is_none) {
            e.push(KeyEntry::new(
                "ground truth unknown",
                KeyGlyph::Swatch(WHITE),
            ));
        }
        let marker = |phase, disagrees| {
            KeyGlyph::Diamond(point_style(&PhasePoint {
                x: 1.0,
                y: 1.0,
                phase,
                disagrees,
            }))
        };
        e.push(KeyEntry::new(
            &format!("{} (simulation)", self.labels.yes),
            marker(Phase::ThreeD, false),
        ));
        e.push(KeyEntry::new(
            &format!("{} (simulation)", self.labels.no),
            marker(Phase::TwoD, false),
        ));
        if self.points.iter().any(|p| p.phase == Phase::NotConverged) {
            e.push(KeyEntry::new(
                "not converged",
                marker(Phase::NotConverged, false),
            ));
        }
        if self.points.iter().any(|p| p.disagrees) {
            e.push(KeyEntry::new(
                self.labels.ring,
                KeyGlyph::Diamond(RING_ONLY),
            ));
        }
        e.extend(
            self.overlays
                .iter()
                .zip(overlay_styles(self.overlays))
                .filter(|(o, _)| !o.label.is_empty())
                .map(|(o, st)| KeyEntry::new(&o.label, KeyGlyph::Line(st))),
        );
        e
    }
}

impl Figure for PhaseFigure<'_> {
    fn size(&self) -> (u32, u32) {
        CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let x = Axis::new(Scale::Log, self.x_range, self.x_label);
        let y = Axis::new(Scale::Log, self.y_range, self.y_label);

        let area = titled_area(root, self.title)?;
        let entries = self.key_entries();
        let (w, h) = area.dim_in_pixel();
        let (w, h) = (w as i32, h as i32);
        let margin = style::MARGIN as i32;
        // The key goes to the right in one column, unless that would take
        // more than 40 % of the width (long overlay labels); then below.
        let side = key_layout(&area, &entries, 1)?.filter(|k| k.w + 2 * margin <= w * 2 / 5);
        let (plot_area, key_area, key, key_right) = match side {
            Some(k) => {
                let (p, a) = area.split_horizontally((w - k.w - 2 * margin).max(1));
                (p, a, Some(k), true)
            }
            None => {
                let k = key_layout(&area, &entries, w - 2 * margin)?;
                let strip = k.map_or(0, |k| k.h + margin);
                let (p, a) = area.split_vertically((h - strip).max(1));
                (p, a, k, false)
            }
        };

        let mut chart = builder(&plot_area, label_areas(&plot_area, &x, &y)?)
            .build_cartesian_2d(x.coord(), y.coord())?;

        // The background covers the grid (pale grid lines over pale colours
        // only add noise; the ticks on the frame remain). Cells of a row with
        // the same state are merged into one rectangle to keep the SVG small.
        draw_mesh(&mut chart, &x, &y, fix)?;
        let n = BACKGROUND_CELLS as f64;
        let (lx, ly) = ((x.lo.log10(), x.hi.log10()), (y.lo.log10(), y.hi.log10()));
        let edge = |(a, b): (f64, f64), i: usize| 10f64.powf(a + (b - a) * i as f64 / n);
        let mut rects = Vec::new();
        for (r, row) in self.truth.iter().enumerate() {
            let mut c0 = 0;
            for c in 1..=row.len() {
                if c == row.len() || row[c] != row[c0] {
                    let color = match row[c0] {
                        Some(true) => Some(BG_3D),
                        Some(false) => Some(BG_2D),
                        None => None,
                    };
                    if let Some(color) = color {
                        rects.push(Rectangle::new(
                            [(edge(lx, c0), edge(ly, r + 1)), (edge(lx, c), edge(ly, r))],
                            color.filled(),
                        ));
                    }
                    c0 = c;
                }
            }
        }
        chart.draw_series(rects)?;

        let styles = overlay_styles(self.overlays);
        let runs: Vec<_> = self
            .overlays
            .iter()
            .map(|o| clip_runs(&drawable_runs(&o.points, Scale::Log, Scale::Log), &x, &y))
            .collect();
        draw_overlays(&mut chart, &runs, &styles)?;

        draw_frame(&plot_area, &chart, &x, &y)?;

        // Points in pixel space, on the whole panel rather than the plotting
        // area: a point on the edge of the range is drawn whole, over the
        // frame, instead of being squashed against it. Converged points go
        // last so that hollow ones never hide them, rings on top of all.
        let (bx, by) = plot_area.get_base_pixel();
        let tol = 1e-9;
        let within = |v: f64, a: &Axis| v >= a.lo * (1.0 - tol) && v <= a.hi * (1.0 + tol);
        let visible = |p: &&PhasePoint| {
            Scale::Log.accepts(p.x) && Scale::Log.accepts(p.y) && within(p.x, &x) && within(p.y, &y)
        };
        let pixel = |p: &PhasePoint| {
            let (px, py) = chart.backend_coord(&(p.x, p.y));
            (px - bx, py - by)
        };
        let mut order: Vec<&PhasePoint> = self.points.iter().filter(visible).collect();
        order.sort_by_key(|p| p.phase != Phase::NotConverged);
        for p in &order {
            let st = DiamondStyle {
                ring: false,
                ..point_style(p)
            };
            draw_diamond(&plot_area, pixel(p), &st)?;
        }
        for p in order.iter().filter(|p| p.disagrees) {
            draw_diamond(&plot_area, pixel(p), &RING_ONLY)?;
        }

        if let Some(k) = key {
            let (plot_x, plot_top) = chart.plotting_area().get_base_pixel();
            let (plot_w, _) = chart.plotting_area().dim_in_pixel();
            let (key_x, key_top) = key_area.get_base_pixel();
            let origin = if key_right {
                // Top-aligned with the plotting area.
                (0, plot_top - key_top)
            } else {
                // Centred below the plotting area.
                let centre = plot_x - key_x + plot_w as i32 / 2;
                ((centre - k.w / 2).clamp(0, (w - k.w).max(0)), 0)
            };
            draw_key(&key_area, &entries, &k, origin, fix)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::height_map::tests::{log_grid, synthetic_overlays};
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    /// 3-D inside the wedge 0.3 < Y·√X < 3 of the synthetic overlays, 2-D
    /// outside, unknown in a corner.
    fn truth(x: f64, y: f64) -> Option<bool> {
        if x > 30.0 && y > 3.0 {
            return None;
        }
        let s = y * x.sqrt();
        Some(s > 0.3 && s < 3.0)
    }

    fn synthetic_points() -> Vec<PhasePoint> {
        let mut pts = Vec::new();
        for (i, &x) in log_grid(-1.0, 2.0, 10).iter().enumerate() {
            for (j, &y) in log_grid(-2.0, 1.0, 9).iter().enumerate() {
                let three_d = truth(x, y).unwrap_or(false);
                // A few wrong verdicts near the boundaries, a few failures.
                let flip = (i + 2 * j) % 11 == 0;
                let phase = if (i * 7 + j * 3) % 17 == 0 {
                    Phase::NotConverged
                } else if three_d != flip {
                    Phase::ThreeD
                } else {
                    Phase::TwoD
                };
                pts.push(PhasePoint {
                    x,
                    y,
                    phase,
                    disagrees: flip && phase != Phase::NotConverged,
                });
            }
        }
        pts
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("phase");
        let stem = dir.join("phase_diagram");
        let title = "Bend–twist: 2-D / 3-D states, protocol vs ground truth";
        plot_phase_diagram(
            &stem,
            title,
            "X (gravity / bending)",
            "Y (curvature × length)",
            // The ranges of the points themselves: edge points drawn whole.
            (0.1, 100.0),
            (0.01, 10.0),
            &truth,
            &synthetic_points(),
            &synthetic_overlays(),
        )
        .expect("plot renders");
        assert_rendered(&stem, title);

        // Long overlay labels move the key below the plot; unlabelled
        // overlays stay out of it.
        let stem = dir.join("phase_diagram_long_labels");
        let mut overlays = synthetic_overlays();
        overlays[0].label = "master curve: X_c1, where the planar coil loses its stability".into();
        overlays[3].label.clear();
        plot_phase_diagram(
            &stem,
            "long key",
            "X",
            "Y",
            (0.05, 200.0),
            (5e-3, 20.0),
            &truth,
            &synthetic_points(),
            &overlays,
        )
        .expect("plot renders");
        assert_rendered(&stem, "long key");
    }

    #[test]
    fn nan_points_empty_inputs_and_bad_ranges() {
        let dir = fresh_dir("phase-degenerate");
        let stem = dir.join("phase_nan");
        let mut pts = synthetic_points();
        pts[0].x = f64::NAN;
        pts[1].y = -1.0;
        pts[2].x = 1e9; // outside the range
        let mut overlays = synthetic_overlays();
        overlays[1].points[10] = (f64::INFINITY, f64::NAN);
        plot_phase_diagram(
            &stem,
            "phase diagram with holes",
            "X",
            "Y",
            (200.0, 0.05), // reversed on purpose
            (5e-3, 20.0),
            &|x, y| if x.is_nan() { Some(true) } else { truth(x, y) },
            &pts,
            &overlays,
        )
        .expect("undrawable points are skipped");
        assert_rendered(&stem, "phase diagram with holes");

        let stem = dir.join("phase_empty");
        plot_phase_diagram(
            &stem,
            "empty phase diagram",
            "X",
            "Y",
            (1.0, 10.0),
            (1.0, 10.0),
            &|_, _| None,
            &[],
            &[],
        )
        .expect("empty diagram renders");
        assert_rendered(&stem, "empty phase diagram");

        // A single column of points (one X): a quarter decade either side.
        let stem_single = dir.join("phase_single_column");
        plot_phase_diagram(
            &stem_single,
            "one column",
            "X",
            "Y",
            (2.0, 2.0),
            (0.1, 10.0),
            &truth,
            &[PhasePoint {
                x: 2.0,
                y: 1.0,
                phase: Phase::ThreeD,
                disagrees: false,
            }],
            &[],
        )
        .expect("a one-column diagram renders");
        assert_rendered(&stem_single, "one column");

        for bad in [(0.0, 1.0), (f64::NAN, 2.0), (1.0, f64::INFINITY)] {
            let err =
                plot_phase_diagram(&stem, "bad", "X", "Y", bad, (1.0, 10.0), &truth, &[], &[])
                    .expect_err("bad range is an error");
            assert!(err.to_string().contains("x range"), "{err}");
        }
    }
}
