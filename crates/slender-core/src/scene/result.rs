//! What a scene solve reports: per rod its shape, strains, bend radius, reactions and the load
//! balance of the structures it belongs to; per structure its solve and stability.

use serde::Serialize;

use crate::geometry::Vec3;
use crate::solver::SolveReport;
use crate::structure::{HeldForces, MemberState, Structure, StructureState};

use super::compile::{CompiledRod, CompiledScene};
use super::spec::SupportKind;

/// The reaction of one support.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SupportResult {
    /// Index in the rod's `supports`.
    pub support: usize,
    /// Clamp, pin, clip, slider or twist hold.
    pub kind: SupportKind,
    /// The support's vertex.
    pub vertex: usize,
    /// Its position (m).
    pub position: [f64; 3],
    /// Force the support applies to the rod (N).
    pub force: [f64; 3],
    /// Moment the support applies to the rod, about its vertex (N m).
    pub moment: [f64; 3],
}

/// Stability of an equilibrium as a scene solve reports it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StabilityResult {
    /// True if the returned equilibrium is stable (no negative Hessian eigenvalue; exact null
    /// modes, e.g. a free roll of a round ring, counted apart).
    pub stable: bool,
    /// Negative eigenvalues of the returned equilibrium's Hessian.
    pub unstable_modes: usize,
    /// Zero eigenvalues (null modes: symmetries that cost no energy).
    pub null_modes: usize,
    /// True if the solve first reached an unstable equilibrium and followed its unstable mode
    /// to the returned one.
    pub followed_unstable_mode: bool,
    /// Negative eigenvalues of the unstable equilibrium that was left (0 if none).
    pub left_unstable_modes: usize,
    /// Energy of the returned equilibrium minus the unstable one's (J; 0 if none).
    pub energy_drop: f64,
}

impl StabilityResult {
    /// The stability of a report's equilibrium (no branch switch).
    pub fn of(report: &SolveReport) -> Self {
        let i = report.inertia.unwrap_or_default();
        let (unstable, null) = match report.modes {
            Some(m) => (m.unstable, m.null),
            None => (i.negative, i.zero),
        };
        Self {
            stable: report.stable() == Some(true),
            unstable_modes: unstable,
            null_modes: null,
            // Bifurcations crossed inside the load path were followed by the solver itself.
            followed_unstable_mode: report.branch_switches > 0,
            left_unstable_modes: 0,
            energy_drop: 0.0,
        }
    }
}

/// One structure's solve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StructureResult {
    /// The rods (names) it is made of.
    pub rods: Vec<String>,
    /// Solver report.
    pub report: SolveReport,
    /// Stability.
    pub stability: StabilityResult,
    /// |Σ reactions + Σ applied forces| (N).
    pub force_imbalance: f64,
    /// |Σ moments of reactions and applied loads| about the centroid (N m).
    pub moment_imbalance: f64,
    /// `force_imbalance` over Σ|forces| involved.
    pub relative_force_imbalance: f64,
    /// `moment_imbalance` over Σ|moments| involved.
    pub relative_moment_imbalance: f64,
}

/// Equilibrium of one rod.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RodResult {
    /// Rod name.
    pub name: String,
    /// Vertex positions (m).
    pub positions: Vec<[f64; 3]>,
    /// Material frame (m₁, m₂, t) of every edge.
    pub frames: Vec<[[f64; 3]; 3]>,
    /// Material curvatures (κ₁, κ₂) at every vertex (1/m; 0 at a free end).
    pub curvature: Vec<[f64; 2]>,
    /// Twist rate at every vertex (rad/m; 0 at a free end).
    pub twist: Vec<f64>,
    /// Axial strain of every edge.
    pub edge_strain: Vec<f64>,
    /// Smallest bend radius along the rod (m; infinite if straight).
    pub min_bend_radius: f64,
    /// Vertices bent tighter than the rod's allowed `min_bend_radius` (empty if none given).
    pub tight_vertices: Vec<usize>,
    /// Reactions, in the order of the rod's supports.
    pub supports: Vec<SupportResult>,
    /// Resultant applied force (N) on this rod: gravity, point, line and follower loads.
    pub applied_force: [f64; 3],
    /// Resultant applied moment about the rod's centroid (N m).
    pub applied_moment: [f64; 3],
    /// Worst |Σ reactions + Σ applied forces| (N) over the structures the rod belongs to (the
    /// rod alone unless joined to others).
    pub force_imbalance: f64,
    /// Worst moment imbalance (N m) over those structures.
    pub moment_imbalance: f64,
    /// `force_imbalance` relative to the forces involved.
    pub relative_force_imbalance: f64,
    /// `moment_imbalance` relative to the moments involved.
    pub relative_moment_imbalance: f64,
    /// Solver report of every part of the rod between interior clamps (its structure's).
    pub reports: Vec<SolveReport>,
    /// True if every part converged.
    pub converged: bool,
    /// True if every part's equilibrium is stable.
    pub stable: bool,
}

