//! PNG/SVG preview of a solved scene: three orthographic views (plus an isometric one) of the
//! rest shape, the loaded equilibrium and, with prescribed motion, the last step.

use std::path::Path;

use anyhow::Result;
use slender_core::scene::{CompiledScene, SceneStep};

use crate::plot::{plot_shape_views, Polyline3};

/// Writes `<stem>.png` and `<stem>.svg`.
pub fn write_preview(scene: &CompiledScene, steps: &[SceneStep], stem: &Path) -> Result<()> {
    let mut shapes = Vec::new();
    for (r, rod) in scene.rods.iter().enumerate() {
        let rest: Vec<[f64; 3]> = scene
            .rest_positions(r)
            .iter()
            .map(|p| [p.x, p.y, p.z])
            .collect();
        shapes.push(Polyline3 {
            label: format!("{} at rest", rod.name),
            points: rest,
            markers: false,
        });
    }
    for (k, sh) in steps[0].shells.iter().enumerate() {
        let rest: Vec<[f64; 3]> = scene.shells[k]
            .rest_positions()
            .iter()
            .map(|p| [p.x, p.y, p.z])
            .collect();
        shapes.push(Polyline3 {
            label: format!("{} at rest", sh.name),
            points: strip_grid(&rest, sh.elements),
            markers: false,
        });
        shapes.push(Polyline3 {
            label: format!("{} equilibrium", sh.name),
            points: strip_grid(&sh.positions, sh.elements),
            markers: false,
        });
    }
    let last = steps.len() - 1;
    let shown: &[usize] = if last == 0 { &[0] } else { &[0, last] };
    for &k in shown {
        for r in &steps[k].rods {
            shapes.push(Polyline3 {
                label: format!("{} step {k}", r.name),
                points: r.positions.clone(),
                // Nodes are marked only where they stay readable.
                markers: r.positions.len() <= 61,
            });
        }
    }
    let title = if let Some(t) = steps[last].time.as_ref().filter(|_| last > 0) {
        format!(
            "slender solve: rest state and frame {last} (t = {:.4} s)",
            t.t
        )
    } else if last == 0 {
        "slender solve: equilibrium".to_string()
    } else {
        format!("slender solve: equilibrium and step {last} of the motion")
    };
    plot_shape_views(stem, &title, &shapes)
}

/// A strip's mesh lines as one polyline broken by NaN points: the lines along the length
/// (one per column) and across the width (one per station).
fn strip_grid(positions: &[[f64; 3]], [nl, nw]: [usize; 2]) -> Vec<[f64; 3]> {
    let v = |i: usize, j: usize| positions[i * (nw + 1) + j];
    let mut out = Vec::new();
    for j in 0..=nw {
        out.extend((0..=nl).map(|i| v(i, j)));
        out.push([f64::NAN; 3]);
    }
    for i in 0..=nl {
        out.extend((0..=nw).map(|j| v(i, j)));
        out.push([f64::NAN; 3]);
    }
    out
}
