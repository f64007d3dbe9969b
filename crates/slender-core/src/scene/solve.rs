//! Solving a scene: the loaded equilibrium, then each prescribed-motion step warm-started from
//! the previous equilibrium, with reactions, strains and the force/moment balance.

use serde::Serialize;

use crate::geometry::Vec3;
use crate::rod::{Rod, RodLoadPath, RodState, SupportMotion};
use crate::solver::{EquilibriumSolver, SolveReport, SolveStatus};

use super::compile::{CompiledRod, CompiledScene};
use super::spec::{MotionStage, SupportKind};

/// Largest rotation (rad) of a support per load step of a motion step.
pub(super) const MAX_PIECE_ROTATION: f64 = 0.2;
/// Largest translation per load step, as a fraction of the moving segment's length.
pub(super) const MAX_PIECE_TRANSLATION: f64 = 0.05;
/// Newton steps past convergence that bring the residual of a scene down to round-off, so
/// that the reactions balance the loads (the default of `solver.polish_iterations` in scenes).
pub const SCENE_POLISH_ITERATIONS: usize = 3;

/// The reaction of one support.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SupportResult {
    /// Index in the rod's `supports`.
    pub support: usize,
    /// Clamp, pin or clip.
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
    /// Reactions, in the order of the rod's supports.
    pub supports: Vec<SupportResult>,
    /// Resultant applied force (N): gravity, point forces.
    pub applied_force: [f64; 3],
    /// Resultant applied moment about the rod's centroid (N m).
    pub applied_moment: [f64; 3],
    /// |Σ reactions + Σ applied forces| (N).
    pub force_imbalance: f64,
    /// |Σ moments of reactions and applied loads| about the centroid (N m).
    pub moment_imbalance: f64,
    /// `force_imbalance` over Σ|forces| involved.
    pub relative_force_imbalance: f64,
    /// `moment_imbalance` over Σ|moments| involved.
    pub relative_moment_imbalance: f64,
    /// Solver report of every part of the rod between interior clamps.
    pub reports: Vec<SolveReport>,
    /// True if every part converged.
    pub converged: bool,
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
    /// Pieces the motion step was split into to converge (1 for step 0).
    pub pieces: usize,
    /// Every rod.
    pub rods: Vec<RodResult>,
    /// Every shell strip (solved once, at step 0: motion moves rod supports only).
    pub shells: Vec<super::shells::ShellResult>,
    /// True if every rod and shell converged.
    pub converged: bool,
}

/// The solving state of a scene: one equilibrium state per rod segment.
pub struct SceneSolver<'a> {
    scene: &'a CompiledScene,
    /// The segments' rods (own copies: support motion sets their load paths).
    rods: Vec<Vec<Rod>>,
    states: Vec<Vec<RodState>>,
    reports: Vec<Vec<SolveReport>>,
    solvers: Vec<Vec<EquilibriumSolver<RodState>>>,
    shells: Vec<super::shells::ShellResult>,
}

impl<'a> SceneSolver<'a> {
    /// Solves the loaded scene (step 0) from the rest state, ramping the loads.
    pub fn new(scene: &'a CompiledScene) -> (Self, SceneStep) {
        let mut rods = Vec::new();
        let mut states = Vec::new();
        let mut reports = Vec::new();
        let mut solvers = Vec::new();
        for rod in &scene.rods {
            let mut st = Vec::new();
            let mut rep = Vec::new();
            let mut sol = Vec::new();
            for seg in &rod.segments {
                let mut state = seg.rod.rest_state().clone();
                let mut solver = EquilibriumSolver::new(&seg.rod, &state, scene.solver);
                let report = solver.solve_in_place(&seg.rod, &mut state, 0.0, 1.0);
                st.push(state);
                rep.push(report);
                sol.push(solver);
            }
            rods.push(rod.segments.iter().map(|s| s.rod.clone()).collect());
            states.push(st);
            reports.push(rep);
            solvers.push(sol);
        }
        let shells = scene
            .shells
            .iter()
            .map(|s| super::shells::solve_shell(s, &scene.solver))
            .collect();
        let me = Self {
            scene,
            rods,
            states,
            reports,
            solvers,
            shells,
        };
        let step = me.snapshot(0, None, 1.0, 1);
        (me, step)
    }

