//! What the page draws after every update ([`ViewState`]): per rod its centerline, material
//! directors and colour fields (twist rate, curvature, bending stress), its bend radius
//! against the allowed one, its supports with their poses and reactions; per structure its
//! solve and stability; the shell strips as surfaces with their clamps as handles; every
//! obstacle's active contacts and the scene's smallest gap. The obstacles' shapes do not change
//! in a session: [`SceneGeometry`] is sent with the replies to `state` and `obstacle`.

use serde::Serialize;
use serde_json::Value;
use slender_core::bspline_shell::StripEnd;
use slender_core::geometry::Vec3;
use slender_core::scene::spec::{
    ObstacleShapeSpec, RodSpec, SectionSpec, SupportKind, UnstablePolicy,
};
use slender_core::scene::{CompiledRod, ObstacleResult, SceneStep, Session};
use slender_core::solver::SolveStatus;

/// Everything the page shows of the current equilibria.
#[derive(Clone, Debug, Serialize)]
pub struct ViewState {
    /// Gravitational acceleration (m/s²).
    pub gravity: [f64; 3],
    /// What the session does with unstable equilibria.
    pub unstable_policy: UnstablePolicy,
    /// True if every rod and shell converged.
    pub converged: bool,
    /// True if every equilibrium is stable.
    pub stable: bool,
    /// Every rod, in the scene's order.
    pub rods: Vec<RodView>,
    /// Every structure (rod parts solved together).
    pub structures: Vec<StructureView>,
    /// Every shell strip (its clamps can be dragged).
    pub shells: Vec<ShellView>,
    /// Every obstacle, in the scene's order (the order of [`SceneGeometry::obstacles`]): its
    /// friction coefficient, the resultant force it applies to the rods (N) and its active
    /// contacts (position, gap, normal, normal and friction force, sticking) as `slender solve`
    /// reports them. Empty without obstacles.
    pub obstacles: Vec<ObstacleResult>,
    /// Smallest gap (m) between a rod's surface and an obstacle over the scene; `None` without
    /// obstacles.
    pub min_gap: Option<f64>,
    /// With self-contact (`contact.self_contact`): every active contact between two segments
    /// of the centerlines, as the core's results list them (`segment_contacts`: kind, the two
    /// sides' rods, edges or vertex, closest points and forces, gap); absent without
    /// self-contact, or from a core whose results do not list them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segment_contacts: Option<Value>,
    /// With self-contact: the smallest gap (m) between two segments that may touch, as the
    /// core's results give it (`min_segment_gap`); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_segment_gap: Option<Value>,
    /// Rod edges whose centerline, and strip faces whose mid-surface, runs through an obstacle
    /// between their vertices (rod or strip, edge or face, obstacle, deepest point, depth), as
    /// the core's results list them: the page warns that the mesh is coarser than the
    /// obstacle there. Empty otherwise.
    pub edges_through_obstacles: Vec<slender_core::scene::EdgeThroughObstacle>,
}