/// One equilibrium of the sequence: step 0 is the loaded scene, then one per motion step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneStep {
    /// Step number (0 = initial equilibrium).
    pub step: usize,
    /// Motion stage of this step (None for step 0).
    pub stage: Option<usize>,
    /// Progress through the stage (1 at its end).
    pub stage_fraction: f64,
    /// Wall time of the solve (s); filled by the caller that has a clock (0 otherwise).
    pub seconds: f64,
    /// Load steps the motion step was split into to converge (1 for step 0).
    pub pieces: usize,
    /// Every rod.
    pub rods: Vec<RodResult>,
    /// Every structure (groups of rod parts solved together).
    pub structures: Vec<StructureResult>,
    /// Every shell strip.
    pub shells: Vec<super::shells::ShellResult>,
    /// True if every rod and shell converged.
    pub converged: bool,
    /// True if every equilibrium is stable.
    pub stable: bool,
    /// In a time-stepped scene (`[time]`): the time, energy and step of this frame. Absent
    /// from the output of equilibrium solves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time: Option<TimeFrame>,
    /// Every obstacle with its active contacts (absent without obstacles).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<ObstacleResult>,
    /// Smallest gap (m) between a rod's surface (a shell strip's face) and an obstacle over the
    /// scene (absent without obstacles; negative would be a penetration, which the barrier
    /// prevents).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_gap: Option<f64>,
    /// With self-contact (`contact.self_contact`): every active contact between segments of
    /// the centerlines — a cable touching itself or another cable — with the force on each
    /// side (absent without self-contact; empty when nothing touches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segment_contacts: Option<Vec<SegmentContactResult>>,
    /// With self-contact: the smallest gap (m) between the surfaces of two segments that may
    /// touch (absent without self-contact, or when no two segments are near each other).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_segment_gap: Option<f64>,
    /// Rod edges whose centerline, and shell-strip faces whose mid-surface, runs *through* an
    /// obstacle between their vertices (absent when there is none). Contact acts at the
    /// vertices, so an obstacle thinner than an element can pass between them: such a shape
    /// is the discrete model's equilibrium but not the cable's, and a finer mesh is needed
    /// there.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub edges_through_obstacles: Vec<EdgeThroughObstacle>,
}

/// A rod edge whose centerline, or a shell strip's face whose mid-surface, passes through an
/// obstacle between its vertices (see [`SceneStep::edges_through_obstacles`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EdgeThroughObstacle {
    /// The rod or the shell strip (name).
    pub rod: String,
    /// True for a shell strip's face, false for a rod's edge.
    pub shell: bool,
    /// A rod's edge: its first vertex (the edge joins it to the next one); a strip's face: its
    /// index in the strip's `faces`.
    pub edge: usize,
    /// The element's vertices: the edge's two, or the face's three (indices into the rod's or
    /// the strip's positions).
    pub vertices: Vec<usize>,
    /// The obstacle (name).
    pub obstacle: String,
    /// The deepest point of the centerline inside the obstacle (m).
    pub position: [f64; 3],
    /// How deep (m) that point is inside the obstacle's surface (> 0); 0 for a mesh, a
    /// surface without an inside, which the element crosses at `position`.
    pub depth: f64,
}