    /// Number of motion steps over all stages.
    pub fn motion_steps(&self) -> usize {
        self.scene.motion.iter().map(|m| m.steps).sum()
    }

    /// Runs step `step` (1-based over all stages) of the prescribed motion. Steps must be run
    /// in order; after a failed step the rod keeps its last equilibrium and says so.
    ///
    /// # Panics
    /// If `step` is 0 or larger than [`Self::motion_steps`].
    pub fn run_motion_step(&mut self, step: usize) -> SceneStep {
        let (stage_index, k) = self.locate(step);
        let stage: &MotionStage = &self.scene.motion[stage_index];
        let rod: &CompiledRod = &self.scene.rods[stage.rod];
        let support = &rod.supports[stage.support];
        let inv = 1.0 / stage.steps as f64;
        let rotation = Vec3::from(stage.rotate) * inv;
        let translation = Vec3::from(stage.translate) * inv;
        let mut pieces = 0;
        for (si, seg) in rod.segments.iter().enumerate() {
            let held: Vec<usize> = support
                .held
                .iter()
                .filter(|&&h| seg.contains(h))
                .map(|&h| h - seg.first_vertex)
                .collect();
            if held.is_empty() {
                continue;
            }
            // The pivot is the support's vertex; for a clip it is on this segment. The step is
            // a load path of the segment (λ from 0 to 1 moves the support), solved by the
            // solver's continuation in steps no larger than MAX_PIECE_*.
            let pivot_local = support.vertex - seg.first_vertex;
            let length = seg.rod.length();
            let first = ((rotation.norm() / MAX_PIECE_ROTATION)
                .max(translation.norm() / (MAX_PIECE_TRANSLATION * length))
                .ceil() as usize)
                .max(1);
            let rod = &mut self.rods[stage.rod][si];
            let state = &mut self.states[stage.rod][si];
            let motion = SupportMotion {
                vertices: held,
                pivot: state.positions()[pivot_local],
                rotation,
                translation,
            };
            let report = match rod.set_load_path(RodLoadPath::support_motion(vec![motion])) {
                Ok(()) => {
                    let solver = &mut self.solvers[stage.rod][si];
                    let user = solver.params;
                    let piece = 1.0 / first as f64;
                    solver.params.initial_load_step = user.initial_load_step.min(piece);
                    solver.params.max_load_step = user.max_load_step.min(piece);
                    let report = solver.solve_in_place(rod, state, 0.0, 1.0);
                    solver.params = user;
                    report
                }
                Err(e) => {
                    let mut r = self.reports[stage.rod][si].clone();
                    r.status = SolveStatus::NotConverged {
                        reason: e.to_string(),
                    };
                    r
                }
            };
            // Back to the plain load ramp; the state holds the moved supports.
            let _ = rod.set_load_path(RodLoadPath::default());
            pieces += report.load_steps;
            self.reports[stage.rod][si] = report;
        }
        self.snapshot(step, Some(stage_index), (k + 1) as f64 * inv, pieces)
    }

    /// (stage, step within the stage) of global motion step `step` ≥ 1.
    fn locate(&self, step: usize) -> (usize, usize) {
        let mut left = step - 1;
        for (i, m) in self.scene.motion.iter().enumerate() {
            if left < m.steps {
                return (i, left);
            }
            left -= m.steps;
        }
        panic!("motion step {step} is past the last stage");
    }

    fn snapshot(&self, step: usize, stage: Option<usize>, frac: f64, pieces: usize) -> SceneStep {
        let rods: Vec<RodResult> = self
            .scene
            .rods
            .iter()
            .enumerate()
            .map(|(i, r)| rod_result(r, &self.states[i], &self.reports[i]))
            .collect();
        let converged = rods.iter().all(|r| r.converged) && self.shells.iter().all(|s| s.converged);
        SceneStep {
            step,
            stage,
            stage_fraction: frac,
            seconds: 0.0,
            pieces,
            rods,
            shells: self.shells.clone(),
            converged,
        }
    }
}

