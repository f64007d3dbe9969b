//! Contact sites: the points of a model that touch obstacles (its centerline vertices), where
//! they are, which free DOFs move them, and how much centerline each stands for.

use nalgebra::Vector3;

use crate::assembly::{MapSlot, FIXED};
use crate::linalg::AdaptiveMatrix;
use crate::rod::{Rod, RodState};
use crate::solver::EquilibriumProblem;
use crate::structure::{Structure, StructureState};

/// Where one coordinate of a site goes among the free DOFs: the coordinate is `coef` × free
/// DOF `dof` (plus a prescribed part), or held when `dof` is [`FIXED`].
pub type SiteDof = MapSlot;

/// One contact site: a centerline vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSite {
    /// Member of a structure (0 for a single rod).
    pub member: usize,
    /// Vertex of that member.
    pub vertex: usize,
    /// The free DOF and coefficient of each coordinate.
    pub dofs: [SiteDof; 3],
    /// Centerline length (m) the site stands for at rest (half of each adjacent edge): the
    /// weight of its contact energy, so that the contact stiffness is per unit length and
    /// does not depend on the mesh. For a shell strip's vertex, its share of the mid-surface
    /// area (m²) instead, the contact stiffness then per unit area (see
    /// [`shell_sites`](super::shell_sites)).
    pub length: f64,
}

/// One centerline edge, for segment–segment (self and cable–cable) contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactEdge {
    /// Member (0 for a single rod).
    pub member: usize,
    /// Its end vertices (member's own numbering).
    pub vertices: [usize; 2],
    /// Rest arc length (m) of its ends along the member.
    pub arc: [f64; 2],
}

/// A model whose centerline vertices can touch obstacles.
pub trait ContactSites: EquilibriumProblem {
    /// Every site, once (a joint's vertex is one site).
    fn contact_sites(&self) -> Vec<ContactSite>;
    /// Position (m) of `site` in `state`.
    fn site_position(&self, state: &Self::State, site: &ContactSite) -> Vector3<f64>;
    /// Every centerline edge.
    fn contact_edges(&self) -> Vec<ContactEdge>;
    /// The model's own Hessian storage, as the run-time choice of storage (contacts with
    /// obstacles touch one vertex at a time and keep the model's pattern).
    fn adaptive_hessian(&self) -> AdaptiveMatrix;
    /// The (member, vertex) whose site stands for `(member, vertex)`: itself, or the master
    /// of the joint it is a copy of.
    fn canonical_vertex(&self, member: usize, vertex: usize) -> (usize, usize) {
        (member, vertex)
    }

    /// Where each of `sites` lies along the model: its line (a member) and rest station
    /// (m) along it, or `None`. The first guess of a support move in contact fades the move
    /// out along these lines toward the contacts it presses (`ContactProblem`'s
    /// `impose_load`). By default the rest arc length along the member's centerline edges.
    fn site_stations(&self, sites: &[ContactSite]) -> Vec<Option<(usize, f64)>> {
        let index: std::collections::HashMap<(usize, usize), usize> = (sites.iter())
            .enumerate()
            .map(|(k, s)| ((s.member, s.vertex), k))
            .collect();
        let mut stations = vec![None; sites.len()];
        for e in self.contact_edges() {
            for (v, s) in e.vertices.iter().zip(e.arc) {
                if let Some(&k) = index.get(&(e.member, *v)) {
                    stations[k].get_or_insert((e.member, s));
                }
            }
        }
        stations
    }
}

/// The edges of one polyline with rest edge lengths `lengths` (`closed`: the last joins the
/// last vertex to the first).
fn polyline_edges(member: usize, lengths: &[f64], n_vertices: usize) -> Vec<ContactEdge> {
    let mut s = 0.0;
    lengths
        .iter()
        .enumerate()
        .map(|(j, &l)| {
            let e = ContactEdge {
                member,
                vertices: [j, (j + 1) % n_vertices],
                arc: [s, s + l],
            };
            s += l;
            e
        })
        .collect()
}

/// Half of each rest edge next to vertex `v` of a polyline of rest edge lengths `lengths`
/// (`closed`: the last edge joins the last vertex to the first).
fn voronoi_length(lengths: &[f64], v: usize, closed: bool) -> f64 {
    let n = lengths.len();
    let left = if v > 0 {
        lengths[v - 1]
    } else if closed && n > 0 {
        lengths[n - 1]
    } else {
        0.0
    };
    let right = if v < n { lengths[v] } else { 0.0 };
    0.5 * (left + right)
}

fn edge_lengths(points: &[Vector3<f64>]) -> Vec<f64> {
    points.windows(2).map(|w| (w[1] - w[0]).norm()).collect()
}

impl ContactSites for Rod {
    fn contact_sites(&self) -> Vec<ContactSite> {
        let n = self.rest_state().positions().len();
        let closed = self.rest_lengths().len() == n;
        (0..n)
            .map(|v| ContactSite {
                member: 0,
                vertex: v,
                dofs: std::array::from_fn(|c| {
                    let dof = self.dofs().vertex(v, c);
                    MapSlot {
                        dof,
                        coef: if dof == FIXED { 0.0 } else { 1.0 },
                    }
                }),
                length: voronoi_length(self.rest_lengths(), v, closed),
            })
            .collect()
    }

    fn site_position(&self, state: &RodState, site: &ContactSite) -> Vector3<f64> {
        state.positions()[site.vertex]
    }

    fn contact_edges(&self) -> Vec<ContactEdge> {
        polyline_edges(0, self.rest_lengths(), self.rest_state().positions().len())
    }

    fn adaptive_hessian(&self) -> AdaptiveMatrix {
        AdaptiveMatrix::Band(self.new_hessian())
    }
}

impl ContactSites for Structure {
    fn contact_sites(&self) -> Vec<ContactSite> {
        let rest = self.rest_state();
        let lengths: Vec<Vec<f64>> = rest
            .members
            .iter()
            .map(|m| edge_lengths(m.positions()))
            .collect();
        let mut sites = Vec::new();
        for (m, member) in self.members().iter().enumerate() {
            for v in 0..member.n_vertices() {
                let group = self.joints().iter().find(|g| g.contains(&(m, v)));
                if group.is_some_and(|g| g[0] != (m, v)) {
                    continue; // a copy of a joint's vertex: the master stands for it
                }
                // A joint's vertex stands for the edges of every member meeting there.
                let length = match group {
                    Some(g) => g
                        .iter()
                        .map(|&(m2, v2)| voronoi_length(&lengths[m2], v2, false))
                        .sum(),
                    None => voronoi_length(&lengths[m], v, false),
                };
                sites.push(ContactSite {
                    member: m,
                    vertex: v,
                    dofs: std::array::from_fn(|c| self.vertex_slot(m, v, c)),
                    length,
                });
            }
        }
        sites
    }

    fn site_position(&self, state: &StructureState, site: &ContactSite) -> Vector3<f64> {
        state.members[site.member].positions()[site.vertex]
    }

    fn contact_edges(&self) -> Vec<ContactEdge> {
        let rest = self.rest_state();
        rest.members
            .iter()
            .enumerate()
            .flat_map(|(m, s)| polyline_edges(m, &edge_lengths(s.positions()), s.positions().len()))
            .collect()
    }

    fn adaptive_hessian(&self) -> AdaptiveMatrix {
        self.new_hessian()
    }

    fn canonical_vertex(&self, member: usize, vertex: usize) -> (usize, usize) {
        self.joints()
            .iter()
            .find(|g| g.contains(&(member, vertex)))
            .map_or((member, vertex), |g| g[0])
    }
}
