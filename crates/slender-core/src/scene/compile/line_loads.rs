//! Distributed line loads lumped on a rod's vertices exactly: the nodal force of vertex v is
//! ∫ q(s) φ_v(s) ds over the rest arc length, with φ_v the hat function of v and q piecewise
//! linear (uniform over an interval, or linear between the rows of a table). On every
//! interval between the nodes and the load's own breakpoints both factors are linear, so
//! Simpson's rule integrates their product exactly.

use crate::geometry::Vec3;

use super::super::error::SceneError;
use super::super::spec::LineLoadSpec;

/// The load q(s) as a function that is linear between its breakpoints.
enum Load {
    Uniform { q: Vec3, from: f64, to: f64 },
    Table(Vec<(f64, Vec3)>),
}

impl Load {
    fn breakpoints(&self) -> Vec<f64> {
        match self {
            Load::Uniform { from, to, .. } => vec![*from, *to],
            Load::Table(rows) => rows.iter().map(|r| r.0).collect(),
        }
    }

    /// q at `s`, on the interval whose midpoint is `mid` (decides the side of a jump).
    fn at(&self, s: f64, mid: f64) -> Vec3 {
        match self {
            Load::Uniform { q, from, to } => {
                if mid >= *from && mid <= *to {
                    *q
                } else {
                    Vec3::zeros()
                }
            }
            Load::Table(rows) => {
                let first = rows[0].0;
                let last = rows[rows.len() - 1].0;
                if !(mid >= first && mid <= last) {
                    return Vec3::zeros();
                }
                let k = rows
                    .windows(2)
                    .position(|w| mid >= w[0].0 && mid <= w[1].0)
                    .unwrap_or(0);
                let (s0, q0) = rows[k];
                let (s1, q1) = rows[k + 1];
                let u = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
                q0 * (1.0 - u) + q1 * u
            }
        }
    }
}

fn finite(path: &str, v: f64, what: &str) -> Result<f64, SceneError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(SceneError::new(path, format!("{v}: {what} must be finite")))
    }
}

/// Nodal forces (vertex, N) of line load `spec` (at `path`) on a rod with node arc lengths
/// `nodes` (m).
pub(super) fn lump(
    path: &str,
    spec: &LineLoadSpec,
    nodes: &[f64],
) -> Result<Vec<(usize, Vec3)>, SceneError> {
    let length = nodes[nodes.len() - 1];
    let load = parse(path, spec, length)?;
    let mut cuts: Vec<f64> = nodes.to_vec();
    cuts.extend(load.breakpoints().into_iter().map(|s| s.clamp(0.0, length)));
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut f = vec![Vec3::zeros(); nodes.len()];
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !(b > a) {
            continue;
        }
        let m = 0.5 * (a + b);
        let j = nodes
            .partition_point(|&s| s <= m)
            .saturating_sub(1)
            .min(nodes.len() - 2);
        let (s0, s1) = (nodes[j], nodes[j + 1]);
        let hat1 = |s: f64| (s - s0) / (s1 - s0);
        for (v, hat) in [
            (j, 1.0 - hat1(a), 1.0 - hat1(m), 1.0 - hat1(b)),
            (j + 1, hat1(a), hat1(m), hat1(b)),
        ]
        .map(|(v, ha, hm, hb)| (v, [ha, hm, hb]))
        {
            let q = [load.at(a, m), load.at(m, m), load.at(b, m)];
            f[v] += (q[0] * hat[0] + q[1] * (4.0 * hat[1]) + q[2] * hat[2]) * ((b - a) / 6.0);
        }
    }
    Ok(f.into_iter()
        .enumerate()
        .filter(|(_, x)| x.norm() > 0.0)
        .collect())
}

/// The load per length q (N/m) of line load `spec` at each node of a rod with node arc lengths
/// `nodes` (m), for drawing it (at a jump of a uniform load, its value inside).
pub(super) fn sample(
    path: &str,
    spec: &LineLoadSpec,
    nodes: &[f64],
) -> Result<Vec<Vec3>, SceneError> {
    let load = parse(path, spec, nodes[nodes.len() - 1])?;
    Ok(nodes.iter().map(|&s| load.at(s, s)).collect())
}