/// One rod as drawn.
#[derive(Clone, Debug, Serialize)]
pub struct RodView {
    /// Rod name.
    pub name: String,
    /// Tube radius (m): the section's radius (equal-area radius for a rectangle).
    pub display_radius: f64,
    /// True for a closed loop.
    pub closed: bool,
    /// Rod formulation as in scene files (`der`, `cosserat`, `cosserat_tan`, `se3`).
    pub model: &'static str,
    /// Rest arc length (m) of every vertex from vertex 0: where a clip added at a point of the
    /// cable goes (`at`).
    pub arclengths: Vec<f64>,
    /// Vertex positions (m).
    pub positions: Vec<[f64; 3]>,
    /// First material director m₁ of every edge (orients the tube, shows the twist).
    pub directors: Vec<[f64; 3]>,
    /// Twist rate at every vertex (rad/m).
    pub twist: Vec<f64>,
    /// Curvature magnitude |κ| at every vertex (1/m).
    pub curvature: Vec<f64>,
    /// Axial strain of every edge.
    pub edge_strain: Vec<f64>,
    /// Axial force of every edge (N; tension positive): EA·ε, EA from the section and the
    /// material (or the section's own `ea`).
    pub axial_force: Vec<f64>,
    /// Largest bending stress in the section at every vertex (Pa), from the change of
    /// curvature from rest: E·|Δκ|·d/2 (circle), E·(|Δκ₁|·w/2 + |Δκ₂|·h/2) (rectangle);
    /// `None` for a section given by its stiffnesses (no material, no fibre distance).
    pub bending_stress: Option<Vec<f64>>,
    /// Smallest bend radius along the rod (m); `None` if straight everywhere.
    pub min_bend_radius: Option<f64>,
    /// The scene's allowed bend radius for this rod (m), if it gives one.
    pub allowed_bend_radius: Option<f64>,
    /// Vertices bent tighter than the allowed radius.
    pub tight_vertices: Vec<usize>,
    /// True if every part of the rod converged.
    pub converged: bool,
    /// True if every part's equilibrium is stable.
    pub stable: bool,
    /// The structures the rod belongs to.
    pub structures: Vec<usize>,
    /// Supports, in the rod's order (the index is the one edits name).
    pub supports: Vec<SupportView>,
    /// Point forces, in the order of the scene's `forces` (the index the `force` edit names).
    pub forces: Vec<ForceView>,
    /// Point moments, in the order of the scene's `moments`.
    pub moments: Vec<MomentView>,
    /// The line loads' load per length (N/m) at each vertex, summed over the scene's
    /// `line_loads` (empty without line loads).
    pub line_load: Vec<[f64; 3]>,
    /// Radius (m) its centerline keeps from obstacles (its structure's contact radius: a
    /// contact's surface point is its vertex minus the normal times this radius plus the
    /// gap); `None` in a scene without contact.
    pub contact_radius: Option<f64>,
}

/// One support as drawn: a handle where it is, its reaction as an arrow.
#[derive(Clone, Debug, Serialize)]
pub struct SupportView {
    /// Clamp, pin, clip, slider or twist hold.
    pub kind: SupportKind,
    /// Held vertex.
    pub vertex: usize,
    /// Rest arc length of the vertex (m).
    pub at: f64,
    /// Where it is (m).
    pub position: [f64; 3],
    /// Its orientation relative to rest, as a rotation vector (axis × angle, rad).
    pub rotation: [f64; 3],
    /// Force the support applies to the rod (N).
    pub force: [f64; 3],
    /// Moment the support applies to the rod about its vertex (N m).
    pub moment: [f64; 3],
    /// Slider axis (unit), if a slider.
    pub axis: Option<[f64; 3]>,
}

/// A point force on a rod: an arrow at its vertex; a dead force can be edited (`force`).
#[derive(Clone, Debug, Serialize)]
pub struct ForceView {
    /// Loaded vertex.
    pub vertex: usize,
    /// Rest arc length of the vertex (m).
    pub at: f64,
    /// Where the vertex is now (m).
    pub position: [f64; 3],
    /// The force as the scene gives it (N): fixed in space, or, for a follower load, in the
    /// rod's rest frame at the vertex (what the page edits).
    pub force: [f64; 3],
    /// The force in space now (N), as the page draws it: `force` for a dead load, `force`
    /// turned with the rod's material frame at the vertex for a follower load.
    pub now: [f64; 3],
    /// A follower load (turns with the rod).
    pub follower: bool,
}

/// A point moment on a rod: a double-headed arrow at its vertex (the right-hand rule about it).
#[derive(Clone, Debug, Serialize)]
pub struct MomentView {
    /// Loaded vertex.
    pub vertex: usize,
    /// Rest arc length of the vertex (m).
    pub at: f64,
    /// Where the vertex is now (m).
    pub position: [f64; 3],
    /// The moment as the scene gives it (N m): fixed in space, or, for a follower load, in the
    /// rod's rest frame at the vertex.
    pub moment: [f64; 3],
    /// The moment in space now (N m), as the page draws it: `moment` for a dead load, turned
    /// with the rod's material frame at the vertex for a follower one.
    pub now: [f64; 3],
    /// A follower load (turns with the rod).
    pub follower: bool,
}

