//! Contact sites of the mid-edge shell strip: its mesh vertices, each standing for its share
//! of the mid-surface's area, kept at the half-thickness h/2 from obstacles.
//!
//! The same [`ContactProblem`](super::ContactProblem) that holds rods off obstacles holds the
//! strip: a site's barrier energy is κ·w·b(g) with w its *area* (m²) here instead of a
//! length, so the barrier stiffness κ of [`ContactParams`] is a stiffness per unit area
//! (N/m³) — see [`ContactParams::for_area_load`] — and the tangential anchor of a sticking
//! contact likewise (N/m³). The contact radius is h/2: the mid-surface keeps that distance, so
//! the strip's faces (its top and bottom surfaces at ±h/2) do not enter the obstacle at the
//! vertices.
//!
//! What the vertices guarantee: the gap is measured at the vertices only. On a plane the
//! distance is affine over a flat triangle, so every point of the mid-surface keeps h/2 as
//! its corners do. On a curved convex obstacle (a round bar, a ball) the mid-surface between
//! vertices may come closer than its corners by up to the chord sag ℓ²/(8ρ) (ℓ the element
//! size, ρ the radius of the obstacle plus h/2): mesh finer than √(8ρ·tolerance). A sharp
//! edge of a box or a mesh can poke between the vertices of an element, as it can between a
//! rod's vertices.
//!
//! Self-contact of the strip (the strip folding onto itself) is not modelled: the strip has
//! no contact edges, so a problem with `self_contact` holds the strip against obstacles only.

use nalgebra::Vector3;

use crate::assembly::{MapSlot, FIXED};
use crate::linalg::AdaptiveMatrix;
use crate::shell::{Shell, ShellState};

use super::problem::ContactParams;
use super::sites::{ContactEdge, ContactSite, ContactSites};

impl Shell {
    /// Rest area (m²) of the mid-surface each vertex stands for: a third of each adjacent
    /// face's rest area (so that the sites' areas add up to the strip's area L·w, and a site
    /// carries the weight its lumped mass does).
    pub fn vertex_areas(&self) -> Vec<f64> {
        let mut area = vec![0.0; self.mesh.rest_positions.len()];
        for (tri, rest) in self.mesh.faces.iter().zip(&self.rest) {
            for &v in tri {
                area[v] += rest.area / 3.0;
            }
        }
        area
    }
}

impl ContactSites for Shell {
    fn contact_sites(&self) -> Vec<ContactSite> {
        self.vertex_areas()
            .into_iter()
            .enumerate()
            .map(|(v, area)| ContactSite {
                member: 0,
                vertex: v,
                dofs: std::array::from_fn(|c| match self.dofs.vertex(v, c) {
                    Some(dof) => MapSlot { dof, coef: 1.0 },
                    // A clamped vertex: the clamp holds it, and takes its contact force.
                    None => MapSlot {
                        dof: FIXED,
                        coef: 0.0,
                    },
                }),
                length: area,
            })
            .collect()
    }

    fn site_position(&self, state: &ShellState, site: &ContactSite) -> Vector3<f64> {
        state.positions[site.vertex]
    }

    /// None: the strip does not touch itself (see the module docs).
    fn contact_edges(&self) -> Vec<ContactEdge> {
        Vec::new()
    }

    /// The rest station x of each vertex along the strip (its rows run across the width).
    fn site_stations(&self, sites: &[ContactSite]) -> Vec<Option<(usize, f64)>> {
        (sites.iter())
            .map(|s| Some((0, self.mesh.rest_positions[s.vertex].x)))
            .collect()
    }

    fn adaptive_hessian(&self) -> AdaptiveMatrix {
        // A site touches the three coordinates of one vertex, all in the pattern of its faces.
        AdaptiveMatrix::Sparse(self.sparse_hessian())
    }
}

impl ContactParams {
    /// Parameters under which an area load `area_load` p (N/m², e.g. the self-weight ρ h g of
    /// a strip) rests a surface whose sites are weighted by area at half the activation
    /// distance `activation` (m), `radius` (m) from the obstacles (h/2 for a strip of
    /// thickness h). The stiffness and the stick stiffness are then per unit area (N/m³):
    /// κ = p / (ĝ (½ + ln 2)), k_t = p / (10⁻⁴ ĝ) — the line-load rule of
    /// [`Self::for_line_load`] with the area in place of the length.
    pub fn for_area_load(radius: f64, activation: f64, area_load: f64) -> Self {
        // The same formulas: only the units of the load (and so of κ and k_t) differ.
        Self::for_line_load(radius, activation, area_load)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shell::{ShellBuilder, ShellProperties};

    #[test]
    fn sites_cover_the_strip_and_clamped_vertices_are_held() {
        let shell = ShellBuilder::new(ShellProperties {
            length: 0.4,
            width: 0.05,
            thickness: 1e-3,
            young: 1e9,
            poisson: 0.3,
            density: 1000.0,
        })
        .elements(6, 3)
        .build()
        .unwrap();
        let sites = shell.contact_sites();
        assert_eq!(sites.len(), 7 * 4);
        let area: f64 = sites.iter().map(|s| s.length).sum();
        assert!((area - 0.4 * 0.05).abs() < 1e-15, "{area}");
        let clamped = &shell.mesh().clamp_vertices;
        for s in &sites {
            let held = s.dofs.iter().all(|d| d.dof == FIXED);
            assert_eq!(held, clamped.contains(&s.vertex), "vertex {}", s.vertex);
        }
        assert!(shell.contact_edges().is_empty());
    }
}
