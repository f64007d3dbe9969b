//! Moving an obstacle in a session: a bracket shifted, a grommet (torus) slid along the
//! harness, the floor raised — the environment edited, where supports are the cable's own.
//!
//! An obstacle is rigid, so a move is a rigid motion: a rotation about the obstacle's
//! reference point (a plane's point, a sphere's, box's or torus's centre, a cylinder's axis
//! point, a mesh's bounding-box centre) and a translation, taken in steps. The cable's current
//! shape may not fit around the moved obstacle — a contact barrier admits no overlap, not even
//! for a Newton start — so each step first moves the centerline vertices that the obstacle
//! sweeps (their path relative to the obstacle meets it, by its own time of impact) or
//! squeezes below the activation distance ĝ: a frictionless surface pushes them along its
//! normal to ĝ (a cable through a slid ring is not dragged along); a rough one carries them
//! rigidly, each keeping its gap, with its sticking anchors. Those moves are spread along each
//! cable to its supports, linearly in arc length, so that a taut cable lifted at one point
//! starts as a V rather than with one edge kinked. Then every structure re-solves warm; a step
//! that does not converge is undone and halved, and a move that still fails is undone whole
//! and the report says why. A flat cable (a mid-edge shell strip in contact) is carried the
//! same way: its vertices are its contact sites, and the moves spread along each column of
//! vertices (one line along the strip per column) to its clamped edges.

use std::sync::Arc;

use nalgebra::Rotation3;

use super::{rotation_vector, solve_structure, EditReport, SceneError, Session};
use crate::contact::{ContactSite, ContactSites, Friction, Obstacle};
use crate::geometry::Vec3;
use crate::scene::compile::contact::obstacle;
use crate::scene::compile::{MAX_STEP_ROTATION, MAX_STEP_TRANSLATION};
use crate::scene::contact_report::{contact_problem, rod_vertex};
use crate::scene::shell_contact_run::ContactStripRun;
use crate::scene::shells::StripModel;
use crate::scene::spec::ObstacleShapeSpec;
use crate::shell::Shell;
use crate::solver::EquilibriumProblem;
use crate::structure::StructureState;

/// Halvings of the steps of one obstacle move before it is given up.
const MAX_OBSTACLE_HALVINGS: usize = 8;

/// Steps one obstacle move may take (as a support move).
const MAX_OBSTACLE_STEPS: f64 = 1000.0;

/// Largest move of the obstacle per step, in units of the shortest rest edge: a pushed
/// vertex then turns its edges by at most a quarter of their length, from which Newton finds
/// the equilibrium (pushed by whole edges, with nothing spread, the solves stalled).
const MAX_STEP_PER_EDGE: f64 = 0.25;

/// A rigid motion x ↦ c + R (x − c) + t (m): rotation `rotation` about the point `about`,
/// then translation `translation`.
#[derive(Clone, Copy, Debug)]
struct RigidMotion {
    rotation: Rotation3<f64>,
    about: Vec3,
    translation: Vec3,
}

impl RigidMotion {
    fn apply(&self, x: &Vec3) -> Vec3 {
        self.about + self.rotation * (x - self.about) + self.translation
    }

    fn inverse_apply(&self, y: &Vec3) -> Vec3 {
        self.about + self.rotation.inverse() * (y - self.translation - self.about)
    }

    /// `self` after `first` is undone: the motion from `first`'s result to `self`'s (both
    /// about the same point).
    fn after_undoing(&self, first: &Self) -> Self {
        debug_assert_eq!(self.about, first.about);
        // y = T(F⁻¹(x)) = c + R Fr⁻¹ (x − tF − c) + t.
        let rotation = self.rotation * first.rotation.inverse();
        let translation = self.translation - rotation * first.translation;
        Self {
            rotation,
            about: self.about,
            translation,
        }
    }
}

