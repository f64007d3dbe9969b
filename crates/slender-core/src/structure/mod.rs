//! Structures: several members (rods) joined rigidly at shared vertices, with supports that
//! act across a member's own DOFs (sliders, twist holds), solved as one problem.
//!
//! A member is a model of its own (a discrete elastic rod, a discrete Cosserat rod or an
//! SE(3) beam) with its own free DOFs, terms and retraction; joints, sliders and twist holds
//! join discrete elastic rods. The structure maps every member DOF to a global DOF (or drops it) with
//! a coefficient ([`MapSlot`](crate::assembly::MapSlot)):
//! * a **joint** identifies a vertex of several members (a branch point, a splice, the two ends
//!   of a closed ring): their coordinates map to the same global DOFs, and *joint hinges*
//!   carry bending and twisting across it, as if the cable continued through it;
//! * a **slider** (roller, sleeve) keeps one global DOF for a vertex, the position along its
//!   axis: the vertex's three coordinates are that DOF times the axis components;
//! * a **twist hold** drops an edge's material angle.
//!
//! The members' terms run through the assembler with their map ([`Assembler::part`]
//! (crate::assembly::Assembler::part)), so no member code knows it is part of a structure.
//! Joint and slider vertices are *anchors* of the members' retractions: they move by exactly
//! their step, so members stay joined.

pub mod builder;
pub mod dof_map;
pub mod joint;
pub mod member;
pub mod model;
pub mod output;

pub use builder::{JointEnd, SliderSupport, StructureBuilder, TwistHold};
pub use member::{Member, MemberState};
pub use model::{Structure, StructureState};
pub use output::{HeldForces, VertexStrain};
