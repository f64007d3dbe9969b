//! Box plots side by side, one panel per grouping (counterpart of the seed's Fig. 12: the
//! percentage of correct 2-D/3-D decisions grouped by each design parameter).
//!
//! Quartiles by linear interpolation between order statistics (the method of plotters'
//! `Quartiles`, computed here in f64: `Quartiles::values` rounds to f32, which turned every
//! value of a zero-width box into an "outlier"); whiskers reach the most extreme values within
//! 1.5 IQR of the box, values beyond are drawn as points.

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{render, style, titled_area, Figure, TextFix};

/// One box: a label and its values (non-finite values are ignored).
#[derive(Clone, Debug, PartialEq)]
pub struct BoxSample {
    /// Category label under the box.
    pub label: String,
    /// The distribution.
    pub values: Vec<f64>,
}

/// One panel: a grouping parameter and one box per value of it.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxPanel {
    /// The parameter (x-axis description).
    pub title: String,
    /// Boxes, left to right.
    pub boxes: Vec<BoxSample>,
}

/// Draws the panels side by side with a common y range `y_range`; writes `<stem>.png` and
/// `<stem>.svg`.
pub fn plot_boxplots(
    stem: &Path,
    title: &str,
    y_desc: &str,
    y_range: (f64, f64),
    panels: &[BoxPanel],
) -> Result<()> {
    render(
        stem,
        &BoxFigure {
            title,
            y_desc,
            y_range,
            panels,
        },
    )
}

struct BoxFigure<'a> {
    title: &'a str,
    y_desc: &'a str,
    y_range: (f64, f64),
    panels: &'a [BoxPanel],
}

/// Box statistics: quartiles, whisker ends and outliers.
#[derive(Clone, Debug)]
struct BoxStats {
    /// Lower quartile, median, upper quartile.
    quartiles: [f64; 3],
    whiskers: (f64, f64),
    outliers: Vec<f64>,
}

fn box_stats(values: &[f64]) -> Option<BoxStats> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    let mut sorted = v.clone();
    sorted.sort_by(f64::total_cmp);
    let quartiles = [0.25, 0.5, 0.75].map(|p| percentile(&sorted, p));
    let [q1, _, q3] = quartiles;
    let iqr = q3 - q1;
    let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
    let inside = v
        .iter()
        .copied()
        .filter(|x| *x >= lo_fence && *x <= hi_fence);
    let whiskers = (
        inside.clone().fold(f64::INFINITY, f64::min),
        inside.fold(f64::NEG_INFINITY, f64::max),
    );
    let outliers = v
        .iter()
        .copied()
        .filter(|x| *x < lo_fence || *x > hi_fence)
        .collect();
    Some(BoxStats {
        quartiles,
        whiskers,
        outliers,
    })
}

/// The `p`-quantile (0 ≤ p ≤ 1) of non-empty ascending `sorted`, interpolated linearly
/// between the order statistics at rank p·(n − 1).
fn percentile(sorted: &[f64], p: f64) -> f64 {
    let rank = p * (sorted.len() - 1) as f64;
    let i = rank.floor() as usize;
    let d = rank - i as f64;
    match sorted.get(i + 1) {
        Some(next) => sorted[i] + (next - sorted[i]) * d,
        None => sorted[i],
    }
}

