//! Grouping the rods' parts into structures: parts joined by joints (or by the closure of a
//! closed rod) are solved together, with the sliders and twist holds on them; parts that touch
//! nothing else are structures of their own.

use crate::geometry::Vec3;
use crate::structure::{JointEnd, SliderSupport, Structure, StructureBuilder, TwistHold};

use super::super::error::SceneError;
use super::super::spec::{JointSpec, RodEnd, SupportKind};
use super::rod::RodDraft;

/// A joint between parts: (rod, part, local vertex) of every end, the master first.
type PartJoint = Vec<(usize, usize, usize)>;

/// Groups every part of `drafts` into structures (setting each part's structure and member
/// index) and returns them; `one_structure`: all parts into one (self-contact: cables touch
/// only within a structure).
pub(super) fn build_structures(
    drafts: &mut [RodDraft],
    joints: &[JointSpec],
    allow_free_motion: bool,
    one_structure: bool,
) -> Result<Vec<Structure>, SceneError> {
    // Parts numbered globally.
    let mut part_ids: Vec<Vec<usize>> = Vec::new();
    let mut n_parts = 0;
    for d in drafts.iter() {
        part_ids.push((n_parts..n_parts + d.rod.parts.len()).collect());
        n_parts += d.rod.parts.len();
    }
    let end_of = |r: usize, end: RodEnd| -> (usize, usize, usize) {
        let rod = &drafts[r].rod;
        match end {
            RodEnd::Start => (r, 0, 0),
            RodEnd::End => {
                let p = rod.parts.len() - 1;
                (r, p, rod.parts[p].n_vertices - 1)
            }
        }
    };
    let mut part_joints: Vec<(String, PartJoint)> = Vec::new();
    for (k, j) in joints.iter().enumerate() {
        let path = format!("joints[{k}]");
        if j.ends.len() < 2 {
            return Err(SceneError::new(
                format!("{path}.ends"),
                "a joint joins at least two rod ends",
            ));
        }
        let mut ends = Vec::new();
        for (e, end) in j.ends.iter().enumerate() {
            let Some(r) = drafts.iter().position(|d| d.rod.name == end.rod) else {
                return Err(unknown_rod(&path, e, &end.rod, drafts));
            };
            if let Some(m) = drafts[r].members.first().filter(|m| m.as_der().is_none()) {
                return Err(SceneError::new(
                    format!("{path}.ends[{e}].rod"),
                    format!(
                        "{:?} is a {} rod: joints join discrete elastic rods (model = \"der\") only",
                        end.rod,
                        m.model_name()
                    ),
                ));
            }
            if drafts[r].rod.closed {
                return Err(SceneError::new(
                    format!("{path}.ends[{e}].rod"),
                    format!(
                        "{:?} is closed: its ends are already joined to each other",
                        end.rod
                    ),
                ));
            }
            ends.push(end_of(r, end.end));
        }
        part_joints.push((path, ends));
    }
    // Closed rods: their end joined to their start (unless a clamp there holds both).
    for (r, d) in drafts.iter().enumerate() {
        if !d.rod.closed {
            continue;
        }
        let n = d.rod.n_edges;
        let clamped = d
            .rod
            .supports
            .iter()
            .any(|s| s.kind == SupportKind::Clamp && (s.vertex == 0 || s.vertex == n));
        if clamped {
            continue;
        }
        let start_held = d.rod.supports.iter().any(|s| s.held.contains(&0));
        let (a, b) = (end_of(r, RodEnd::Start), end_of(r, RodEnd::End));
        let ends = if start_held { vec![a, b] } else { vec![b, a] };
        part_joints.push((format!("rods[{r}].closed"), ends));
    }

    // Union-find over parts.
    let mut parent: Vec<usize> = (0..n_parts).collect();
    fn find(p: &mut [usize], i: usize) -> usize {
        let mut i = i;
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for (_, ends) in &part_joints {
        let a = part_ids[ends[0].0][ends[0].1];
        for &(r, p, _) in &ends[1..] {
            let b = part_ids[r][p];
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            parent[rb] = ra;
        }
    }
    if one_structure {
        for p in 1..n_parts {
            let (ra, rb) = (find(&mut parent, 0), find(&mut parent, p));
            parent[rb] = ra;
        }
    }
    let mut group_of_root: Vec<Option<usize>> = vec![None; n_parts];
    let mut groups: Vec<Vec<(usize, usize)>> = Vec::new();
    for (r, d) in drafts.iter().enumerate() {
        for (p, &id) in part_ids[r].iter().enumerate().take(d.rod.parts.len()) {
            let root = find(&mut parent, id);
            let g = *group_of_root[root].get_or_insert_with(|| {
                groups.push(Vec::new());
                groups.len() - 1
            });
            groups[g].push((r, p));
        }
    }

    let mut structures = Vec::with_capacity(groups.len());
    for (g, members) in groups.iter().enumerate() {
        let member_of =
            |r: usize, p: usize| members.iter().position(|&m| m == (r, p)).expect("member");
        let mut b = StructureBuilder::new();
        if allow_free_motion {
            b = b.allow_free_motion();
        }
        for &(r, p) in members {
            b = b.member(drafts[r].members[p].clone());
        }
        for (_, ends) in &part_joints {
            if !members.contains(&(ends[0].0, ends[0].1)) {
                continue;
            }
            b = b.joint(
                ends.iter()
                    .map(|&(r, p, v)| JointEnd {
                        member: member_of(r, p),
                        vertex: v,
                    })
                    .collect(),
            );
        }
        for &(r, p) in members {
            let rod = &drafts[r].rod;
            let part = &rod.parts[p];
            for s in &rod.supports {
                match s.kind {
                    SupportKind::Slider if part.contains(s.vertex) => {
                        // A vertex shared by two parts (an interior clamp) is held already.
                        b = b.slider(SliderSupport {
                            member: member_of(r, p),
                            vertex: s.vertex - part.first_vertex,
                            axis: s.axis.unwrap_or_else(Vec3::x),
                        });
                    }
                    SupportKind::TwistHold => {
                        let e = s.edge.expect("edge");
                        if e >= part.first_vertex && e + 1 < part.first_vertex + part.n_vertices {
                            b = b.twist_hold(TwistHold {
                                member: member_of(r, p),
                                edge: e - part.first_vertex,
                            });
                        }
                    }
                    _ => {}
                }
            }
        }
        let structure = b.build().map_err(|e| {
            let names: Vec<String> = members
                .iter()
                .map(|&(r, _)| drafts[r].rod.name.clone())
                .collect::<std::collections::BTreeSet<_>>()
                .into_iter()
                .collect();
            let (r0, _) = members[0];
            let msg = e.to_string();
            let what = if names.len() > 1 {
                format!("rods {} (joined)", names.join(", "))
            } else {
                format!("rod {:?}", names[0])
            };
            if msg.contains("rigid-body") {
                SceneError::new(
                    format!("rods[{r0}].supports"),
                    format!("{what} can move as a rigid body: hold it so that it can neither translate, rotate nor spin about its own axis (a clamp, or pins/clips/sliders that do): {msg}"),
                )
            } else {
                SceneError::new(format!("rods[{r0}]"), format!("{what}: {msg}"))
            }
        })?;
        for (m, &(r, p)) in members.iter().enumerate() {
            drafts[r].rod.parts[p].structure = g;
            drafts[r].rod.parts[p].member = m;
        }
        structures.push(structure);
    }
    Ok(structures)
}

/// The error for a joint end naming no rod.
fn unknown_rod(path: &str, e: usize, name: &str, drafts: &[RodDraft]) -> SceneError {
    SceneError::new(
        format!("{path}.ends[{e}].rod"),
        format!(
            "{name:?}: no rod has this name (rods: {})",
            drafts
                .iter()
                .map(|d| d.rod.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}
