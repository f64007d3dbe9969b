//! The structure's global DOFs: where every member DOF goes (see the module docs).

use crate::assembly::{MapSlot, FIXED};

use super::member::Member;

/// How a member DOF is tied to others before numbering.
#[derive(Clone, Debug)]
pub(super) enum Tie {
    /// Free on its own.
    Own,
    /// Dropped (a twist hold, or a joint whose master vertex is held).
    Fixed,
    /// Shares global DOF group `group` with coefficient `coef`.
    Group { group: usize, coef: f64 },
}

/// Global DOF numbering of a structure.
#[derive(Clone, Debug)]
pub struct GlobalDofs {
    /// Per member, per own free DOF: the global DOF and coefficient.
    pub(super) maps: Vec<Vec<MapSlot>>,
    /// Number of global free DOFs.
    pub(super) n_free: usize,
    /// A (member, own DOF) of every global DOF (scales are taken from it).
    pub(super) owner: Vec<(usize, usize)>,
    /// Σ c² · inertia over the member DOFs of each global DOF (kg or kg m²).
    pub(super) inertia: Vec<f64>,
    /// Σ c² over the member DOFs of each global DOF (averages a difference over them).
    pub(super) weight: Vec<f64>,
    /// Per member: `Some(offset)` if its own DOF i is global DOF offset + i with coefficient
    /// 1 for every i (a rod with no ties), so that its step is a plain slice of the global one.
    pub(super) offsets: Vec<Option<usize>>,
    /// Per member: `Some(offset)` as in `offsets` if, besides, the member owns every one of
    /// those global DOFs (no other member shares them), so that its DOF scales are written
    /// to the slice directly.
    pub(super) owned_offsets: Vec<Option<usize>>,
}

impl GlobalDofs {
    /// Numbers the global DOFs in member order (so that a single rod keeps its band), giving
    /// every tied group one DOF at its first member DOF.
    pub(super) fn new(members: &[Member], ties: &[Vec<Tie>]) -> Self {
        let mut maps: Vec<Vec<MapSlot>> = members
            .iter()
            .map(|m| {
                vec![
                    MapSlot {
                        dof: FIXED,
                        coef: 0.0
                    };
                    m.n_free()
                ]
            })
            .collect();
        let mut group_dof: Vec<Option<usize>> = Vec::new();
        let mut owner = Vec::new();
        for (m, member_ties) in ties.iter().enumerate() {
            for (i, tie) in member_ties.iter().enumerate() {
                maps[m][i] = match *tie {
                    Tie::Fixed => MapSlot {
                        dof: FIXED,
                        coef: 0.0,
                    },
                    Tie::Own => {
                        owner.push((m, i));
                        MapSlot {
                            dof: owner.len() - 1,
                            coef: 1.0,
                        }
                    }
                    Tie::Group { group, coef } => {
                        if group_dof.len() <= group {
                            group_dof.resize(group + 1, None);
                        }
                        let dof = *group_dof[group].get_or_insert_with(|| {
                            owner.push((m, i));
                            owner.len() - 1
                        });
                        MapSlot { dof, coef }
                    }
                };
            }
        }
        let n_free = owner.len();
        let mut inertia = vec![0.0; n_free];
        let mut weight = vec![0.0; n_free];
        for (m, map) in maps.iter().enumerate() {
            for (i, slot) in map.iter().enumerate() {
                if slot.dof != FIXED {
                    inertia[slot.dof] += slot.coef * slot.coef * members[m].inertia_metric(i);
                    weight[slot.dof] += slot.coef * slot.coef;
                }
            }
        }
        let offsets = maps
            .iter()
            .map(|map| {
                let first = map.first().map_or(0, |s| s.dof);
                map.iter()
                    .enumerate()
                    .all(|(i, s)| s.dof != FIXED && s.dof == first + i && s.coef == 1.0)
                    .then_some(first)
            })
            .collect::<Vec<_>>();
        let owned_offsets = offsets
            .iter()
            .enumerate()
            .map(|(m, offset)| {
                offset.filter(|&o| (0..maps[m].len()).all(|i| owner[o + i] == (m, i)))
            })
            .collect();
        Self {
            maps,
            n_free,
            owner,
            inertia,
            weight,
            offsets,
            owned_offsets,
        }
    }

    /// The step of member `m`'s own DOF `i` given the global step `dx`.
    #[inline]
    pub(super) fn gather(&self, m: usize, i: usize, dx: &[f64]) -> f64 {
        let s = self.maps[m][i];
        if s.dof == FIXED {
            0.0
        } else {
            s.coef * dx[s.dof]
        }
    }
}