/// One structure's last solve.
#[derive(Clone, Debug, Serialize)]
pub struct StructureView {
    /// Rod names.
    pub rods: Vec<String>,
    /// Converged or not.
    pub converged: bool,
    /// Why not, if not.
    pub reason: Option<String>,
    /// Newton iterations of the last solve.
    pub iterations: usize,
    /// Load steps of the last solve.
    pub load_steps: usize,
    /// Largest residual force (N).
    pub residual: f64,
    /// Residual over the largest external nodal force.
    pub relative_residual: f64,
    /// True if stable.
    pub stable: bool,
    /// Negative Hessian eigenvalues.
    pub unstable_modes: usize,
    /// Null modes (symmetries).
    pub null_modes: usize,
    /// True if an unstable equilibrium was followed to this one.
    pub followed_unstable_mode: bool,
    /// Smallest eigenvalue of H v = λ M v (1/s²), when computed.
    pub lambda_min: Option<f64>,
}

/// One shell strip as drawn.
#[derive(Clone, Debug, Serialize)]
pub struct ShellView {
    /// Strip name.
    pub name: String,
    /// Vertex positions (m): the grid's vertex (station i, column j) is
    /// i·(width_elements + 1) + j.
    pub positions: Vec<[f64; 3]>,
    /// Elements across the width (the grid has width_elements + 1 columns).
    pub width_elements: usize,
    /// Triangles.
    pub faces: Vec<[usize; 3]>,
    /// True if its solve converged.
    pub converged: bool,
    /// Its clamps, as handles (in the order of the scene's `clamps`).
    pub clamps: Vec<ShellClampView>,
    /// Its dead point forces, in the order of the scene's `forces` (the index the `force`
    /// edit names with `shell`).
    pub forces: Vec<ShellForceView>,
    /// Distance (m) its mid-surface keeps from obstacles, h/2 (a contact's surface point is
    /// its vertex minus the normal times this plus the gap); `None` in a scene without
    /// obstacles.
    pub contact_radius: Option<f64>,
}

/// A point force on a strip: an arrow at its grid vertex; editable (`force` with `shell`).
#[derive(Clone, Debug, Serialize)]
pub struct ShellForceView {
    /// Station along the length (0 … elements) and column across (0 … width_elements).
    pub station: usize,
    /// See `station`.
    pub column: usize,
    /// The loaded vertex of `positions`: station·(width_elements + 1) + column.
    pub vertex: usize,
    /// Where the vertex is now (m).
    pub position: [f64; 3],
    /// The force (N), fixed in space.
    pub force: [f64; 3],
}

/// A clamp of a strip as a handle: the centre of its clamped edge and its orientation.
#[derive(Clone, Debug, Serialize)]
pub struct ShellClampView {
    /// Index in the strip's `clamps` (what a `move` with `shell` addresses as `support`).
    pub index: usize,
    /// `"start"` (x = 0 at rest) or `"end"` (x = L).
    pub edge: &'static str,
    /// Centre of the clamped edge now (m).
    pub position: [f64; 3],
    /// Orientation relative to rest, as a rotation vector (rad).
    pub rotation: [f64; 3],
    /// Length of the clamped edge: the strip's width (m).
    pub edge_length: f64,
    /// The edge's direction now (unit): the handle is drawn along it.
    pub edge_direction: [f64; 3],
    /// The clamp's normal now (unit).
    pub normal: [f64; 3],
}

