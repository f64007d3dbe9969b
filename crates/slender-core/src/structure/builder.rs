//! Building a structure: members, joints, sliders and twist holds, validated.

use crate::assembly::FIXED;
use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::linalg::{AdaptiveMatrix, SparseSymmetricMatrix, SymmetricBandMatrix};
use crate::rod::bending::{material_curvature, BendingHinge};
use crate::rod::hinge::HingeFrame;
use crate::rod::twisting::TwistingHinge;
use crate::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};

use super::dof_map::{GlobalDofs, Tie};
use super::joint::{HingeSide, JointHinge};
use super::member::Member;
use super::model::{Structure, StructurePath, StructureState};

/// One end of a member meeting a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointEnd {
    /// Member index.
    pub member: usize,
    /// The member's end vertex (0 or its last vertex).
    pub vertex: usize,
}

/// A sliding support: the vertex is held across the straight axis through its position and
/// slides freely along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderSupport {
    /// Member index.
    pub member: usize,
    /// The held vertex.
    pub vertex: usize,
    /// Unit axis of sliding.
    pub axis: Vec3,
}

/// A twist hold: the material angle of an edge is held (its position stays free).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TwistHold {
    /// Member index.
    pub member: usize,
    /// The held edge.
    pub edge: usize,
}

/// Largest half-bandwidth kept in banded storage; wider patterns go sparse.
const MAX_BAND: usize = 16;

/// Builds a [`Structure`].
#[derive(Clone, Debug, Default)]
pub struct StructureBuilder {
    members: Vec<Member>,
    joints: Vec<Vec<JointEnd>>,
    sliders: Vec<SliderSupport>,
    holds: Vec<TwistHold>,
    free_motion: bool,
}

impl StructureBuilder {
    /// An empty structure.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a member; members are numbered in the order they are added.
    pub fn member(mut self, m: Member) -> Self {
        self.members.push(m);
        self
    }

    /// Joins member ends rigidly at one point (at least two ends; their rest positions must
    /// coincide). The first end is the joint's master: a support at the joint belongs to it.
    pub fn joint(mut self, ends: Vec<JointEnd>) -> Self {
        self.joints.push(ends);
        self
    }

    /// Adds a sliding support.
    pub fn slider(mut self, s: SliderSupport) -> Self {
        self.sliders.push(s);
        self
    }

    /// Adds a twist hold.
    pub fn twist_hold(mut self, h: TwistHold) -> Self {
        self.holds.push(h);
        self
    }

    /// Accepts a structure that can move rigidly (not held against every rigid-body motion):
    /// for time stepping, where the mass makes every step well posed (a pendulum, a cable in
    /// free fall). Its equilibria cannot be solved.
    pub fn allow_free_motion(mut self) -> Self {
        self.free_motion = true;
        self
    }

