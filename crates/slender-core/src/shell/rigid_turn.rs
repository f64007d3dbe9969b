//! Turning a free-DOF vector with a rigidly turned shell (both discretizations): the position
//! blocks (a vertex or control point's x, y, z) turn, other DOFs (angles measured from the
//! faces) do not. The continuation's chord predictor uses it to solve for the Newton step of
//! a strip turned with its clamp with the factorization from before the turn (see
//! [`EquilibriumProblem::turn_free`](crate::solver::EquilibriumProblem::turn_free)).

use std::collections::HashMap;

use nalgebra::Rotation3;

use crate::geometry::Vec3;

/// Turns the position blocks of `v` (length `n`, free DOFs) by `turn`; `position(i)` is the
/// point and component (0–2) of free DOF `i`, `None` for a DOF that does not turn. Returns
/// false, leaving `v` alone, if some point has only part of its components free (its block
/// cannot be turned within the free DOFs).
pub fn turn_vertex_blocks(
    n: usize,
    position: impl Fn(usize) -> Option<(usize, usize)>,
    turn: &Rotation3<f64>,
    v: &mut [f64],
) -> bool {
    // Free DOF of each component, per point.
    let mut blocks: HashMap<usize, [Option<usize>; 3]> = HashMap::new();
    for i in 0..n {
        if let Some((point, c)) = position(i) {
            blocks.entry(point).or_insert([None; 3])[c] = Some(i);
        }
    }
    let mut full = Vec::with_capacity(blocks.len());
    for block in blocks.values() {
        match block {
            [Some(x), Some(y), Some(z)] => full.push([*x, *y, *z]),
            _ => return false,
        }
    }
    for [x, y, z] in full {
        let turned = turn * Vec3::new(v[x], v[y], v[z]);
        v[x] = turned.x;
        v[y] = turned.y;
        v[z] = turned.z;
    }
    true
}
