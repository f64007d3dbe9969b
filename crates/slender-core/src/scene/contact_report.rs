//! The contacts of a scene's structures as results — per obstacle its active contacts, every
//! active pair of touching segments (self-contact, cable against cable), the smallest gaps —
//! and the obstacle forces each structure's balance must include. One function for the
//! equilibria of a [`Session`](super::Session) and the frames of a
//! [`TimeRun`](super::TimeRun), so both report contacts the same way.

use crate::assembly::FIXED;
use crate::contact::edge_penetration::{deepest_point_inside, segment_crossing};
use crate::contact::{ContactProblem, ContactSites, Friction, SegmentSide};
use crate::geometry::Vec3;
use crate::structure::{Structure, StructureState};

use super::compile::CompiledScene;
use super::result::{
    ContactResult, EdgeThroughObstacle, ObstacleResult, SegmentContactKind, SegmentContactResult,
};
use super::shell_contact_run::StripContacts;

/// Everything a scene step reports about its contacts.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactReport {
    /// Every obstacle with its active contacts (empty without obstacles).
    pub obstacles: Vec<ObstacleResult>,
    /// Smallest gap (m) of a rod or a shell strip to an obstacle (None without obstacles).
    pub min_gap: Option<f64>,
    /// Every active segment pair (None without self-contact).
    pub segment_contacts: Option<Vec<SegmentContactResult>>,
    /// Smallest gap (m) between two segments that may touch (None without self-contact or
    /// when none are near).
    pub min_segment_gap: Option<f64>,
    /// Per structure: (position, force) of every obstacle contact on a free vertex, for the
    /// force and moment balance. Segment pairs act between parts of one structure and cancel
    /// in its balance, so they are not listed.
    pub external: Vec<Vec<(Vec3, Vec3)>>,
    /// Rod edges whose centerline, and strip faces whose mid-surface, runs through an
    /// obstacle between their vertices.
    pub edges_through_obstacles: Vec<EdgeThroughObstacle>,
}

/// The contact problem of structure `k` of `scene` around `state`, with friction state
/// `friction` (empty: every contact free); `None` if the scene has no contact.
pub(crate) fn contact_problem<'a>(
    scene: &'a CompiledScene,
    k: usize,
    state: &StructureState,
    friction: &[Friction],
) -> Option<Result<ContactProblem<'a, Structure>, String>> {
    let c = scene.contact.as_ref()?;
    let s = &scene.structures[k];
    Some(
        ContactProblem::with_radii(
            s,
            c.obstacles.clone(),
            c.params[k],
            state,
            &c.chains[k],
            &c.radii[k],
        )
        .inspect(|p| p.set_friction_state(friction))
        .map_err(|e| format!("contact: {e}")),
    )
}

/// The rod (name) and its vertex for vertex `vertex` of member `member` of structure `k`.
pub(crate) fn rod_vertex(
    scene: &CompiledScene,
    k: usize,
    member: usize,
    vertex: usize,
) -> (String, usize) {
    scene
        .rods
        .iter()
        .find_map(|r| {
            r.parts
                .iter()
                .find(|part| part.structure == k && part.member == member)
                .map(|part| (r.name.clone(), part.first_vertex + vertex))
        })
        .unwrap_or_else(|| (format!("structure{k}.member{member}"), vertex))
}

/// Appends every edge of structure `k` (in `state`) whose centerline runs through one of the
/// scene's obstacles between its vertices (see [`deepest_point_inside`]), or crosses a mesh
/// (see [`segment_crossing`]).
fn edges_through(
    scene: &CompiledScene,
    k: usize,
    state: &StructureState,
    out: &mut Vec<EdgeThroughObstacle>,
) {
    let Some(c) = &scene.contact else {
        return;
    };
    for edge in scene.structures[k].contact_edges() {
        let positions = state.members[edge.member].positions();
        let [a, b] = edge.vertices;
        let (p, q) = (positions[a], positions[b]);
        for (obstacle, name) in c.obstacles.iter().zip(&c.names) {
            let through = if obstacle.signed() {
                deepest_point_inside(|x| obstacle.surface(x).distance, &p, &q)
            } else {
                // A surface without an inside is crossed, at no depth.
                segment_crossing(obstacle.as_ref(), &p, &q).map(|t| (t, 0.0))
            };
            if let Some((t, d)) = through {
                let (rod, vertex) = rod_vertex(scene, k, edge.member, a);
                out.push(EdgeThroughObstacle {
                    rod,
                    shell: false,
                    edge: vertex,
                    vertices: vec![vertex, vertex + 1],
                    obstacle: name.clone(),
                    position: (p + (q - p) * t).into(),
                    depth: d.abs(),
                });
            }
        }
    }
}

