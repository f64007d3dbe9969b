//! Rod and shell shapes as legacy ASCII VTK PolyData for ParaView: one polyline per rod, with
//! the radius (for ParaView's Tube filter: "Vary radius by scalar"), curvature and twist as
//! point data; every shell strip as triangles (POLYGONS), its points after the rods' (radius,
//! curvature and twist 0 there; `rod` numbers rods first, then shells). Numbers are written in shortest round-trip form, so a reader gets the exact values.

use std::fmt::Write;

use slender_core::scene::{CompiledRod, RodResult, ShellResult};

/// The VTK text of one step: every rod of `results` (matched with `rods`) as a polyline and
/// every shell of `shells` as triangles.
pub fn rods_to_vtk(
    title: &str,
    rods: &[CompiledRod],
    results: &[RodResult],
    shells: &[ShellResult],
) -> String {
    let rod_points: usize = results.iter().map(|r| r.positions.len()).sum();
    let n_points: usize = rod_points + shells.iter().map(|r| r.positions.len()).sum::<usize>();
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
    for r in shells {
        for p in &r.positions {
            let _ = writeln!(s, "{:e} {:e} {:e}", p[0], p[1], p[2]);
        }
    }
    if !results.is_empty() {
        let size: usize = results.iter().map(|r| r.positions.len() + 1).sum();
        let _ = writeln!(s, "LINES {} {size}", results.len());
    }
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
    let n_faces: usize = shells.iter().map(|r| r.faces.len()).sum();
    if n_faces > 0 {
        let _ = writeln!(s, "POLYGONS {n_faces} {}", 4 * n_faces);
        for r in shells {
            for f in &r.faces {
                let _ = writeln!(s, "3 {} {} {}", offset + f[0], offset + f[1], offset + f[2]);
            }
            offset += r.positions.len();
        }
    }
    let _ = writeln!(s, "POINT_DATA {n_points}");
    let mut scalar = |name: &str, value: &dyn Fn(usize, &RodResult, usize) -> f64| {
        let _ = writeln!(s, "SCALARS {name} double 1\nLOOKUP_TABLE default");
        for (k, r) in results.iter().enumerate() {
            for i in 0..r.positions.len() {
                let _ = writeln!(s, "{:e}", value(k, r, i));
            }
        }
        // Shells: structure number for `rod`, 0 for the rod-only quantities.
        for (k, r) in shells.iter().enumerate() {
            let v = if name == "rod" {
                (results.len() + k) as f64
            } else {
                0.0
            };
            for _ in 0..r.positions.len() {
                let _ = writeln!(s, "{v:e}");
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

/// The rods of one step as VTK XML PolyData (`.vtp`, ASCII): the same polylines and point
/// data as [`rods_to_vtk`], in the format a ParaView collection (`.pvd`) lists.
pub fn rods_to_vtp(rods: &[CompiledRod], results: &[RodResult]) -> String {
    let n_points: usize = results.iter().map(|r| r.positions.len()).sum();
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <PolyData>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{n_points}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">",
        results.len()
    );
    s.push_str("      <PointData Scalars=\"radius\">\n");
    let mut array = |name: &str, value: &dyn Fn(usize, &RodResult, usize) -> f64| {
        let _ = write!(
            s,
            "        <DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
        );
        for (k, r) in results.iter().enumerate() {
            for i in 0..r.positions.len() {
                let _ = write!(s, " {:e}", value(k, r, i));
            }
        }
        s.push_str(" </DataArray>\n");
    };
    array("radius", &|k, _, _| rods[k].display_radius);
    array("curvature", &|_, r, i| {
        (r.curvature[i][0].powi(2) + r.curvature[i][1].powi(2)).sqrt()
    });
    array("twist", &|_, r, i| r.twist[i]);
    array("rod", &|k, _, _| k as f64);
    s.push_str("      </PointData>\n      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">");
    for r in results {
        for p in &r.positions {
            let _ = write!(s, " {:e} {:e} {:e}", p[0], p[1], p[2]);
        }
    }
    s.push_str(" </DataArray>\n      </Points>\n      <Lines>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">");
    for i in 0..n_points {
        let _ = write!(s, " {i}");
    }
    s.push_str(
        " </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">",
    );
    let mut offset = 0;
    for r in results {
        offset += r.positions.len();
        let _ = write!(s, " {offset}");
    }
    s.push_str(" </DataArray>\n      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n");
    s
}
