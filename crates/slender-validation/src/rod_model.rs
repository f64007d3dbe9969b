//! The rod formulations the benchmarks run side by side (seed §2): the discrete elastic rod
//! (Kirchhoff, slender's default), the discrete Cosserat rod (CRod-type) and the SE(3) beam
//! (Odin-type). Each benchmark builds its rod from a [`RodSpec`] and runs generic code over
//! [`BenchmarkRod`]; [`with_rod_model!`](crate::with_rod_model) picks the type.

use serde::{Deserialize, Serialize};
use slender_core::cosserat::{CosseratBuilder, CosseratRod};
use slender_core::framed::{DofSlot, FramedState, ShearStiffness};
use slender_core::geometry::Vec3;
use slender_core::lie::DarbouxMeasure;
use slender_core::linalg::SymmetricBandMatrix;
use slender_core::rod::{Grading, RestCurve, Rod, RodBuilder, RodProperties, RodState};
use slender_core::se3::{Se3Builder, Se3Rod};
use slender_core::solver::EquilibriumProblem;
use slender_core::ModelError;

/// A rod formulation.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum RodModel {
    /// Discrete elastic rod (Bergou et al.): Kirchhoff, positions plus one twist angle per
    /// edge. slender's default.
    #[default]
    Der,
    /// Discrete Cosserat rod (Lang, Linn & Arnold; CRod-type): a frame per edge, shear, the
    /// quaternion (sine) Darboux vector 2 sin(φ/2).
    Cosserat,
    /// The same rod with the tangent (Cayley) Darboux vector 2 tan(φ/2), the discrete elastic
    /// rod's curvature: it separates the staggered grid and shear from the curvature measure.
    CosseratTangent,
    /// Geometrically exact SE(3) beam (Sonneville et al.; Odin-type): a pose per node,
    /// helicoidal elements.
    Se3,
}

impl RodModel {
    /// All models, in report order.
    pub const ALL: [RodModel; 4] = [
        RodModel::Der,
        RodModel::Cosserat,
        RodModel::CosseratTangent,
        RodModel::Se3,
    ];

    /// Name in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Der => "der",
            Self::Cosserat => "cosserat",
            Self::CosseratTangent => "cosserat-tan",
            Self::Se3 => "se3",
        }
    }

    /// Label in plots and reports.
    pub fn label(self) -> &'static str {
        match self {
            Self::Der => "discrete elastic rod (Kirchhoff)",
            Self::Cosserat => "discrete Cosserat rod (CRod-type)",
            Self::CosseratTangent => "discrete Cosserat rod, tangent Darboux vector",
            Self::Se3 => "SE(3) beam (Odin-type)",
        }
    }

    /// Parses [`Self::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == s)
    }
}

/// What a benchmark builds: a rod clamped at s = 0 along `curve`.
#[derive(Clone, Debug, PartialEq)]
pub struct RodSpec {
    /// Rest centerline.
    pub curve: RestCurve,
    /// Section stiffnesses and mass per length.
    pub properties: RodProperties,
    /// Shear stiffnesses (ignored by the discrete elastic rod).
    pub shear: ShearStiffness,
    /// Number of elements.
    pub elements: usize,
    /// Node distribution.
    pub grading: Grading,
    /// First material director at the clamp.
    pub first_director: Vec3,
    /// Gravity (m/s²) at load factor 1.
    pub gravity: Vec3,
    /// Gravity (m/s²) on at every load factor.
    pub preload_gravity: Vec3,
    /// Motion restricted to the plane ⊥ this axis, if any.
    pub planar_axis: Option<usize>,
    /// Darboux measure of a Cosserat rod.
    pub darboux: DarbouxMeasure,
}

/// A rod formulation as the benchmarks use it: built from a [`RodSpec`], solved by the one
/// solver, measured by its vertex positions.
pub trait BenchmarkRod: EquilibriumProblem<Hessian = SymmetricBandMatrix> + Sized {
    /// Builds the rod.
    fn from_spec(spec: &RodSpec) -> Result<Self, ModelError>;
    /// The stress-free state.
    fn rest(&self) -> &Self::State;
    /// Vertex positions (m) of a state.
    fn positions(state: &Self::State) -> &[Vec3];
    /// Rest element lengths (m).
    fn element_lengths(&self) -> &[f64];
    /// Rest length (m).
    fn rod_length(&self) -> f64;
    /// True if free DOF `i` is an angle (rad) rather than a coordinate (m).
    fn is_rotational(&self, i: usize) -> bool;
    /// The free DOFs that move out of the plane ⊥ e_axis (that coordinate of the vertices;
    /// the twist angles, or the frames' rotations about in-plane axes), in order.
    fn out_of_plane_dofs(&self, axis: usize) -> Vec<usize>;
    /// Half-bandwidth of the out-of-plane block in that ordering.
    const OUT_OF_PLANE_BANDWIDTH: usize;
}

