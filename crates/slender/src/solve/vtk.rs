//! Rod shapes as legacy ASCII VTK PolyData for ParaView: one polyline per rod, with the
//! radius (for ParaView's Tube filter: "Vary radius by scalar"), curvature and twist as point
//! data. Numbers are written in shortest round-trip form, so a reader gets the exact values.

use std::fmt::Write;

use slender_core::scene::{CompiledRod, RodResult};

/// The VTK text of one step: every rod of `results` (matched with `rods`) as a polyline.
pub fn rods_to_vtk(title: &str, rods: &[CompiledRod], results: &[RodResult]) -> String {
    let n_points: usize = results.iter().map(|r| r.positions.len()).sum();
    let mut s = String::new();
    let title: String = title.chars().filter(|c| *c != '\n').take(250).collect();
    let _ = writeln!(
        s,
        "# vtk DataFile Version 3.0\n{title}\nASCII\nDATASET POLYDATA"
    );
    let _ = writeln!(s, "POINTS {n_points} double");
    for r in results {
        for p in &r.positions {
            let _ = writeln!(s, "{:e} {:e} {:e}", p[0], p[1], p[2]);
        }
    }
    let size: usize = results.iter().map(|r| r.positions.len() + 1).sum();
    let _ = writeln!(s, "LINES {} {size}", results.len());
    let mut offset = 0;
    for r in results {
        let n = r.positions.len();
        let _ = write!(s, "{n}");
        for i in 0..n {
            let _ = write!(s, " {}", offset + i);
        }
        s.push('\n');
        offset += n;
    }
    let _ = writeln!(s, "POINT_DATA {n_points}");
    let mut scalar = |name: &str, value: &dyn Fn(usize, &RodResult, usize) -> f64| {
        let _ = writeln!(s, "SCALARS {name} double 1\nLOOKUP_TABLE default");
        for (k, r) in results.iter().enumerate() {
            for i in 0..r.positions.len() {
                let _ = writeln!(s, "{:e}", value(k, r, i));
            }
        }
    };
    scalar("radius", &|k, _, _| rods[k].display_radius);
    scalar("curvature", &|_, r, i| {
        (r.curvature[i][0].powi(2) + r.curvature[i][1].powi(2)).sqrt()
    });
    scalar("twist", &|_, r, i| r.twist[i]);
    scalar("rod", &|k, _, _| k as f64);
    s
}