fn arr(v: Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Assembles the whole rod's result from its segments' states.
fn rod_result(rod: &CompiledRod, states: &[RodState], reports: &[SolveReport]) -> RodResult {
    let nv = rod.n_edges + 1;
    let mut positions = vec![Vec3::zeros(); nv];
    let mut frames = Vec::with_capacity(rod.n_edges);
    let mut curvature = vec![[0.0; 2]; nv];
    let mut twist = vec![0.0; nv];
    let mut hits = vec![0usize; nv];
    let mut edge_strain = Vec::with_capacity(rod.n_edges);
    let mut reactions: Vec<Vec<(Vec3, Vec3)>> = vec![Vec::new(); nv];
    let mut applied_force = Vec3::zeros();
    let mut applied_moment_origin = Vec3::zeros();
    for (seg, s) in rod.segments.iter().zip(states) {
        let a = seg.first_vertex;
        for (k, p) in s.positions().iter().enumerate() {
            positions[a + k] = *p;
        }
        for j in 0..seg.rod.n_edges() {
            let f = s.material_frame(j);
            frames.push([arr(f[0]), arr(f[1]), arr(f[2])]);
        }
        for h in seg.rod.hinge_strains(s) {
            let v = a + h.vertex;
            curvature[v][0] += h.curvature[0];
            curvature[v][1] += h.curvature[1];
            twist[v] += h.twist;
            hits[v] += 1;
        }
        edge_strain.extend(seg.rod.edge_strains(s));
        for r in seg.rod.reactions(s, 1.0) {
            reactions[a + r.vertex].push((r.force, r.moment));
        }
        let l = seg.rod.applied_loads(s, 1.0);
        applied_force += l.force;
        applied_moment_origin += l.moment;
    }
    // A vertex shared by two segments (interior clamp) has a half hinge on each side.
    for v in 0..nv {
        if hits[v] > 1 {
            let w = 1.0 / hits[v] as f64;
            curvature[v][0] *= w;
            curvature[v][1] *= w;
            twist[v] *= w;
        }
    }
    let centroid = positions.iter().sum::<Vec3>() / nv as f64;
    let applied_moment = applied_moment_origin - centroid.cross(&applied_force);
    let mut supports = Vec::with_capacity(rod.supports.len());
    let mut total_f = applied_force;
    let mut total_m = applied_moment;
    let mut f_scale = applied_force.norm();
    let mut m_scale = applied_moment.norm();
    for (k, sup) in rod.supports.iter().enumerate() {
        let xv = positions[sup.vertex];
        let mut force = Vec3::zeros();
        let mut moment = Vec3::zeros();
        for &h in &sup.held {
            for (f, m) in &reactions[h] {
                force += f;
                moment += (positions[h] - xv).cross(f) + m;
            }
        }
        total_f += force;
        let m_c = (xv - centroid).cross(&force) + moment;
        total_m += m_c;
        f_scale += force.norm();
        m_scale += (xv - centroid).norm() * force.norm() + moment.norm();
        supports.push(SupportResult {
            support: k,
            kind: sup.kind,
            vertex: sup.vertex,
            position: arr(xv),
            force: arr(force),
            moment: arr(moment),
        });
    }
    // A moment M at a support is carried by forces of order M/L inside the rod: count it
    // in the force scale, so that a rod bent by its clamps alone has a meaningful one.
    let length: f64 = rod.segments.iter().map(|s| s.rod.length()).sum();
    f_scale += supports
        .iter()
        .map(|s| Vec3::from(s.moment).norm())
        .sum::<f64>()
        / length;
    let rel = |x: f64, s: f64| if s > 0.0 { x / s } else { x };
    RodResult {
        name: rod.name.clone(),
        positions: positions.iter().map(|p| arr(*p)).collect(),
        frames,
        curvature,
        twist,
        edge_strain,
        supports,
        applied_force: arr(applied_force),
        applied_moment: arr(applied_moment),
        force_imbalance: total_f.norm(),
        moment_imbalance: total_m.norm(),
        relative_force_imbalance: rel(total_f.norm(), f_scale),
        relative_moment_imbalance: rel(total_m.norm(), m_scale),
        reports: reports.to_vec(),
        converged: reports.iter().all(|r| r.converged()),
    }
}