fn arr(v: Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The view of the session's current equilibria; `step` is `session.results(..)`.
pub fn view_state(session: &Session, step: &SceneStep) -> ViewState {
    let scene = session.compiled();
    let rods = scene
        .rods
        .iter()
        .zip(&step.rods)
        .enumerate()
        .map(|(r, (rod, res))| {
            let supports = res
                .supports
                .iter()
                .enumerate()
                .map(|(s, sup)| {
                    let pose = session.pose(r, s);
                    SupportView {
                        kind: sup.kind,
                        vertex: sup.vertex,
                        at: rod.node_arclengths[sup.vertex],
                        position: sup.position,
                        rotation: pose.map_or([0.0; 3], |p| {
                            arr(nalgebra::UnitQuaternion::from_rotation_matrix(&p.rotation)
                                .scaled_axis())
                        }),
                        force: sup.force,
                        moment: sup.moment,
                        axis: rod.supports[s].axis.map(arr),
                    }
                })
                .collect();
            let forces = session.spec().rods[r]
                .forces
                .iter()
                .zip(&rod.force_vertices)
                .enumerate()
                .map(|(k, (f, &v))| ForceView {
                    vertex: v,
                    at: rod.node_arclengths[v],
                    position: res.positions[v],
                    force: f.force,
                    now: session.force_now(r, k).unwrap_or(f.force),
                    follower: f.follower,
                })
                .collect();
            let moments = session.spec().rods[r]
                .moments
                .iter()
                .zip(&rod.moment_vertices)
                .enumerate()
                .map(|(k, (m, &v))| MomentView {
                    vertex: v,
                    at: rod.node_arclengths[v],
                    position: res.positions[v],
                    moment: m.moment,
                    now: session.moment_now(r, k).unwrap_or(m.moment),
                    follower: m.follower,
                })
                .collect();
            let mut structures: Vec<usize> = rod.parts.iter().map(|p| p.structure).collect();
            structures.dedup();
            // The rod's own radius: each rod keeps it, in whatever structure.
            let contact_radius = scene
                .contact
                .as_ref()
                .and_then(|c| c.rod_radii.get(r).copied());
            RodView {
                name: res.name.clone(),
                display_radius: rod.display_radius,
                closed: rod.closed,
                model: session.spec().rods[r].model.name(),
                arclengths: rod.node_arclengths.clone(),
                positions: res.positions.clone(),
                directors: res.frames.iter().map(|f| f[0]).collect(),
                twist: res.twist.clone(),
                curvature: res
                    .curvature
                    .iter()
                    .map(|k| (k[0] * k[0] + k[1] * k[1]).sqrt())
                    .collect(),
                edge_strain: res.edge_strain.clone(),
                axial_force: {
                    let ea = axial_stiffness(&session.spec().rods[r]);
                    res.edge_strain.iter().map(|e| ea * e).collect()
                },
                bending_stress: bending_stress(session, r),
                min_bend_radius: res
                    .min_bend_radius
                    .is_finite()
                    .then_some(res.min_bend_radius),
                allowed_bend_radius: rod.min_bend_radius,
                tight_vertices: res.tight_vertices.clone(),
                converged: res.converged,
                stable: res.stable,
                structures,
                supports,
                forces,
                moments,
                line_load: rod.line_load_per_length.clone(),
                contact_radius,
            }
        })
        .collect();
    let structures = step
        .structures
        .iter()
        .map(|s| StructureView {
            rods: s.rods.clone(),
            converged: s.report.converged(),
            reason: match &s.report.status {
                SolveStatus::Converged => None,
                SolveStatus::NotConverged { reason } => Some(reason.clone()),
            },
            iterations: s.report.iterations,
            load_steps: s.report.load_steps,
            residual: s.report.residual,
            relative_residual: s.report.relative_residual,
            stable: s.stability.stable,
            unstable_modes: s.stability.unstable_modes,
            null_modes: s.stability.null_modes,
            followed_unstable_mode: s.stability.followed_unstable_mode,
            lambda_min: s.report.lambda_min,
        })
        .collect();
    let shells = step
        .shells
        .iter()
        .enumerate()
        .map(|(i, s)| ShellView {
            name: s.name.clone(),
            positions: s.positions.clone(),
            width_elements: scene.shells[i].width_elements(),
            faces: s.faces.clone(),
            converged: s.converged,
            clamps: scene.shells[i]
                .clamps
                .iter()
                .enumerate()
                .filter_map(|(k, c)| {
                    let pose = session.shell_pose(i, k)?;
                    let rv = nalgebra::UnitQuaternion::from_rotation_matrix(&pose.rotation)
                        .scaled_axis();
                    Some(ShellClampView {
                        index: k,
                        edge: match c.end {
                            StripEnd::Start => "start",
                            StripEnd::End => "end",
                        },
                        position: arr(pose.position),
                        edge_length: scene.shells[i].width(),
                        rotation: arr(rv),
                        edge_direction: arr(pose.rotation * Vec3::z()),
                        normal: arr(pose.rotation * Vec3::y()),
                    })
                })
                .collect(),
            forces: {
                let columns = scene.shells[i].width_elements() + 1;
                session.spec().shells[i]
                    .forces
                    .iter()
                    .map(|f| {
                        let vertex = f.station * columns + f.column;
                        ShellForceView {
                            station: f.station,
                            column: f.column,
                            vertex,
                            position: s.positions[vertex],
                            force: f.force,
                        }
                    })
                    .collect()
            },
            contact_radius: scene
                .contact
                .as_ref()
                .and_then(|c| c.shell_params.get(i))
                .map(|p| p.radius),
        })
        .collect();
    let (segment_contacts, min_segment_gap) = segment_contacts(session, step);
    ViewState {
        gravity: session.spec().gravity,
        unstable_policy: session.spec().unstable,
        converged: step.converged,
        stable: step.stable,
        rods,
        structures,
        shells,
        obstacles: step.obstacles.clone(),
        min_gap: step.min_gap,
        segment_contacts,
        min_segment_gap,
        edges_through_obstacles: step.edges_through_obstacles.clone(),
    }
}

/// The results' `segment_contacts` and `min_segment_gap` (self-contact), read by name from
/// the serialized step: the view forwards them where the core reports them and needs no
/// change of its own when they appear or change. Only scenes with self-contact pay for the
/// serialization.
fn segment_contacts(session: &Session, step: &SceneStep) -> (Option<Value>, Option<Value>) {
    let self_contact = session
        .compiled()
        .contact
        .as_ref()
        .is_some_and(|c| c.params.iter().any(|p| p.self_contact));
    if !self_contact {
        return (None, None);
    }
    match serde_json::to_value(step) {
        Ok(Value::Object(mut m)) => (
            m.remove("segment_contacts").filter(|v| !v.is_null()),
            m.remove("min_segment_gap").filter(|v| !v.is_null()),
        ),
        _ => (None, None),
    }
}

/// The scene's obstacles as the page draws them (sent once: they do not move), with what the
/// page needs to read the contacts.
#[derive(Clone, Debug, Serialize)]
pub struct SceneGeometry {
    /// Every obstacle, in the scene's order (the order of [`ViewState::obstacles`]).
    pub obstacles: Vec<ObstacleGeometry>,
    /// Activation distance ĝ (m): every contact rests within it of the surface; `None` without
    /// contact.
    pub activation: Option<f64>,
    /// True if the structures' cables are in contact with themselves and each other.
    pub self_contact: bool,
    /// The box (min and max corners, m) of the cables at rest and now, the strips and the
    /// bounded obstacles: what the unbounded shapes are drawn over.
    pub extent: [[f64; 3]; 2],
}

/// One obstacle as drawn.
#[derive(Clone, Debug, Serialize)]
pub struct ObstacleGeometry {
    /// Its name (as in its contacts' results).
    pub name: String,
    /// Coulomb coefficient μ.
    pub friction: f64,
    /// Its shape, at its pose.
    pub shape: ShapeGeometry,
}

/// An obstacle's shape (m). Planes and cylinders are unbounded: they are given as the finite
/// piece that covers the scene's extent.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ShapeGeometry {
    /// A square piece of the plane, of side `size`, centred on the extent's centre projected
    /// onto it; `normal` is the outward unit normal (the solid is below).
    Plane {
        /// Centre of the drawn square (a point of the plane).
        center: [f64; 3],
        /// Outward unit normal.
        normal: [f64; 3],
        /// Side of the drawn square (1.5 × the extent's diagonal).
        size: f64,
    },
    /// A ball.
    Sphere {
        /// Centre.
        center: [f64; 3],
        /// Radius.
        radius: f64,
    },
    /// A piece of the infinite round bar: centred on the extent's centre projected onto the
    /// axis, as long as the extent along the axis plus half its diagonal.
    Cylinder {
        /// Centre of the drawn piece (a point of the axis).
        center: [f64; 3],
        /// Unit axis.
        axis: [f64; 3],
        /// Radius.
        radius: f64,
        /// Length of the drawn piece.
        length: f64,
    },
    /// A ring (solid torus): the tube's centre circle of radius `radius` about `center` in the
    /// plane normal to `axis`, and the tube's radius.
    Torus {
        /// Centre.
        center: [f64; 3],
        /// Unit axis.
        axis: [f64; 3],
        /// Radius of the tube's centre circle.
        radius: f64,
        /// Radius of the tube.
        tube_radius: f64,
    },
    /// A box of edge lengths `size` along its axes, turned by `rotation` about its centre.
    Box {
        /// Centre.
        center: [f64; 3],
        /// Edge lengths along the box's axes.
        size: [f64; 3],
        /// Rotation vector (axis × angle, rad) of the box's axes from the global ones.
        rotation: [f64; 3],
    },
    /// A triangle mesh (a mesh file's triangles, as read into the scene).
    Mesh {
        /// Vertex positions.
        vertices: Vec<[f64; 3]>,
        /// Vertex index triples.
        triangles: Vec<[usize; 3]>,
    },
}