/// What touches in a [`SegmentContactResult`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SegmentContactKind {
    /// Two edges crossing (side a and side b are edges).
    EdgeEdge,
    /// A vertex against an edge (side a is a vertex, side b an edge): where edges run
    /// parallel, the edge–edge contact fades out and these carry the load.
    VertexEdge,
}

/// One contact between two segments of the centerlines (self-contact of a cable, or two
/// cables of one structure pressing on each other). The forces are those the barrier applies
/// at the segments' vertices, summed per side: equal and opposite, and together with the
/// supports, the obstacles' contacts and the loads they balance each rod. The share acting
/// on a vertex held by a support goes to that support (as for obstacle contacts) and is left
/// out of the side's force.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SegmentContactResult {
    /// Edge–edge or vertex–edge.
    pub kind: SegmentContactKind,
    /// Side a: the rod (name).
    pub rod_a: String,
    /// Side a's edge (the rod's numbering; edge i joins vertices i and i + 1), for an
    /// edge–edge contact.
    pub edge_a: Option<usize>,
    /// Side a's vertex, for a vertex–edge contact.
    pub vertex_a: Option<usize>,
    /// Side a's closest point to side b (m).
    pub point_a: [f64; 3],
    /// Force (N) side b applies to side a.
    pub force_a: [f64; 3],
    /// Side b: the rod (name).
    pub rod_b: String,
    /// Side b's edge.
    pub edge_b: usize,
    /// Side b's closest point to side a (m).
    pub point_b: [f64; 3],
    /// Force (N) side a applies to side b.
    pub force_b: [f64; 3],
    /// Gap (m) between the two surfaces: distance of the closest points minus twice the
    /// contact radius, in (0, activation).
    pub gap: f64,
}

/// An obstacle and the forces it applies.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObstacleResult {
    /// Name (`obstacle<i>` by default).
    pub name: String,
    /// Coulomb coefficient μ.
    pub friction: f64,
    /// Resultant force (N) the obstacle applies to the rods and shell strips (normal and
    /// friction).
    pub force: [f64; 3],
    /// Its active contacts (gap below the activation distance).
    pub contacts: Vec<ContactResult>,
}

/// One contact of a rod vertex with an obstacle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactResult {
    /// The rod (name), or the shell strip's when `shell` is true.
    pub rod: String,
    /// True if `rod` names a shell strip (`shells[]`): `vertex` is then the strip's vertex
    /// of the result grid, station·(width_elements + 1) + column, and the gap is measured
    /// from its mid-surface less h/2. Absent (false) for a rod.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub shell: bool,
    /// The rod's (or strip's) vertex.
    pub vertex: usize,
    /// The vertex's position (m).
    pub position: [f64; 3],
    /// Gap (m) between the rod's surface (a strip's face, h/2 off its mid-surface) and the
    /// obstacle's, in (0, activation).
    pub gap: f64,
    /// Outward unit normal of the obstacle there.
    pub normal: [f64; 3],
    /// Normal force on the rod (N), along `normal`.
    pub normal_force: [f64; 3],
    /// Friction force on the rod (N), tangential, |friction| ≤ μ |normal force|.
    pub friction_force: [f64; 3],
    /// True while the contact sticks.
    pub sticking: bool,
}

/// One frame of a time-stepped scene: the state after `time_step` steps.
///
/// The frame's rods and structures are reported as for an equilibrium, with these
/// differences: the moving state is not an equilibrium, so a structure's force and moment
/// imbalance is the resultant of the inertial forces (Σ m a), not an error; no stability is
/// analysed (`stable` is true, no modes); the solver report is that of the frame's last time
/// step (frame 0: no solve, 0 iterations), with `relative_residual`, `force_scale`,
/// `residual_floor` and `energy_decrement` not computed (null).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimeFrame {
    /// Time (s).
    pub t: f64,
    /// Frame number (0 = the start).
    pub frame: usize,
    /// Time steps taken to reach it.
    pub time_step: usize,
    /// Energies of the whole scene (J).
    pub energy: FrameEnergy,
    /// Newton iterations of the last time step over all structures (0 for frame 0).
    pub iterations: usize,
    /// True: every time step up to this frame converged (frames are written only then).
    pub converged: bool,
}