impl RodSpec {
    /// The spec with the options of `model` (the Darboux measure of a Cosserat rod).
    pub fn for_model(mut self, model: RodModel) -> Self {
        self.darboux = match model {
            RodModel::CosseratTangent => DarbouxMeasure::Tangent,
            _ => DarbouxMeasure::Sine,
        };
        self
    }

    /// The discrete elastic rod of this spec.
    pub fn build_der(&self) -> Result<Rod, ModelError> {
        let mut b = RodBuilder::new(self.curve.clone(), self.properties)
            .elements(self.elements)
            .grading(self.grading)
            .first_director(self.first_director)
            .clamp_start()
            .gravity(self.gravity)
            .preload_gravity(self.preload_gravity);
        if let Some(k) = self.planar_axis {
            b = b.planar_motion(k);
        }
        b.build()
    }
}

macro_rules! framed_builder {
    ($spec:expr, $builder:ty $(, $opt:ident)?) => {{
        let s = $spec;
        let mut b = <$builder>::new(s.curve.clone(), s.properties, s.shear)
            $(.$opt(s.$opt))?
            .elements(s.elements)
            .grading(s.grading)
            .first_director(s.first_director)
            .clamp_start()
            .gravity(s.gravity)
            .preload_gravity(s.preload_gravity);
        if let Some(k) = s.planar_axis {
            b = b.planar_motion(k);
        }
        b.build()
    }};
}

impl BenchmarkRod for Rod {
    fn from_spec(spec: &RodSpec) -> Result<Self, ModelError> {
        spec.build_der()
    }
    fn rest(&self) -> &RodState {
        self.rest_state()
    }
    fn positions(state: &RodState) -> &[Vec3] {
        state.positions()
    }
    fn element_lengths(&self) -> &[f64] {
        self.rest_lengths()
    }
    fn rod_length(&self) -> f64 {
        self.length()
    }
    fn is_rotational(&self, i: usize) -> bool {
        self.dofs().is_angle(i)
    }
    fn out_of_plane_dofs(&self, axis: usize) -> Vec<usize> {
        (0..self.n_free())
            .filter(|&i| {
                let f = self.dofs().full_index(i);
                f % 4 == axis || f % 4 == 3
            })
            .collect()
    }
    /// (y₁, θ¹, y₂, θ², …): a hinge couples five consecutive entries.
    const OUT_OF_PLANE_BANDWIDTH: usize = 4;
}

/// Out-of-plane DOFs of a rod with frames: coordinate `axis` of the vertices, rotation
/// components about the other two axes.
fn framed_out_of_plane(dofs: &slender_core::framed::FramedDofs, axis: usize) -> Vec<usize> {
    (0..dofs.n_free())
        .filter(|&i| match dofs.slot(i) {
            DofSlot::Position { k, .. } => k == axis,
            DofSlot::Rotation { k, .. } => k != axis,
        })
        .collect()
}

/// The benchmark view of a framed rod: everything but how it is built and its out-of-plane
/// bandwidth comes from the shared [`FramedCore`](slender_core::framed::FramedCore).
macro_rules! framed_benchmark_rod {
    ($rod:ty, $builder:ty $(, $opt:ident)?; $(#[$doc:meta])* bandwidth = $bw:expr) => {
        impl BenchmarkRod for $rod {
            fn from_spec(spec: &RodSpec) -> Result<Self, ModelError> {
                framed_builder!(spec, $builder $(, $opt)?)
            }
            fn rest(&self) -> &FramedState {
                self.rest_state()
            }
            fn positions(state: &FramedState) -> &[Vec3] {
                state.positions()
            }
            fn element_lengths(&self) -> &[f64] {
                self.rest_lengths()
            }
            fn rod_length(&self) -> f64 {
                self.length()
            }
            fn is_rotational(&self, i: usize) -> bool {
                self.dofs().is_rotation(i)
            }
            fn out_of_plane_dofs(&self, axis: usize) -> Vec<usize> {
                framed_out_of_plane(self.dofs(), axis)
            }
            $(#[$doc])*
            const OUT_OF_PLANE_BANDWIDTH: usize = $bw;
        }
    };
}

framed_benchmark_rod!(CosseratRod, CosseratBuilder, darboux;
    /// (y_j, ω_j (2), y_{j+1}, …): a vertex term spans two frames, five entries.
    bandwidth = 4);
framed_benchmark_rod!(Se3Rod, Se3Builder;
    /// (y_A, ω_A (2), y_B, ω_B (2)): an element spans six entries.
    bandwidth = 5);

/// Evaluates `$body` with the type alias `$p` bound to the rod type of `$model`.
#[macro_export]
macro_rules! with_rod_model {
    ($model:expr, $p:ident => $body:expr) => {
        match $model {
            $crate::rod_model::RodModel::Der => {
                type $p = slender_core::rod::Rod;
                $body
            }
            $crate::rod_model::RodModel::Cosserat
            | $crate::rod_model::RodModel::CosseratTangent => {
                type $p = slender_core::cosserat::CosseratRod;
                $body
            }
            $crate::rod_model::RodModel::Se3 => {
                type $p = slender_core::se3::Se3Rod;
                $body
            }
        }
    };
}
