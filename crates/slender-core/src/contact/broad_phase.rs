//! The broad phase of segment–segment contact: sort-and-sweep of axis-aligned boxes along x,
//! so that only pairs whose boxes overlap reach the exact distance.

use nalgebra::Vector3;

/// An axis-aligned box (min and max corners, m).
pub type Aabb = (Vector3<f64>, Vector3<f64>);

/// Reusable buffers of [`overlapping_pairs`].
#[derive(Clone, Debug, Default)]
pub struct SweepBuffers {
    order: Vec<usize>,
}

/// Every pair (i, j), i < j, whose boxes overlap, into `out` (cleared first), in a
/// deterministic order.
pub fn overlapping_pairs(
    boxes: &[Aabb],
    buffers: &mut SweepBuffers,
    out: &mut Vec<(usize, usize)>,
) {
    out.clear();
    let order = &mut buffers.order;
    order.clear();
    order.extend(0..boxes.len());
    order.sort_by(|&a, &b| boxes[a].0.x.total_cmp(&boxes[b].0.x).then(a.cmp(&b)));
    for (k, &i) in order.iter().enumerate() {
        let (lo, hi) = boxes[i];
        for &j in &order[k + 1..] {
            let (lo_j, hi_j) = boxes[j];
            if lo_j.x > hi.x {
                break;
            }
            if lo_j.y <= hi.y && lo.y <= hi_j.y && lo_j.z <= hi.z && lo.z <= hi_j.z {
                out.push((i.min(j), i.max(j)));
            }
        }
    }
    out.sort_unstable();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_overlapping_pairs() {
        let b = |x0: f64, y0: f64, z0: f64, s: f64| {
            (
                Vector3::new(x0, y0, z0),
                Vector3::new(x0 + s, y0 + s, z0 + s),
            )
        };
        let boxes = vec![
            b(0.0, 0.0, 0.0, 1.0),
            b(0.5, 0.5, 0.5, 1.0),
            b(0.9, 3.0, 0.0, 1.0),
            b(5.0, 0.0, 0.0, 1.0),
            b(-0.5, -0.5, -0.5, 0.6),
        ];
        let mut out = Vec::new();
        overlapping_pairs(&boxes, &mut SweepBuffers::default(), &mut out);
        // Brute force.
        let mut expected = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                let (a, c) = (boxes[i], boxes[j]);
                if (0..3).all(|k| a.0[k] <= c.1[k] && c.0[k] <= a.1[k]) {
                    expected.push((i, j));
                }
            }
        }
        assert_eq!(out, expected);
        assert_eq!(out, vec![(0, 1), (0, 4)]);
    }
}
