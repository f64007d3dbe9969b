//! PNG/SVG preview of a solved scene: three orthographic views (plus an isometric one) of the
//! rest shape, the loaded equilibrium and, with prescribed motion, the last step.

use std::path::Path;

use anyhow::Result;
use slender_core::scene::{CompiledScene, SceneStep};

use crate::plot::{plot_shape_views, Polyline3};

/// Writes `<stem>.png` and `<stem>.svg`.
pub fn write_preview(scene: &CompiledScene, steps: &[SceneStep], stem: &Path) -> Result<()> {
    let mut shapes = Vec::new();
    for rod in &scene.rods {
        let mut rest = Vec::new();
        for seg in &rod.segments {
            let skip = usize::from(!rest.is_empty());
            rest.extend(
                seg.rod.rest_state().positions()[skip..]
                    .iter()
                    .map(|p| [p.x, p.y, p.z]),
            );
        }
        shapes.push(Polyline3 {
            label: format!("{} at rest", rod.name),
            points: rest,
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
    let title = if last == 0 {
        "slender solve: equilibrium".to_string()
    } else {
        format!("slender solve: equilibrium and step {last} of the motion")
    };
    plot_shape_views(stem, &title, &shapes)
}