/// The reference point (m) obstacles turn about.
fn reference_point(shape: &ObstacleShapeSpec) -> Vec3 {
    match shape {
        ObstacleShapeSpec::Plane { point, .. } | ObstacleShapeSpec::Cylinder { point, .. } => {
            Vec3::from(*point)
        }
        ObstacleShapeSpec::Sphere { center, .. }
        | ObstacleShapeSpec::Box { center, .. }
        | ObstacleShapeSpec::Torus { center, .. } => Vec3::from(*center),
        ObstacleShapeSpec::Mesh { vertices, .. } => {
            let mut lo = Vec3::repeat(f64::INFINITY);
            let mut hi = Vec3::repeat(f64::NEG_INFINITY);
            for v in vertices {
                let v = Vec3::from(*v);
                lo = lo.inf(&v);
                hi = hi.sup(&v);
            }
            if vertices.is_empty() {
                Vec3::zeros()
            } else {
                0.5 * (lo + hi)
            }
        }
    }
}

/// `shape` moved by `m`. A mesh read from a file becomes inline (its moved vertices are what
/// the saved scene must hold).
fn moved_shape(shape: &ObstacleShapeSpec, m: &RigidMotion) -> ObstacleShapeSpec {
    let point = |p: &[f64; 3]| -> [f64; 3] { m.apply(&Vec3::from(*p)).into() };
    let direction = |d: &[f64; 3]| -> [f64; 3] { (m.rotation * Vec3::from(*d)).into() };
    match shape {
        ObstacleShapeSpec::Plane { point: p, normal } => ObstacleShapeSpec::Plane {
            point: point(p),
            normal: direction(normal),
        },
        ObstacleShapeSpec::Sphere { center, radius } => ObstacleShapeSpec::Sphere {
            center: point(center),
            radius: *radius,
        },
        ObstacleShapeSpec::Cylinder {
            point: p,
            axis,
            radius,
        } => ObstacleShapeSpec::Cylinder {
            point: point(p),
            axis: direction(axis),
            radius: *radius,
        },
        ObstacleShapeSpec::Box {
            center,
            size,
            rotate,
        } => ObstacleShapeSpec::Box {
            center: point(center),
            size: *size,
            rotate: rotation_vector(&(m.rotation * Rotation3::new(Vec3::from(*rotate)))).into(),
        },
        ObstacleShapeSpec::Torus {
            center,
            axis,
            radius,
            tube_radius,
        } => ObstacleShapeSpec::Torus {
            center: point(center),
            axis: direction(axis),
            radius: *radius,
            tube_radius: *tube_radius,
        },
        ObstacleShapeSpec::Mesh {
            vertices,
            triangles,
            ..
        } => ObstacleShapeSpec::Mesh {
            file: None,
            vertices: vertices.iter().map(point).collect(),
            triangles: triangles.clone(),
        },
    }
}

/// Why a step of the obstacle cannot carry a model's cable along.
enum CarryError {
    /// The obstacle sweeps a held vertex (member, vertex).
    Held(usize, usize),
    /// The carried cable would be pressed into obstacle `obstacle` at (member, vertex).
    Pressed(usize, usize, usize),
}