    /// Validates and builds; errors name the joint, slider or hold and what is wrong. A
    /// structure that can still move rigidly (a singular stiffness at rest) is an error
    /// unless [`Self::allow_free_motion`].
    pub fn build(mut self) -> Result<Structure, ModelError> {
        if self.members.is_empty() {
            return Err(ModelError::structure(
                "members",
                "a structure needs at least one member",
            ));
        }
        let nm = self.members.len();
        let length_scale = self.members.iter().map(|m| m.length()).fold(0.0, f64::max);
        let mut ties: Vec<Vec<Tie>> = self
            .members
            .iter()
            .map(|m| vec![Tie::Own; m.n_free()])
            .collect();
        let mut groups = 0usize;
        let mut anchors: Vec<Vec<usize>> = vec![Vec::new(); nm];
        let mut joint_groups = Vec::new();
        let mut used: Vec<(usize, usize)> = Vec::new();

        for (k, ends) in self.joints.iter().enumerate() {
            let path = format!("joints[{k}]");
            if ends.len() < 2 {
                return Err(ModelError::structure(
                    path,
                    "a joint joins at least two member ends",
                ));
            }
            for (e, end) in ends.iter().enumerate() {
                if end.member >= nm {
                    return Err(ModelError::structure(
                        format!("{path}[{e}].member"),
                        format!("{}: must be < {nm} (number of members)", end.member),
                    ));
                }
                if self.members[end.member].as_der().is_none() {
                    return Err(ModelError::structure(
                        format!("{path}[{e}].member"),
                        format!(
                            "member {} is a {} rod: joints join discrete elastic rods (model \"der\") only",
                            end.member,
                            self.members[end.member].model_name()
                        ),
                    ));
                }
                let last = self.members[end.member].n_edges();
                if end.vertex != 0 && end.vertex != last {
                    return Err(ModelError::structure(
                        format!("{path}[{e}].vertex"),
                        format!(
                            "{}: joints connect member ends (vertex 0 or {last}); split a cable where a branch leaves it",
                            end.vertex
                        ),
                    ));
                }
                if used.contains(&(end.member, end.vertex)) {
                    return Err(ModelError::structure(
                        format!("{path}[{e}]"),
                        format!(
                            "member {} vertex {} is already in a joint",
                            end.member, end.vertex
                        ),
                    ));
                }
                used.push((end.member, end.vertex));
            }
            let master = ends[0];
            let x0 = self.members[master.member].rest_state().positions()[master.vertex];
            for (e, end) in ends.iter().enumerate().skip(1) {
                let x = self.members[end.member].rest_state().positions()[end.vertex];
                if !((x - x0).norm() <= 1e-9 * length_scale.max(1e-300)) {
                    return Err(ModelError::structure(
                        format!("{path}[{e}]"),
                        format!(
                            "member {} vertex {} is at {:?}, {:.3e} m from the joint's first end at {:?}: joined ends must meet",
                            end.member,
                            end.vertex,
                            [x.x, x.y, x.z],
                            (x - x0).norm(),
                            [x0.x, x0.y, x0.z]
                        ),
                    ));
                }
                if self.members[end.member].vertex_dof(end.vertex, 0) == FIXED {
                    return Err(ModelError::structure(
                        format!("{path}[{e}]"),
                        "only the joint's first end may be held by a support (its other ends follow it)",
                    ));
                }
            }
            for c in 0..3 {
                let i0 = self.members[master.member].vertex_dof(master.vertex, c);
                if i0 == FIXED {
                    for end in &ends[1..] {
                        let i = self.members[end.member].vertex_dof(end.vertex, c);
                        ties[end.member][i] = Tie::Fixed;
                    }
                } else {
                    for end in ends {
                        let i = self.members[end.member].vertex_dof(end.vertex, c);
                        ties[end.member][i] = Tie::Group {
                            group: groups,
                            coef: 1.0,
                        };
                    }
                    groups += 1;
                }
            }
            for end in ends {
                anchors[end.member].push(end.vertex);
            }
            joint_groups.push(
                ends.iter()
                    .map(|e| (e.member, e.vertex))
                    .collect::<Vec<_>>(),
            );
        }

        for (k, s) in self.sliders.iter_mut().enumerate() {
            let path = format!("sliders[{k}]");
            if s.member >= nm {
                return Err(ModelError::structure(
                    format!("{path}.member"),
                    format!("{}: must be < {nm}", s.member),
                ));
            }
            let n = self.members[s.member].n_edges();
            if s.vertex > n {
                return Err(ModelError::structure(
                    format!("{path}.vertex"),
                    format!("{}: must be <= {n}", s.vertex),
                ));
            }
            let norm = s.axis.norm();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(ModelError::structure(
                    format!("{path}.axis"),
                    "must be a finite, non-zero direction",
                ));
            }
            s.axis /= norm;
            if used.contains(&(s.member, s.vertex)) {
                return Err(ModelError::structure(
                    format!("{path}.vertex"),
                    "the vertex is already in a joint or held by another slider",
                ));
            }
            used.push((s.member, s.vertex));
            for c in 0..3 {
                let i = self.members[s.member].vertex_dof(s.vertex, c);
                if i == FIXED {
                    return Err(ModelError::structure(
                        format!("{path}.vertex"),
                        "the vertex is already held by a clamp, pin or clip",
                    ));
                }
                ties[s.member][i] = Tie::Group {
                    group: groups,
                    coef: s.axis[c],
                };
            }
            groups += 1;
            anchors[s.member].push(s.vertex);
        }