/// The mechanical energy (J) of a moving scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct FrameEnergy {
    /// ½ vᵀ M v, lumped mass.
    pub kinetic: f64,
    /// Elastic (strain) energy.
    pub elastic: f64,
    /// Potential of gravity and of the dead point and line loads: minus their work from the
    /// rest state (0 at t = 0).
    pub gravity_and_loads: f64,
    /// Elastic + gravity and loads.
    pub potential: f64,
    /// Kinetic + potential: constant in an undamped motion with the energy-conserving scheme.
    pub total: f64,
}

fn arr(v: Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Generalized forces the supports of every member supply, joints included.
fn structure_gradients(s: &Structure, st: &StructureState) -> Vec<HeldForces> {
    let mut out: Vec<HeldForces> = s
        .members()
        .iter()
        .zip(&st.members)
        .map(|(m, ms)| m.held_forces(ms, 1.0))
        .collect();
    s.add_joint_gradients(st, &mut out);
    out
}

/// Force and moment balance of a structure: (imbalance, relative) for force and moment;
/// `external` are further forces (position, force) on it: its contact forces.
fn balance(
    scene: &CompiledScene,
    k: usize,
    st: &StructureState,
    grads: &[HeldForces],
    external: &[(Vec3, Vec3)],
) -> [f64; 4] {
    let s = &scene.structures[k];
    let mut total_f = Vec3::zeros();
    let mut total_m = Vec3::zeros();
    let mut f_scale = 0.0;
    let mut m_scale = 0.0;
    let mut length = 0.0;
    // Applied loads about the origin, then reactions.
    for (r, rs) in s.members().iter().zip(&st.members) {
        let l = r.applied_loads(rs, 1.0);
        total_f += l.force;
        total_m += l.moment;
        f_scale += l.force.norm();
        // The loads' moments may cancel (forces along a line through the origin): their scale
        // is the force times the structure's reach from the origin.
        let reach = rs.positions().iter().map(|x| x.norm()).fold(0.0, f64::max);
        m_scale += l.moment.norm() + reach * l.force.norm();
        length += r.length();
    }
    let mut reaction_moments = 0.0;
    for rod in &scene.rods {
        for (si, sup) in rod.supports.iter().enumerate() {
            let _ = sup;
            let Some((_, f, mo, x)) = support_reaction(scene, rod, si, k, grads, st) else {
                continue;
            };
            total_f += f;
            total_m += x.cross(&f) + mo;
            f_scale += f.norm();
            m_scale += x.norm() * f.norm() + mo.norm();
            reaction_moments += mo.norm();
        }
    }
    for (x, f) in external {
        total_f += f;
        total_m += x.cross(f);
        f_scale += f.norm();
        m_scale += x.norm() * f.norm();
    }
    // A moment M at a support is carried by forces of order M/L inside the rod: count it in
    // the force scale, so that a rod bent by its clamps alone has a meaningful one.
    f_scale += reaction_moments / length.max(f64::MIN_POSITIVE);
    let rel = |x: f64, s: f64| if s > 0.0 { x / s } else { x };
    [
        total_f.norm(),
        total_m.norm(),
        rel(total_f.norm(), f_scale),
        rel(total_m.norm(), m_scale),
    ]
}

/// The reaction (part index, force, moment about the support's vertex, position) of support
/// `si` of `rod` if it acts on structure `k`.
fn support_reaction(
    scene: &CompiledScene,
    rod: &CompiledRod,
    si: usize,
    k: usize,
    grads: &[HeldForces],
    st: &StructureState,
) -> Option<(usize, Vec3, Vec3, Vec3)> {
    let sup = &rod.supports[si];
    let s = &scene.structures[k];
    let mut force = Vec3::zeros();
    let mut moment = Vec3::zeros();
    let mut found = None;
    let mut xv = Vec3::zeros();
    for (pi, part) in rod.parts.iter().enumerate() {
        if part.structure != k {
            continue;
        }
        let member = &s.members()[part.member];
        let ms = &st.members[part.member];
        let x = ms.positions();
        let n = member.n_edges();
        let local = |v: usize| v - part.first_vertex;
        if part.contains(sup.vertex) {
            xv = x[local(sup.vertex)];
            found = Some(pi);
        }
        match (&grads[part.member], ms) {
            (HeldForces::Der(g), MemberState::Der(rs)) => match sup.kind {
                SupportKind::TwistHold => {
                    let e = sup.edge.expect("edge");
                    if e >= part.first_vertex && e < part.first_vertex + n {
                        let j = e - part.first_vertex;
                        let t = rs
                            .frames()
                            .edge(crate::rod::frames::EdgeId::Real(j))
                            .tangent;
                        moment += t * g.thetas[j];
                        found = Some(pi);
                    }
                }
                _ => {
                    for &h in &sup.held {
                        if !part.contains(h) {
                            continue;
                        }
                        let lv = local(h);
                        let f = g.vertices[lv];
                        force += f;
                        moment += (x[lv] - xv).cross(&f);
                        if sup.kind == SupportKind::Clamp {
                            if lv == 0 && rs.frames().ghost_start.is_some() {
                                moment += g.ghost_moments[0];
                            }
                            if lv == n && rs.frames().ghost_end.is_some() {
                                moment += g.ghost_moments[1];
                            }
                        }
                    }
                }
            },
            (HeldForces::Framed(reactions), _) => {
                for &h in &sup.held {
                    if !part.contains(h) {
                        continue;
                    }
                    let lv = local(h);
                    if let Some(r) = reactions.iter().find(|r| r.vertex == lv) {
                        force += r.force;
                        moment += (x[lv] - xv).cross(&r.force) + r.moment;
                    }
                }
            }
            _ => unreachable!("forces and state of different models"),
        }
    }
    found.map(|p| (p, force, moment, xv))
}

/// Builds the results of every rod and structure from the structures' states.
pub fn scene_results(
    scene: &CompiledScene,
    states: &[StructureState],
    reports: &[SolveReport],
    stability: &[StabilityResult],
) -> (Vec<RodResult>, Vec<StructureResult>) {
    scene_results_with(scene, states, reports, stability, &[])
}

/// As [`scene_results`], with further forces (position, force) per structure in the balance:
/// its contact forces (empty: none).
pub fn scene_results_with(
    scene: &CompiledScene,
    states: &[StructureState],
    reports: &[SolveReport],
    stability: &[StabilityResult],
    external: &[Vec<(Vec3, Vec3)>],
) -> (Vec<RodResult>, Vec<StructureResult>) {
    let grads: Vec<Vec<HeldForces>> = scene
        .structures
        .iter()
        .zip(states)
        .map(|(s, st)| structure_gradients(s, st))
        .collect();
    let balances: Vec<[f64; 4]> = (0..scene.structures.len())
        .map(|k| {
            let ext = external.get(k).map_or(&[][..], |e| e.as_slice());
            balance(scene, k, &states[k], &grads[k], ext)
        })
        .collect();
    let structures = (0..scene.structures.len())
        .map(|k| {
            let mut rods: Vec<String> = scene
                .rods
                .iter()
                .filter(|r| r.parts.iter().any(|p| p.structure == k))
                .map(|r| r.name.clone())
                .collect();
            rods.dedup();
            StructureResult {
                rods,
                report: reports[k].clone(),
                stability: stability[k].clone(),
                force_imbalance: balances[k][0],
                moment_imbalance: balances[k][1],
                relative_force_imbalance: balances[k][2],
                relative_moment_imbalance: balances[k][3],
            }
        })
        .collect();
    let rods = scene
        .rods
        .iter()
        .map(|rod| rod_result(scene, rod, states, reports, stability, &grads, &balances))
        .collect();
    (rods, structures)
}

fn rod_result(
    scene: &CompiledScene,
    rod: &CompiledRod,
    states: &[StructureState],
    reports: &[SolveReport],
    stability: &[StabilityResult],
    grads: &[Vec<HeldForces>],
    balances: &[[f64; 4]],
) -> RodResult {
    let nv = rod.n_edges + 1;
    let mut positions = vec![Vec3::zeros(); nv];
    let mut frames = Vec::with_capacity(rod.n_edges);
    let mut curvature = vec![[0.0; 2]; nv];
    let mut twist = vec![0.0; nv];
    let mut hits = vec![0usize; nv];
    let mut edge_strain = Vec::with_capacity(rod.n_edges);
    let mut applied_force = Vec3::zeros();
    let mut applied_moment_origin = Vec3::zeros();
    let mut part_reports = Vec::new();
    let mut structures_of_rod = Vec::new();
    for part in &rod.parts {
        let s = &scene.structures[part.structure];
        let r = &s.members()[part.member];
        let rs = &states[part.structure].members[part.member];
        let a = part.first_vertex;
        for (k, p) in rs.positions().iter().enumerate() {
            positions[a + k] = *p;
        }
        for f in r.edge_frames(rs) {
            frames.push([arr(f[0]), arr(f[1]), arr(f[2])]);
        }
        for h in r.vertex_strains(rs) {
            let v = a + h.vertex;
            curvature[v][0] += h.curvature[0];
            curvature[v][1] += h.curvature[1];
            twist[v] += h.twist;
            hits[v] += 1;
        }
        edge_strain.extend(r.edge_strains(rs));
        let l = r.applied_loads(rs, 1.0);
        applied_force += l.force;
        applied_moment_origin += l.moment;
        part_reports.push(reports[part.structure].clone());
        if !structures_of_rod.contains(&part.structure) {
            structures_of_rod.push(part.structure);
        }
    }
    // A vertex shared by two parts (interior clamp) has a half hinge on each side.
    for v in 0..nv {
        if hits[v] > 1 {
            let w = 1.0 / hits[v] as f64;
            curvature[v][0] *= w;
            curvature[v][1] *= w;
            twist[v] *= w;
        }
    }
    let kappa_max = curvature
        .iter()
        .map(|c| (c[0] * c[0] + c[1] * c[1]).sqrt())
        .fold(0.0, f64::max);
    let tight_vertices = match rod.min_bend_radius {
        Some(r_min) => (0..nv)
            .filter(|&v| {
                let k = (curvature[v][0].powi(2) + curvature[v][1].powi(2)).sqrt();
                k * r_min > 1.0
            })
            .collect(),
        None => Vec::new(),
    };
    let centroid = positions.iter().sum::<Vec3>() / nv as f64;
    let applied_moment = applied_moment_origin - centroid.cross(&applied_force);
    let mut supports = Vec::with_capacity(rod.supports.len());
    for (si, sup) in rod.supports.iter().enumerate() {
        let mut force = Vec3::zeros();
        let mut moment = Vec3::zeros();
        for &k in &structures_of_rod {
            if let Some((_, f, m, _)) = support_reaction(scene, rod, si, k, &grads[k], &states[k]) {
                force += f;
                moment += m;
            }
        }
        supports.push(SupportResult {
            support: si,
            kind: sup.kind,
            vertex: sup.vertex,
            position: arr(positions[sup.vertex]),
            force: arr(force),
            moment: arr(moment),
        });
    }
    let worst = |i: usize| {
        structures_of_rod
            .iter()
            .map(|&k| balances[k][i])
            .fold(0.0, f64::max)
    };
    let converged = part_reports.iter().all(|r| r.converged());
    RodResult {
        name: rod.name.clone(),
        positions: positions.iter().map(|p| arr(*p)).collect(),
        frames,
        curvature,
        twist,
        edge_strain,
        min_bend_radius: if kappa_max > 0.0 {
            1.0 / kappa_max
        } else {
            f64::INFINITY
        },
        tight_vertices,
        supports,
        applied_force: arr(applied_force),
        applied_moment: arr(applied_moment),
        force_imbalance: worst(0),
        moment_imbalance: worst(1),
        relative_force_imbalance: worst(2),
        relative_moment_imbalance: worst(3),
        reports: part_reports,
        converged,
        stable: structures_of_rod.iter().all(|&k| stability[k].stable),
    }
}