/// Smallest diagonal (m) of the extent the unbounded shapes are drawn over.
const MIN_EXTENT: f64 = 1e-3;

/// The obstacles of the session's scene as drawn; `step` is `session.results(..)`.
pub fn scene_geometry(session: &Session, step: &SceneStep) -> SceneGeometry {
    let scene = session.compiled();
    let mut lo = Vec3::repeat(f64::INFINITY);
    let mut hi = Vec3::repeat(f64::NEG_INFINITY);
    let mut grow = |p: Vec3| {
        if p.iter().all(|c| c.is_finite()) {
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
    };
    for r in 0..scene.rods.len() {
        scene.rest_positions(r).into_iter().for_each(&mut grow);
    }
    for p in step.rods.iter().flat_map(|r| &r.positions) {
        grow(Vec3::from(*p));
    }
    for p in step.shells.iter().flat_map(|s| &s.positions) {
        grow(Vec3::from(*p));
    }
    if let Some(c) = &scene.contact {
        for o in &c.obstacles {
            let (a, b) = o.bounds();
            if a.iter().chain(b.iter()).all(|c| c.is_finite()) {
                grow(a);
                grow(b);
            }
        }
    }
    if lo.x > hi.x {
        // Nothing bounded (cannot happen: every scene has a rod or a strip).
        lo = Vec3::zeros();
        hi = Vec3::zeros();
    }
    let centre = 0.5 * (lo + hi);
    let diagonal = (hi - lo).norm().max(MIN_EXTENT);
    let corners: Vec<Vec3> = (0..8)
        .map(|k| {
            Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    let unit = |v: [f64; 3]| {
        let v = Vec3::from(v);
        v / v.norm()
    };
    let names = scene.contact.as_ref().map(|c| c.names.clone());
    let obstacles = session
        .spec()
        .obstacles
        .iter()
        .enumerate()
        .map(|(i, o)| {
            // Where the edits have moved it.
            let moved = session.obstacle_shape(i).unwrap_or_else(|| o.shape.clone());
            let shape = match &moved {
                ObstacleShapeSpec::Plane { point, normal } => {
                    let n = unit(*normal);
                    let p = Vec3::from(*point);
                    ShapeGeometry::Plane {
                        center: arr(centre - n * (centre - p).dot(&n)),
                        normal: arr(n),
                        size: 1.5 * diagonal,
                    }
                }
                ObstacleShapeSpec::Sphere { center, radius } => ShapeGeometry::Sphere {
                    center: *center,
                    radius: *radius,
                },
                ObstacleShapeSpec::Cylinder {
                    point,
                    axis,
                    radius,
                } => {
                    let a = unit(*axis);
                    let p = Vec3::from(*point);
                    let along = corners.iter().map(|c| (c - p).dot(&a));
                    let (smin, smax) = along
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
                            (l.min(s), h.max(s))
                        });
                    ShapeGeometry::Cylinder {
                        center: arr(p + a * (0.5 * (smin + smax))),
                        axis: arr(a),
                        radius: *radius,
                        length: (smax - smin) + 0.5 * diagonal,
                    }
                }
                ObstacleShapeSpec::Torus {
                    center,
                    axis,
                    radius,
                    tube_radius,
                } => ShapeGeometry::Torus {
                    center: *center,
                    axis: arr(unit(*axis)),
                    radius: *radius,
                    tube_radius: *tube_radius,
                },
                ObstacleShapeSpec::Box {
                    center,
                    size,
                    rotate,
                } => ShapeGeometry::Box {
                    center: *center,
                    size: *size,
                    rotation: *rotate,
                },
                ObstacleShapeSpec::Mesh {
                    vertices,
                    triangles,
                    ..
                } => ShapeGeometry::Mesh {
                    vertices: vertices.clone(),
                    triangles: triangles.clone(),
                },
            };
            ObstacleGeometry {
                name: names
                    .as_ref()
                    .and_then(|n| n.get(i).cloned())
                    .unwrap_or_else(|| format!("obstacle{i}")),
                friction: o.friction,
                shape,
            }
        })
        .collect();
    let params = scene.contact.as_ref().map(|c| &c.params[..]).unwrap_or(&[]);
    SceneGeometry {
        obstacles,
        activation: params.iter().map(|p| p.activation).reduce(f64::max),
        self_contact: params.iter().any(|p| p.self_contact),
        extent: [arr(lo), arr(hi)],
    }
}

/// Axial stiffness EA (N) of a rod's section: E times the area of a circle or rectangle, or
/// the section's own `ea`.
fn axial_stiffness(spec: &RodSpec) -> f64 {
    let young = spec.material.as_ref().map_or(0.0, |m| m.young);
    match spec.section {
        SectionSpec::Circle { diameter } => {
            young * std::f64::consts::PI * diameter * diameter / 4.0
        }
        SectionSpec::Rectangle { width, height } => young * width * height,
        SectionSpec::Stiffness { ea, .. } => ea,
    }
}

/// Largest bending stress (Pa) at every vertex of rod `r`, from the change of material
/// curvature from rest (see [`RodView::bending_stress`]); `None` without a material.
fn bending_stress(session: &Session, r: usize) -> Option<Vec<f64>> {
    let spec = session.spec().rods.get(r)?;
    let young = spec.material.as_ref()?.young;
    let rod: &CompiledRod = &session.compiled().rods[r];
    // Distance of the outermost fibre from the neutral axis for each bending direction.
    let stress = |dk: [f64; 2]| match spec.section {
        SectionSpec::Circle { diameter } => {
            Some(young * (dk[0] * dk[0] + dk[1] * dk[1]).sqrt() * 0.5 * diameter)
        }
        // κ₁ moves the centerline along m₁ (the width): the fibre at w/2 is the farthest.
        SectionSpec::Rectangle { width, height } => {
            Some(young * (dk[0].abs() * 0.5 * width + dk[1].abs() * 0.5 * height))
        }
        SectionSpec::Stiffness { .. } => None,
    };
    let nv = rod.n_edges + 1;
    let mut dk = vec![[0.0; 2]; nv];
    let mut hits = vec![0usize; nv];
    for part in &rod.parts {
        let structure = &session.compiled().structures[part.structure];
        let member = &structure.members()[part.member];
        let state = &session.state(part.structure).members[part.member];
        for h in member.vertex_strains(state) {
            let v = part.first_vertex + h.vertex;
            dk[v][0] += h.curvature[0] - h.rest_curvature[0];
            dk[v][1] += h.curvature[1] - h.rest_curvature[1];
            hits[v] += 1;
        }
    }
    // A vertex shared by two parts (interior clamp) has a half hinge on each side.
    (0..nv)
        .map(|v| {
            let w = 1.0 / hits[v].max(1) as f64;
            stress([dk[v][0] * w, dk[v][1] * w])
        })
        .collect()
}