        for (k, h) in self.holds.iter().enumerate() {
            let path = format!("twist_holds[{k}]");
            if h.member >= nm {
                return Err(ModelError::structure(
                    format!("{path}.member"),
                    format!("{}: must be < {nm}", h.member),
                ));
            }
            let Some(rod) = self.members[h.member].as_der() else {
                return Err(ModelError::structure(
                    format!("{path}.member"),
                    format!(
                        "member {} is a {} rod: a twist hold holds a discrete elastic rod's edge angle (model \"der\")",
                        h.member,
                        self.members[h.member].model_name()
                    ),
                ));
            };
            let n = rod.n_edges();
            if h.edge >= n {
                return Err(ModelError::structure(
                    format!("{path}.edge"),
                    format!("{}: must be < {n}", h.edge),
                ));
            }
            let i = rod.dofs().theta(h.edge);
            if i == FIXED {
                return Err(ModelError::structure(
                    format!("{path}.edge"),
                    "the edge's twist is already held",
                ));
            }
            ties[h.member][i] = Tie::Fixed;
        }

        for (m, a) in anchors.iter().enumerate() {
            if !a.is_empty() {
                if let Some(r) = self.members[m].as_der_mut() {
                    r.set_anchors(a);
                }
            }
        }
        let dofs = GlobalDofs::new(&self.members, &ties);

        // Joint hinges: a star from the master end to every other end.
        let mut joints = Vec::new();
        for ends in &self.joints {
            let master = ends[0];
            for end in &ends[1..] {
                joints.push(self.joint_hinge(joints.len(), master, *end, &dofs));
            }
        }
        let rest = StructureState {
            members: self.members.iter().map(|m| m.rest_state()).collect(),
            joint_twists: vec![0.0; joints.len()],
        };
        let mut structure = Structure {
            members: self.members,
            dofs,
            joints,
            joint_groups,
            sliders: self.sliders,
            holds: self.holds,
            hessian: AdaptiveMatrix::Band(SymmetricBandMatrix::new(0, 0)),
            rest,
            path: StructurePath::default(),
        };
        structure.hessian = hessian_pattern(&structure);
        // Rest twists and curvatures of the joint hinges from the rest state: stress-free rest.
        let mut twists = vec![0.0; structure.joints.len()];
        for (k, j) in structure.joints.iter().enumerate() {
            twists[k] = j.continued_twist(&structure.rest, 0.0);
        }
        structure.rest.joint_twists = twists;
        let rest = structure.rest.clone();
        for j in structure.joints.iter_mut() {
            let hs = j.hinge_state(&rest);
            j.bending.rest_kappa = material_curvature(&HingeFrame::new(&hs));
            j.twisting.rest_twist = hs.twist();
        }
        if !self.free_motion {
            check_no_free_motion(&structure)?;
        }
        Ok(structure)
    }

    /// The hinge between the master end's edge and another end's edge at a joint.
    fn joint_hinge(
        &self,
        index: usize,
        master: JointEnd,
        end: JointEnd,
        dofs: &GlobalDofs,
    ) -> JointHinge {
        let side = |e: JointEnd, incoming: bool| -> HingeSide {
            let r = self.members[e.member].as_der().expect("rod");
            let n = r.n_edges();
            let (edge, outer, stored_into_joint) = if e.vertex == 0 {
                (0, 1, false)
            } else {
                (n - 1, n - 1, true)
            };
            // Side 0 of a hinge is its incoming edge, side 1 its outgoing one.
            let sign = if stored_into_joint == incoming {
                1.0
            } else {
                -1.0
            };
            HingeSide {
                member: e.member,
                edge,
                joint_vertex: e.vertex,
                outer_vertex: outer,
                sign,
            }
        };
        let s0 = side(master, true);
        let s1 = side(end, false);
        let r0 = self.members[s0.member].as_der().expect("rod");
        let r1 = self.members[s1.member].as_der().expect("rod");
        let g = |m: usize, i: usize| -> usize {
            if i == FIXED {
                FIXED
            } else {
                dofs.maps[m][i].dof
            }
        };
        let mut d = [FIXED; 11];
        for c in 0..3 {
            d[c] = g(s0.member, r0.dofs().vertex(s0.outer_vertex, c));
            d[4 + c] = g(s0.member, r0.dofs().vertex(s0.joint_vertex, c));
            d[8 + c] = g(s1.member, r1.dofs().vertex(s1.outer_vertex, c));
        }
        d[3] = g(s0.member, r0.dofs().theta(s0.edge));
        d[7] = g(s1.member, r1.dofs().theta(s1.edge));
        let (k0, k1) = (r0.properties().stiffness, r1.properties().stiffness);
        let voronoi = 0.5 * (r0.rest_lengths()[s0.edge] + r1.rest_lengths()[s1.edge]);
        JointHinge {
            index,
            sides: [s0, s1],
            dofs: d,
            bending: BendingHinge {
                stiffness: [0.5 * (k0.ei1 + k1.ei1), 0.5 * (k0.ei2 + k1.ei2)],
                rest_kappa: [0.0; 2],
                voronoi_length: voronoi,
            },
            twisting: TwistingHinge {
                stiffness: 0.5 * (k0.gj + k1.gj),
                rest_twist: 0.0,
                voronoi_length: voronoi,
            },
        }
    }
}

