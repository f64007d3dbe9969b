//! The bend–twist bifurcation of a naturally curved rod (seed §4, design.md §1.2).

pub mod acceptance;
pub mod case;
pub mod criticality;
pub mod master_curve;
pub mod measures;
pub mod protocol;
pub mod regime;
pub mod stability;
pub mod sweep;