/// The load of `spec` (at `path`) on a rod of rest length `length` (m), checked.
fn parse(path: &str, spec: &LineLoadSpec, length: f64) -> Result<Load, SceneError> {
    Ok(match (&spec.force_per_length, &spec.table) {
        (Some(q), None) => {
            let q = Vec3::from(*q);
            if q.iter().any(|c| !c.is_finite()) {
                return Err(SceneError::new(
                    format!("{path}.force_per_length"),
                    format!(
                        "{:?}: every component must be finite (N/m)",
                        spec.force_per_length.unwrap()
                    ),
                ));
            }
            let from = finite(&format!("{path}.from"), spec.from.unwrap_or(0.0), "from")?;
            let to = finite(&format!("{path}.to"), spec.to.unwrap_or(length), "to")?;
            if !(0.0 <= from && from < to && to <= length * (1.0 + 1e-12)) {
                return Err(SceneError::new(
                    path,
                    format!("from = {from}, to = {to}: need 0 <= from < to <= {length} (the rod's rest length, m)"),
                ));
            }
            Load::Uniform { q, from, to }
        }
        (None, Some(rows)) => {
            if spec.from.is_some() || spec.to.is_some() {
                return Err(SceneError::new(
                    path,
                    "`from`/`to` go with `force_per_length`, not with `table`",
                ));
            }
            if rows.len() < 2 {
                return Err(SceneError::new(
                    format!("{path}.table"),
                    "needs at least two rows [s, fx, fy, fz]",
                ));
            }
            let mut out: Vec<(f64, Vec3)> = Vec::with_capacity(rows.len());
            for (k, r) in rows.iter().enumerate() {
                if r.iter().any(|c| !c.is_finite()) {
                    return Err(SceneError::new(
                        format!("{path}.table[{k}]"),
                        "every value must be finite",
                    ));
                }
                if !(r[0] >= 0.0 && r[0] <= length * (1.0 + 1e-12)) {
                    return Err(SceneError::new(
                        format!("{path}.table[{k}]"),
                        format!("s = {}: must be within 0..={length} (m)", r[0]),
                    ));
                }
                if let Some(prev) = out.last() {
                    if !(r[0] > prev.0) {
                        return Err(SceneError::new(
                            format!("{path}.table[{k}]"),
                            "s must increase from row to row",
                        ));
                    }
                }
                out.push((r[0], Vec3::new(r[1], r[2], r[3])));
            }
            Load::Table(out)
        }
        _ => {
            return Err(SceneError::new(
                path,
                "give exactly one of `force_per_length` (uniform) or `table` (varying)",
            ))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nodes() -> Vec<f64> {
        (0..=8).map(|k| 0.125 * k as f64).collect()
    }

    #[test]
    fn a_uniform_load_is_sampled_inside_its_interval_ends_included() {
        let spec = LineLoadSpec {
            force_per_length: Some([0.0, 2.0, 0.0]),
            from: Some(0.25),
            to: Some(0.75),
            table: None,
        };
        let q = sample("l", &spec, &nodes()).unwrap();
        let loaded: Vec<usize> = (0..q.len()).filter(|&v| q[v].norm() > 0.0).collect();
        assert_eq!(loaded, [2, 3, 4, 5, 6]);
        assert!(loaded.iter().all(|&v| q[v] == Vec3::new(0.0, 2.0, 0.0)));
    }

    #[test]
    fn a_table_is_sampled_linearly_between_its_rows_and_zero_outside() {
        let spec = LineLoadSpec {
            force_per_length: None,
            from: None,
            to: None,
            table: Some(vec![[0.125, 0.0, 0.0, 1.0], [0.625, 0.0, 0.0, 3.0]]),
        };
        let q = sample("l", &spec, &nodes()).unwrap();
        let z: Vec<f64> = q.iter().map(|x| x.z).collect();
        assert_eq!(z, [0.0, 1.0, 1.5, 2.0, 2.5, 3.0, 0.0, 0.0, 0.0]);
        // The lumped nodal forces integrate to the load's resultant, ∫ q ds = 1.0 N.
        let total: f64 = lump("l", &spec, &nodes())
            .unwrap()
            .iter()
            .map(|(_, f)| f.z)
            .sum();
        assert!((total - 1.0).abs() < 1e-14, "{total}");
    }
}