/// The Hessian storage: banded if every stencil fits a narrow band, else the sparse pattern.
fn hessian_pattern(s: &Structure) -> AdaptiveMatrix {
    let n = s.dofs.n_free;
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    let mut bw = 0usize;
    let mut add = |idx: &[usize], pairs: &mut Vec<(usize, usize)>| {
        for (a, &i) in idx.iter().enumerate() {
            if i == FIXED {
                continue;
            }
            for &j in &idx[..=a] {
                if j == FIXED {
                    continue;
                }
                bw = bw.max(i.abs_diff(j));
                pairs.push((i, j));
            }
        }
    };
    for (m, member) in s.members.iter().enumerate() {
        let map = &s.dofs.maps[m];
        member.for_each_stencil(|st| {
            let mapped: Vec<usize> = st
                .iter()
                .map(|&i| if i == FIXED { FIXED } else { map[i].dof })
                .collect();
            add(&mapped, &mut pairs);
        });
    }
    for j in &s.joints {
        add(&j.dofs, &mut pairs);
    }
    if bw <= MAX_BAND {
        AdaptiveMatrix::Band(SymmetricBandMatrix::new(n, bw.max(1)))
    } else {
        AdaptiveMatrix::Sparse(SparseSymmetricMatrix::from_pattern(n, pairs))
    }
}

/// Rejects a structure whose stiffness at rest is singular (a free rigid-body motion).
fn check_no_free_motion(s: &Structure) -> Result<(), ModelError> {
    if s.n_free() == 0 {
        return Ok(());
    }
    let rest = s.rest_state().clone();
    let params = SolverParams {
        compute_lambda_min: true,
        ..SolverParams::default()
    };
    let mut solver = EquilibriumSolver::new(s, &rest, params);
    let sol = solver.solve(s, &rest, 0.0, 0.0);
    let singular = match (sol.report.inertia, sol.report.lambda_min_normalized) {
        (Some(i), _) if i.zero > 0 || i.negative > 0 => true,
        (None, _) => true,
        (_, Some(l)) => !(l > 1e-9),
        _ => false,
    };
    if singular {
        return Err(ModelError::structure(
            "supports",
            format!(
                "the structure has a free rigid-body motion (its stiffness at rest is singular, λ_min/(EI/ρAL⁴) = {:.3e}): hold it so that it can neither translate, rotate nor spin about a cable's axis",
                sol.report.lambda_min_normalized.unwrap_or(0.0)
            ),
        ));
    }
    Ok(())
}