impl Figure for BoxFigure<'_> {
    fn size(&self) -> (u32, u32) {
        style::WIDE_CANVAS
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>, fix: TextFix) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let area = titled_area(root, self.title)?;
        let n = self.panels.len().max(1);
        let cells = area.split_evenly((1, n));
        let tick_font = (style::FAMILY, style::TICK_LABEL_SIZE)
            .into_font()
            .color(&style::AXIS);
        let desc_font = (style::FAMILY, style::AXIS_DESC_SIZE)
            .into_font()
            .color(&style::AXIS);
        let (y_lo, y_hi) = self.y_range;
        for (k, (panel, cell)) in self.panels.iter().zip(&cells).enumerate() {
            let m = panel.boxes.len().max(1);
            let mut chart = ChartBuilder::on(cell)
                .margin(style::MARGIN)
                .x_label_area_size(70)
                .y_label_area_size(if k == 0 { 90 } else { 50 })
                .build_cartesian_2d(0.0..m as f64, y_lo..y_hi)?;
            let labels: Vec<String> = panel.boxes.iter().map(|b| b.label.clone()).collect();
            let x_fmt = |v: &f64| {
                let i = v.floor() as usize;
                // Labels sit at box centres (i + 0.5); other key points stay blank.
                if (v - (i as f64 + 0.5)).abs() < 1e-9 {
                    labels.get(i).cloned().unwrap_or_default()
                } else {
                    String::new()
                }
            };
            chart
                .configure_mesh()
                .disable_x_mesh()
                .light_line_style(style::GRID_MINOR.stroke_width(1))
                .bold_line_style(style::GRID_MAJOR.stroke_width(1))
                .x_labels(2 * m + 1)
                .x_label_formatter(&x_fmt)
                .y_label_offset(fix.center_shift(style::TICK_LABEL_SIZE))
                .x_label_style(tick_font.clone())
                .y_label_style(tick_font.clone())
                .axis_desc_style(desc_font.clone())
                .x_desc(panel.title.as_str())
                .y_desc(if k == 0 { self.y_desc } else { "" })
                .draw()?;
            for (i, b) in panel.boxes.iter().enumerate() {
                let Some(s) = box_stats(&b.values) else {
                    continue;
                };
                let c = i as f64 + 0.5;
                let half = 0.25;
                let [q1, med, q3] = s.quartiles;
                let color = style::series_color(k);
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(c - half, q1), (c + half, q3)],
                    color.mix(0.25).filled(),
                )))?;
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(c - half, q1), (c + half, q3)],
                    color.stroke_width(2),
                )))?;
                let line = |a: (f64, f64), b: (f64, f64), w: u32| {
                    PathElement::new(vec![a, b], style::AXIS.stroke_width(w))
                };
                chart.draw_series([
                    line((c - half, med), (c + half, med), 3),
                    line((c, q3), (c, s.whiskers.1), 1),
                    line((c, q1), (c, s.whiskers.0), 1),
                    line(
                        (c - half / 2.0, s.whiskers.1),
                        (c + half / 2.0, s.whiskers.1),
                        1,
                    ),
                    line(
                        (c - half / 2.0, s.whiskers.0),
                        (c + half / 2.0, s.whiskers.0),
                        1,
                    ),
                ])?;
                chart.draw_series(
                    s.outliers
                        .iter()
                        .map(|&y| Circle::new((c, y), 4, style::AXIS.stroke_width(1))),
                )?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::test_util::{assert_rendered, fresh_dir};

    #[test]
    fn whiskers_and_outliers_follow_the_1_5_iqr_rule() {
        // 1..=9 and an outlier at 100: Q1 = 3, Q3 = 7 (linear interpolation), fences −3, 13.
        let mut v: Vec<f64> = (1..=9).map(f64::from).collect();
        v.push(100.0);
        let s = box_stats(&v).unwrap();
        assert_eq!(s.outliers, vec![100.0]);
        assert_eq!(s.whiskers, (1.0, 9.0));
        assert!(box_stats(&[f64::NAN]).is_none());
        // A zero-width box (every configuration scored the same) has no outliers and its
        // whiskers on the box.
        let s = box_stats(&[88.88888888888889; 4]).unwrap();
        assert!(s.outliers.is_empty());
        assert_eq!(s.whiskers, (88.88888888888889, 88.88888888888889));
        // plotters' documented example: quartiles 20.25, 37.5, 39.75.
        let s = box_stats(&[7.0, 15.0, 36.0, 39.0, 40.0, 41.0]).unwrap();
        assert_eq!(s.quartiles, [20.25, 37.5, 39.75]);
    }

    #[test]
    fn renders_png_and_svg() {
        let dir = fresh_dir("boxplot");
        let stem = dir.join("boxplot");
        let title = "Correct decisions by parameter";
        let panel = |name: &str, labels: &[&str]| BoxPanel {
            title: name.into(),
            boxes: labels
                .iter()
                .enumerate()
                .map(|(i, l)| BoxSample {
                    label: l.to_string(),
                    values: (0..12).map(|j| 70.0 + 2.0 * i as f64 + j as f64).collect(),
                })
                .collect(),
        };
        let panels = vec![
            panel("Ω", &["shell", "combined", "IPS"]),
            panel("n_L", &["8", "15", "20", "30", "45", "60"]),
            panel("m_ls", &["1", "3", "5"]),
            panel("σ", &["0.1", "0.2", "0.3", "0.4"]),
        ];
        plot_boxplots(&stem, title, "correct decisions (%)", (0.0, 100.0), &panels)
            .expect("plot renders");
        assert_rendered(&stem, title);
    }
}