/// The contacts of the structures in `states` (one per structure of `scene`), each with its
/// friction state in `friction`.
pub(crate) fn contact_report(
    scene: &CompiledScene,
    states: &[StructureState],
    friction: &[&[Friction]],
) -> ContactReport {
    let Some(c) = &scene.contact else {
        return ContactReport::default();
    };
    let mut obstacles: Vec<ObstacleResult> = c
        .names
        .iter()
        .zip(&c.obstacles)
        .map(|(name, o)| ObstacleResult {
            name: name.clone(),
            friction: o.friction(),
            force: [0.0; 3],
            contacts: Vec::new(),
        })
        .collect();
    let self_contact = c.params.iter().any(|p| p.self_contact);
    let mut pairs = Vec::new();
    let mut external = vec![Vec::new(); states.len()];
    let mut min_gap = f64::INFINITY;
    let mut min_segment_gap = f64::INFINITY;
    let mut through = Vec::new();
    for (k, state) in states.iter().enumerate() {
        let Some(Ok(p)) = contact_problem(scene, k, state, friction.get(k).copied().unwrap_or(&[]))
        else {
            continue;
        };
        let held = |site: usize| p.sites()[site].dofs.iter().all(|d| d.dof == FIXED);
        if !c.obstacles.is_empty() {
            min_gap = min_gap.min(p.min_gap(state));
            edges_through(scene, k, state, &mut through);
        }
        for f in p.contact_forces(state) {
            if held(f.site) {
                // A held vertex: its support takes the contact force.
                continue;
            }
            let site = p.sites()[f.site];
            let x = p.model().site_position(state, &site);
            let total = f.force + f.friction;
            external[k].push((x, total));
            let (rod, vertex) = rod_vertex(scene, k, site.member, site.vertex);
            let o = &mut obstacles[f.obstacle];
            for i in 0..3 {
                o.force[i] += total[i];
            }
            o.contacts.push(ContactResult {
                rod,
                shell: false,
                vertex,
                position: x.into(),
                gap: f.gap,
                normal: f.normal.into(),
                normal_force: f.force.into(),
                friction_force: f.friction.into(),
                sticking: f.sticking,
            });
        }
        if p.params().self_contact {
            min_segment_gap = min_segment_gap.min(p.min_self_gap(state));
            // The share on a held vertex goes to its support, as for obstacle contacts.
            let free_force = |side: &SegmentSide| -> [f64; 3] {
                side.forces
                    .iter()
                    .filter(|(s, _)| !held(*s))
                    .map(|(_, f)| f)
                    .sum::<Vec3>()
                    .into()
            };
            for pair in p.segment_contacts(state) {
                let (a, b) = (&pair.a, &pair.b);
                let (rod_a, vertex_a) = rod_vertex(scene, k, a.member, a.vertex.unwrap_or(0));
                let (rod_b, edge_b) = rod_vertex(scene, k, b.member, b.edge.unwrap_or(0));
                let edge_a = a.edge.map(|e| rod_vertex(scene, k, a.member, e).1);
                pairs.push(SegmentContactResult {
                    kind: if a.edge.is_some() {
                        SegmentContactKind::EdgeEdge
                    } else {
                        SegmentContactKind::VertexEdge
                    },
                    rod_a,
                    edge_a,
                    vertex_a: a.vertex.map(|_| vertex_a),
                    point_a: a.point.into(),
                    force_a: free_force(a),
                    rod_b,
                    edge_b,
                    point_b: b.point.into(),
                    force_b: free_force(b),
                    gap: pair.gap,
                });
            }
        }
    }
    ContactReport {
        min_gap: (!c.obstacles.is_empty()).then_some(min_gap),
        obstacles,
        segment_contacts: self_contact.then_some(pairs),
        min_segment_gap: (self_contact && min_segment_gap.is_finite()).then_some(min_segment_gap),
        external,
        edges_through_obstacles: through,
    }
}

/// Adds the contacts of the scene's shell strips (`strips[i]` of `shells[i]`, `None` for a
/// strip without contact) to `report`: each under its obstacle, named by the strip and its
/// vertex, into the obstacle's resultant, the strips' smallest gap into the scene's, and
/// their faces through obstacles after the rods' edges.
pub(crate) fn add_strip_contacts(
    scene: &CompiledScene,
    strips: &[Option<StripContacts>],
    report: &mut ContactReport,
) {
    for (c, strip) in scene.shells.iter().zip(strips) {
        let Some(strip) = strip else {
            continue;
        };
        report.min_gap = Some(
            report
                .min_gap
                .map_or(strip.min_gap, |g| g.min(strip.min_gap)),
        );
        for (f, vertex, x) in &strip.contacts {
            let total = f.force + f.friction;
            let o = &mut report.obstacles[f.obstacle];
            for i in 0..3 {
                o.force[i] += total[i];
            }
            o.contacts.push(ContactResult {
                rod: c.name.clone(),
                shell: true,
                vertex: *vertex,
                position: (*x).into(),
                gap: f.gap,
                normal: f.normal.into(),
                normal_force: f.force.into(),
                friction_force: f.friction.into(),
                sticking: f.sticking,
            });
        }
        for f in &strip.through {
            report.edges_through_obstacles.push(EdgeThroughObstacle {
                rod: c.name.clone(),
                shell: true,
                edge: f.face,
                vertices: f.vertices.to_vec(),
                obstacle: report.obstacles[f.obstacle].name.clone(),
                position: f.position.into(),
                depth: f.depth,
            });
        }
    }
}
