//! Contact radii per site: each centerline vertex keeps its own cable's radius, so that a thin
//! rod and a thick one in one structure (self-contact puts every rod of a scene in one) rest
//! on obstacles at their own radii, and two touching edges keep their radii's sum apart.

use crate::error::ModelError;

use super::sites::{ContactSite, ContactSites};

/// Checks `radii` (one per member, m): each finite and ≥ 0; errors name `radii[m]`.
pub(crate) fn validate_member_radii(radii: &[f64]) -> Result<(), ModelError> {
    match radii
        .iter()
        .enumerate()
        .find(|(_, r)| !(r.is_finite() && **r >= 0.0))
    {
        Some((m, &r)) => Err(ModelError::parameter(
            format!("radii[{m}]"),
            r,
            "finite and >= 0 (m: the contact radius of that member)",
        )),
        None => Ok(()),
    }
}

/// The contact radius (m) of member `m`: `radii[m]`, or `default` for a member missing from
/// `radii`.
pub(crate) fn member_radius(radii: &[f64], m: usize, default: f64) -> f64 {
    radii.get(m).copied().unwrap_or(default)
}

/// The radius (m) of every site of `model` (`sites` = its [`ContactSites::contact_sites`]):
/// its member's, and at a vertex where members meet (a joint, whose copies the site stands
/// for) the largest of theirs — the thickest cable there touches first. Members missing from
/// `radii` have `default`.
pub(crate) fn site_radii<P: ContactSites>(
    model: &P,
    sites: &[ContactSite],
    radii: &[f64],
    default: f64,
) -> Vec<f64> {
    let mut out: Vec<f64> = sites
        .iter()
        .map(|s| member_radius(radii, s.member, default))
        .collect();
    let first = member_radius(radii, 0, default);
    let uniform = radii.iter().all(|&r| r == first) && (radii.is_empty() || first == default);
    if uniform {
        // One radius everywhere (a single cable, or rods of one section): nothing meets a
        // thicker member, and the edge walk below is skipped (time runs build a problem per
        // step).
        return out;
    }
    let index: std::collections::HashMap<(usize, usize), usize> = sites
        .iter()
        .enumerate()
        .map(|(k, s)| ((s.member, s.vertex), k))
        .collect();
    for e in model.contact_edges() {
        let r = member_radius(radii, e.member, default);
        for v in e.vertices {
            if let Some(&k) = index.get(&model.canonical_vertex(e.member, v)) {
                out[k] = out[k].max(r);
            }
        }
    }
    out
}