/// Where the obstacle's step `step` leaves the contact sites of one model: the free-DOF
/// displacement `dx` that moves every site the obstacle sweeps or squeezes out of its way —
/// along the moved surface's normal when it is frictionless, rigidly with it when rough —
/// and spreads the carried sites' moves along each member to its anchors, linearly in arc
/// length (a taut cable lifted at one point becomes a V, not a kink of one edge: the first
/// guess's stretch is then spread as the equilibrium's is). `old` is obstacle `o` of
/// `problem.obstacles()` before the step. When the spread would press a site into an
/// obstacle, the swept sites alone are carried. `chain` places a site on the lines the moves
/// are spread along: (line, position along it) — a rod's (member, vertex), a strip's
/// (column, station).
fn carry_displacement<P: ContactSites>(
    problem: &crate::contact::ContactProblem<'_, P>,
    state: &P::State,
    o: usize,
    step: &RigidMotion,
    chain: impl Fn(&ContactSite) -> (usize, usize),
    dx: &mut [f64],
) -> Result<(), CarryError> {
    let sites = problem.sites();
    let old = &*problem.obstacles()[o];
    let frictionless = old.friction() == 0.0;
    let activation = problem.params().activation;
    let fixed = |i: usize| {
        sites[i]
            .dofs
            .iter()
            .any(|d| d.dof == crate::assembly::FIXED || d.coef == 0.0)
    };
    let position: Vec<Vec3> = sites
        .iter()
        .map(|site| problem.model().site_position(state, site))
        .collect();
    // The swept sites' moves.
    let mut carried: Vec<Option<Vec3>> = vec![None; sites.len()];
    for (i, site) in sites.iter().enumerate() {
        let p = position[i];
        // Seen from the obstacle, the site moves by the inverse motion: if that path comes
        // within the activation distance of the surface (at the site's contact radius), the
        // obstacle sweeps the site. The margin matters: a site left behind just outside the
        // surface would start the solve at a gap of round-off size, where the barrier's
        // force is beyond what double precision can balance.
        let relative = step.inverse_apply(&p) - p;
        let clearance = problem.site_radius(i) + activation;
        let swept = relative.norm() > 0.0 && old.time_of_impact(&p, &relative, clearance) < 1.0;
        // The site seen from the moved obstacle: its gap there and the outward normal.
        let seen_after = old.surface(&step.inverse_apply(&p));
        let gap_after = seen_after.distance - problem.site_radius(i);
        if !swept && gap_after >= activation {
            continue;
        }
        if fixed(i) {
            return Err(CarryError::Held(site.member, site.vertex));
        }
        carried[i] = Some(if frictionless && !(swept && gap_after >= activation) {
            // A frictionless surface pushes along its normal only: the site goes to the
            // activation distance of the moved surface (a cable sliding through a moved ring
            // is not dragged along with it).
            step.rotation * seen_after.normal * (activation - gap_after)
        } else {
            // A rough surface holds the site (its anchor moves with it), and a site the
            // obstacle passed through (a thin part, a large step) goes with it: carried
            // rigidly the site keeps its gap; one resting on the surface is lifted to the
            // activation distance, so that the solve starts where the barrier is mild
            // rather than at the steep end a squeezed contact sits on.
            let seen = old.surface(&p);
            let lift = (activation - (seen.distance - problem.site_radius(i))).max(0.0);
            step.apply(&(p + seen.normal * lift)) - p
        });
    }
    let spread = spread_along_lines(sites, chain, &position, &carried, fixed);
    // The moved obstacle is obstacle o after the step; every other obstacle stays.
    let gap_after = |i: usize, q: &Vec3| -> (usize, f64) {
        problem
            .obstacles()
            .iter()
            .enumerate()
            .map(|(k, ob)| {
                let at = if k == o { step.inverse_apply(q) } else { *q };
                (k, ob.surface(&at).distance - problem.site_radius(i))
            })
            .fold((o, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
    };
    let fits = |moves: &[Option<Vec3>]| -> Result<(), CarryError> {
        for (i, m) in moves.iter().enumerate() {
            if let Some(d) = m {
                let (k, g) = gap_after(i, &(position[i] + d));
                if g <= 0.0 {
                    return Err(CarryError::Pressed(k, sites[i].member, sites[i].vertex));
                }
            }
        }
        Ok(())
    };
    let moves = if fits(&spread).is_ok() {
        spread
    } else {
        fits(&carried)?;
        carried
    };
    dx.fill(0.0);
    for (site, m) in sites.iter().zip(&moves) {
        if let Some(d) = m {
            for (c, slot) in site.dofs.iter().enumerate() {
                dx[slot.dof] += d[c] / slot.coef;
            }
        }
    }
    Ok(())
}

/// The site moves along each line of sites (`chain`: a site's line and its position along
/// it — a rod's member, a strip's column of vertices), from its carried sites' moves
/// (`carried`), spread to the sites between them and the line's held sites (`fixed`: no
/// move) linearly in arc length along the current shape; past the last anchor at either end,
/// the nearest anchor's move. Lines without a carried site do not move.
fn spread_along_lines(
    sites: &[ContactSite],
    chain: impl Fn(&ContactSite) -> (usize, usize),
    position: &[Vec3],
    carried: &[Option<Vec3>],
    fixed: impl Fn(usize) -> bool,
) -> Vec<Option<Vec3>> {
    let mut out = vec![None; sites.len()];
    let mut order: Vec<usize> = (0..sites.len()).collect();
    order.sort_by_key(|&i| chain(&sites[i]));
    for chain in order.chunk_by(|&a, &b| chain(&sites[a]).0 == chain(&sites[b]).0) {
        if !chain.iter().any(|&i| carried[i].is_some()) {
            continue;
        }
        let mut arc = Vec::with_capacity(chain.len());
        let mut s = 0.0;
        for (k, &i) in chain.iter().enumerate() {
            if k > 0 {
                s += (position[i] - position[chain[k - 1]]).norm();
            }
            arc.push(s);
        }
        let anchor =
            |i: usize| -> Option<Vec3> { carried[i].or_else(|| fixed(i).then(Vec3::zeros)) };
        let anchors: Vec<usize> = (0..chain.len())
            .filter(|&k| anchor(chain[k]).is_some())
            .collect();
        for (k, &i) in chain.iter().enumerate() {
            if fixed(i) {
                continue;
            }
            let next = anchors.partition_point(|&a| a < k);
            let d = match (next.checked_sub(1).map(|p| anchors[p]), anchors.get(next)) {
                (_, Some(&b)) if b == k => anchor(i),
                (Some(a), Some(&b)) => {
                    let w = (arc[k] - arc[a]) / (arc[b] - arc[a]);
                    Some(
                        anchor(chain[a]).unwrap_or_default() * (1.0 - w)
                            + anchor(chain[b]).unwrap_or_default() * w,
                    )
                }
                (Some(a), None) => anchor(chain[a]),
                (None, Some(&b)) => anchor(chain[b]),
                (None, None) => None,
            };
            out[i] = d;
        }
    }
    out
}

/// Moves the anchors of the sticking and sliding contacts with obstacle `o` (of `n`) by
/// `step`: friction holds a site to a point of the obstacle's surface, which moves with it.
fn carry_friction(friction: &mut [Friction], o: usize, n: usize, step: &RigidMotion) {
    for (k, f) in friction.iter_mut().enumerate() {
        if k % n != o {
            continue;
        }
        match f {
            Friction::Free => {}
            Friction::Stick { anchor, normal } => {
                *anchor = step.apply(anchor);
                *normal = step.rotation * *normal;
            }
            Friction::Slide { origin, normal, .. } => {
                *origin = step.apply(origin);
                *normal = step.rotation * *normal;
            }
        }
    }
}

/// Motion steps of a saved stage that moves an obstacle by the rotation vector `rotation`
/// (rad) and the translation `translation` (m), in a scene whose shortest structure is
/// `shortest` long (each step is divided further where it sweeps a cable: see
/// [`Session::move_obstacle_to`]).
pub(super) fn stage_steps(rotation: &Vec3, translation: &Vec3, shortest: f64) -> usize {
    (rotation.norm() / MAX_STEP_ROTATION)
        .max(translation.norm() / (MAX_STEP_TRANSLATION * shortest))
        .ceil()
        .max(1.0) as usize
}

impl Session {
    /// The length (m) of the shortest member of any structure or strip (∞ without one): what
    /// sets the largest translation of an obstacle per step.
    pub(super) fn shortest_member(&self) -> f64 {
        self.scene
            .structures
            .iter()
            .flat_map(|s| s.members().iter().map(|m| m.length()))
            .chain(self.scene.shells.iter().map(|c| c.length()))
            .fold(f64::INFINITY, f64::min)
    }

    /// The point (m) obstacle `obstacle` turns about in [`Self::move_obstacle_by`]: its
    /// reference point in the scene file (a plane's or cylinder's `point`, a sphere's, box's
    /// or torus's `center`, a mesh's bounding-box centre) as moved so far; `None` if there is
    /// no such obstacle.
    pub fn obstacle_reference(&self, obstacle: usize) -> Option<Vec3> {
        let spec = self.spec.obstacles.get(obstacle)?;
        Some(reference_point(&spec.shape) + self.obstacle_moves[obstacle].1)
    }

    /// The shape of obstacle `obstacle` now (moved by the edits), or `None` if there is no
    /// such obstacle.
    pub fn obstacle_shape(&self, obstacle: usize) -> Option<ObstacleShapeSpec> {
        let spec = self.spec.obstacles.get(obstacle)?;
        let (rotation, translation) = self.obstacle_moves[obstacle];
        if rotation == Rotation3::identity() && translation == Vec3::zeros() {
            // Not moved: the file's numbers to the bit.
            return Some(spec.shape.clone());
        }
        Some(moved_shape(
            &spec.shape,
            &RigidMotion {
                rotation,
                about: reference_point(&spec.shape),
                translation,
            },
        ))
    }

    /// Moves obstacle `obstacle` rigidly — turned by the rotation vector `rotation` (rad)
    /// about its reference point ([`Self::obstacle_reference`]), then shifted by
    /// `translation` (m) — and re-solves every structure from the current equilibrium (see
    /// [`Self::move_obstacle_to`]).
    pub fn move_obstacle_by(
        &mut self,
        obstacle: usize,
        rotation: Vec3,
        translation: Vec3,
    ) -> Result<EditReport, SceneError> {
        let Some(&(r, t)) = self.obstacle_moves.get(obstacle) else {
            return Err(no_obstacle(obstacle, self.spec.obstacles.len()));
        };
        if rotation
            .iter()
            .chain(translation.iter())
            .any(|c| !c.is_finite())
        {
            return Err(SceneError::new(
                format!("obstacles[{obstacle}]"),
                "the move must be finite",
            ));
        }
        self.move_obstacle_to(obstacle, Rotation3::new(rotation) * r, t + translation)
    }

    /// Moves obstacle `obstacle` to the rigid motion (`rotation` about the reference point
    /// of its shape in the scene file, then `translation`, m) from that shape, and re-solves
    /// every structure from the current equilibrium: in steps of at most 0.2 rad, 5 % of the
    /// shortest structure and a quarter of the shortest element, each step moving the
    /// centerline vertices the obstacle sweeps or squeezes out of its way (see the module
    /// docs). The saved scene keeps the file's obstacle and adds a motion stage to here. If
    /// a step does not converge, the obstacle and every equilibrium go back and the report
    /// says so.
    ///
    /// Errors name `obstacles[i]`: no such obstacle, a move that is not finite or too large
    /// for one edit. An obstacle that would push into a support or a strip's clamped edge, or
    /// press a cable or strip into another obstacle, is a report that did not converge,
    /// saying so. Shell strips in contact are carried and re-solved with the rods (their
    /// reports add to the edit's iterations and residual).
    pub fn move_obstacle_to(
        &mut self,
        obstacle: usize,
        rotation: Rotation3<f64>,
        translation: Vec3,
    ) -> Result<EditReport, SceneError> {
        let path = || format!("obstacles[{obstacle}]");
        let (Some(spec), Some(&(r0, t0))) = (
            self.spec.obstacles.get(obstacle).cloned(),
            self.obstacle_moves.get(obstacle),
        ) else {
            return Err(no_obstacle(obstacle, self.spec.obstacles.len()));
        };
        if rotation
            .matrix()
            .iter()
            .chain(translation.iter())
            .any(|c| !c.is_finite())
        {
            return Err(SceneError::new(path(), "the move must be finite"));
        }
        let turn = rotation_vector(&(rotation * r0.inverse()));
        let shift = translation - t0;
        let shortest = self.shortest_member();
        // The farthest a point of the obstacle near the rods moves: the translation plus the
        // rotation's sweep at the farthest rod vertex from the reference point.
        let about = reference_point(&spec.shape);
        let centre = about + t0;
        let (mut edge, mut reach) = (f64::INFINITY, 0.0_f64);
        for (s, run) in self.scene.structures.iter().zip(&self.runs) {
            for (rest, now) in s.rest_state().members.iter().zip(&run.state.members) {
                for w in rest.positions().windows(2) {
                    edge = edge.min((w[1] - w[0]).norm());
                }
                for p in now.positions() {
                    reach = reach.max((p - centre).norm());
                }
            }
        }
        for (c, run) in self.scene.shells.iter().zip(&self.shells) {
            if let (StripModel::Midedge(shell), Some(now)) = (&c.model, run.midedge_state()) {
                // The mesh's shortest rest edge (a graded strip's are shortest at its start).
                let mesh = shell.mesh();
                for &[a, b] in &mesh.edges {
                    edge = edge.min((mesh.rest_positions[a] - mesh.rest_positions[b]).norm());
                }
                for x in &now.positions {
                    reach = reach.max((x - centre).norm());
                }
            }
        }
        let sweep = shift.norm() + turn.norm() * reach;
        let steps = (turn.norm() / MAX_STEP_ROTATION)
            .max(shift.norm() / (MAX_STEP_TRANSLATION * shortest))
            .max(sweep / (MAX_STEP_PER_EDGE * edge))
            .ceil()
            .max(1.0);
        if !(steps <= MAX_OBSTACLE_STEPS) {
            return Err(SceneError::new(
                path(),
                format!(
                    "the move ({:.3e} m, {:.3e} rad) is too large for one edit (at most {:.3e} \
                     m and {} rad, and {:.3e} m of sweep: a quarter of the shortest element \
                     per step)",
                    shift.norm(),
                    turn.norm(),
                    MAX_OBSTACLE_STEPS * MAX_STEP_TRANSLATION * shortest,
                    MAX_OBSTACLE_STEPS * MAX_STEP_ROTATION,
                    MAX_OBSTACLE_STEPS * MAX_STEP_PER_EDGE * edge,
                ),
            ));
        }
        let Some(before) = self
            .scene
            .contact
            .as_ref()
            .map(|c| c.obstacles[obstacle].clone())
        else {
            return Err(SceneError::new(path(), "the scene has no compiled contact"));
        };
        // The motion from the file's shape at fraction s of this edit.
        let at = |s: f64| RigidMotion {
            rotation: Rotation3::new(turn * s) * r0,
            about,
            translation: t0 + shift * s,
        };
        let steps = steps as usize;
        let mut ks = std::mem::take(&mut self.affected);
        ks.clear();
        ks.extend(0..self.runs.len());
        for run in self.runs.iter_mut() {
            run.save();
        }
        // The strips keep no backup of their own across several solves: the whole runs are
        // kept (an obstacle move is no interactive drag; the copies are not on a hot path).
        let strips_before = self.shells.clone();
        let mut strip_snapshot = Vec::new();
        let mut reason = None;
        let n_obstacles = self.spec.obstacles.len();
        // Fractions of the edit done and tried next; a step that does not converge is
        // undone and halved (a contact passing from one vertex to the next can take a
        // Newton solve hundreds of iterations from a full step, and a tenth from half).
        let (mut done, full) = (0.0_f64, 1.0 / steps as f64);
        let mut size = full;
        let (mut halvings, mut taken) = (0, 0);
        let mut snapshot: Vec<(StructureState, Vec<Friction>)> = Vec::new();
        let mut current = before.clone();
        while done < 1.0 {
            let next = if done + size >= 1.0 - 1e-12 {
                1.0
            } else {
                done + size
            };
            let (from, to) = (at(done), at(next));
            let moved = match obstacle_for(&path(), &spec, &moved_shape(&spec.shape, &to)) {
                Ok(o) => o,
                Err(e) => {
                    reason = Some(e.to_string());
                    break;
                }
            };
            snapshot.clear();
            snapshot.extend(
                self.runs
                    .iter()
                    .map(|r| (r.state.clone(), r.friction.clone())),
            );
            strip_snapshot.clone_from(&self.shells);
            let this = to.after_undoing(&from);
            let mut failure = None;
            for &k in &ks {
                // A support in the way or a cable pressed into another obstacle does not go
                // away with smaller steps: no retry.
                if let Err(e) = self.carry(k, obstacle, n_obstacles, &this) {
                    failure = Some((e, false));
                    break;
                }
            }
            if failure.is_none() {
                for (c, run) in self.scene.shells.iter().zip(self.shells.iter_mut()) {
                    let (StripModel::Midedge(shell), Some(run)) = (&c.model, run.contact_run_mut())
                    else {
                        continue;
                    };
                    if let Err(e) = carry_strip(run, shell, &c.name, obstacle, n_obstacles, &this) {
                        failure = Some((e, false));
                        break;
                    }
                }
            }
            if failure.is_none() {
                if let Some(c) = self.scene.contact.as_mut() {
                    c.obstacles[obstacle] = moved.clone();
                }
                for (c, run) in self.scene.shells.iter().zip(self.shells.iter_mut()) {
                    if let (StripModel::Midedge(shell), Some(run)) =
                        (&c.model, run.contact_run_mut())
                    {
                        run.set_obstacle(obstacle, moved.clone());
                        if failure.is_some() {
                            continue;
                        }
                        let report = run.resolve(shell);
                        if !report.converged() {
                            failure = Some((
                                format!(
                                    "strip {:?}, the obstacle at {:.3} of its move: {:?}",
                                    c.name, next, report.status
                                ),
                                true,
                            ));
                        }
                    }
                }
                for &k in &ks {
                    if failure.is_some() {
                        break;
                    }
                    let run = &mut self.runs[k];
                    // A contact pressed by the moving obstacle settles on its barrier by
                    // many short Newton steps: the step gets the long budget of a snap.
                    let user = run.solver.params;
                    run.solver.params.max_iterations =
                        user.snap_iterations.max(user.max_iterations);
                    let report = solve_structure(&self.scene, k, run, 1.0, 1.0);
                    run.solver.params = user;
                    let failed = !report.converged();
                    if failed {
                        failure = Some((
                            format!(
                                "the obstacle at {:.3} of its move: {:?}",
                                next, report.status
                            ),
                            true,
                        ));
                    }
                    run.report = report;
                    if failed {
                        break;
                    }
                }
            }
            match failure {
                None => {
                    done = next;
                    current = moved;
                    taken += 1;
                }
                Some((why, retry)) => {
                    // Back to the start of the step, the obstacle with it.
                    for (run, (state, friction)) in self.runs.iter_mut().zip(snapshot.drain(..)) {
                        run.state = state;
                        run.friction = friction;
                    }
                    if let Some(c) = self.scene.contact.as_mut() {
                        c.obstacles[obstacle] = current.clone();
                    }
                    // The strips' runs hold their copies of the obstacles: back with them.
                    self.shells.clone_from(&strip_snapshot);
                    halvings += 1;
                    if !retry || halvings > MAX_OBSTACLE_HALVINGS {
                        reason = Some(format!("{why} (after {taken} steps)"));
                        break;
                    }
                    size *= 0.5;
                }
            }
        }
        if reason.is_some() {
            if let Some(c) = self.scene.contact.as_mut() {
                c.obstacles[obstacle] = before;
            }
            let mut summary = self.summary(&ks, reason);
            self.add_strips(&mut summary);
            for run in self.runs.iter_mut() {
                run.restore();
            }
            self.shells = strips_before;
            self.affected = ks;
            return Ok(summary);
        }
        self.obstacle_moves[obstacle] = (rotation, translation);
        let mut report = self.stabilized(ks);
        self.add_strips(&mut report);
        Ok(report)
    }

    /// Adds the last solves of the strips in contact to `report` (an obstacle move re-solves
    /// them with the rods).
    fn add_strips(&self, report: &mut EditReport) {
        for run in self.shells.iter() {
            if let Some(r) = run.contact_report() {
                report.iterations += r.iterations;
                report.load_steps += r.load_steps;
                report.relative_residual = report.relative_residual.max(r.relative_residual);
            }
        }
    }

    /// Carries structure `k`'s sites swept by obstacle `o`'s step `step` (and its contacts'
    /// friction anchors) along; an error names a held vertex in the way.
    fn carry(
        &mut self,
        k: usize,
        o: usize,
        n_obstacles: usize,
        step: &RigidMotion,
    ) -> Result<(), String> {
        let run = &mut self.runs[k];
        let problem = match contact_problem(&self.scene, k, &run.state, &run.friction) {
            None => return Ok(()),
            Some(Err(e)) => return Err(e),
            Some(Ok(p)) => p,
        };
        let structure = &self.scene.structures[k];
        let mut dx = vec![0.0; structure.n_free()];
        let along_members = |s: &ContactSite| (s.member, s.vertex);
        match carry_displacement(&problem, &run.state, o, step, along_members, &mut dx) {
            Ok(()) => {}
            Err(CarryError::Held(member, vertex)) => {
                let (rod, v) = rod_vertex(&self.scene, k, member, vertex);
                return Err(format!(
                    "obstacles[{o}] would push into the held vertex {v} of rod {rod:?} (a \
                     support): move the support first"
                ));
            }
            Err(CarryError::Pressed(other, member, vertex)) => {
                let (rod, v) = rod_vertex(&self.scene, k, member, vertex);
                return Err(format!(
                    "obstacles[{o}] would press vertex {v} of rod {rod:?} into obstacles[{other}]"
                ));
            }
        }
        if dx.iter().any(|&d| d != 0.0) {
            // The chart moves each vertex by exactly its step (the solver's retraction would
            // turn edges about their neighbours instead); frames follow the new edges.
            let mut moved = run.state.clone();
            structure.chart(&run.state, &dx, &mut moved);
            run.state = moved;
        }
        carry_friction(&mut run.friction, o, n_obstacles, step);
        Ok(())
    }
}

/// Carries the vertices of strip `name` (mid-edge `shell`, solved by `run`) that obstacle
/// `o`'s step `step` sweeps or squeezes along, spread along each column of vertices to its
/// clamped ends, and the anchors of its contacts' friction; an error names a clamped vertex
/// in the way or a vertex pressed into another obstacle.
fn carry_strip(
    run: &mut ContactStripRun,
    shell: &Shell,
    name: &str,
    o: usize,
    n_obstacles: usize,
    step: &RigidMotion,
) -> Result<(), String> {
    let columns = shell.mesh().n_width + 1;
    let place = |v: usize| (v / columns, v % columns);
    let problem = run.problem(shell)?;
    let mut dx = vec![0.0; problem.n_free()];
    let (state, _) = run.state_and_friction();
    let along_columns = |s: &ContactSite| (s.vertex % columns, s.vertex / columns);
    match carry_displacement(&problem, state, o, step, along_columns, &mut dx) {
        Ok(()) => {}
        Err(CarryError::Held(_, v)) => {
            let (station, column) = place(v);
            return Err(format!(
                "obstacles[{o}] would push into the clamped edge of strip {name:?} (station \
                 {station}, column {column}): move the clamp first"
            ));
        }
        Err(CarryError::Pressed(other, _, v)) => {
            let (station, column) = place(v);
            return Err(format!(
                "obstacles[{o}] would press strip {name:?} (station {station}, column \
                 {column}) into obstacles[{other}]"
            ));
        }
    }
    let (state, friction) = run.state_and_friction();
    if dx.iter().any(|&d| d != 0.0) {
        // Positions move by exactly their steps; the moved state was produced by no Newton
        // step, so it has no membrane remainder.
        let mut moved = state.clone();
        problem.displace(state, &dx, 1.0, &mut moved);
        moved.membrane_remainder.clear();
        *state = moved;
    }
    carry_friction(friction, o, n_obstacles, step);
    Ok(())
}

/// The error for an obstacle index past the `count` of the scene.
fn no_obstacle(obstacle: usize, count: usize) -> SceneError {
    SceneError::new(
        format!("obstacles[{obstacle}]"),
        format!("no such obstacle (the scene has {count})"),
    )
}

/// The obstacle of `spec` with its shape replaced by `shape`.
fn obstacle_for(
    path: &str,
    spec: &crate::scene::spec::ObstacleSpec,
    shape: &ObstacleShapeSpec,
) -> Result<Arc<dyn Obstacle>, SceneError> {
    let mut s = spec.clone();
    s.shape = shape.clone();
    obstacle(path, &s)
}
