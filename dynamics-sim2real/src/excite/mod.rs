//! Exciting motions: a periodic motion of every joint, designed within the
//! robot's limits to make the identification of its base parameters, with
//! per-joint Coulomb and viscous friction, rotor inertia and effort
//! offsets, well conditioned (see `docs/excite.md`).
//!
//! | file | concept |
//! |---|---|
//! | `basis.rs` | [`Fourier`]: the trajectory basis, periodic, at rest at the start pose every period |
//! | `limits.rs` | [`Limits`]: the URDF's limits, an acceleration limit, the margin |
//! | `columns.rs` | [`BaseColumns`]: the weighted regressor's columns and the base parameters (rank reduction over random states) |
//! | `criterion.rs` | [`Criterion`], [`Figures`]: condition number (and D-optimality) of the unit-column base regressor |
//! | `clearance.rs` | [`Clearance`], [`Clearances`]: link frame origins above the ground and apart (not meshes) |
//! | `constraints.rs` | [`check`]: positions, velocities, accelerations and efforts (inverse dynamics) against the limits; [`room`] |
//! | `search.rs` | the optimiser (an evolution strategy with a fixed seed; why in its docs) |
//! | `identifiability.rs` | [`identifiability`]: predicted standard deviation per base parameter at a stated effort noise; what stays unidentifiable |
//! | `separate.rs` | [`Rival`], [`separation_angles`]: the smallest principal angle between two rival effects' columns (or first-order signatures: delay, elasticity, backlash), the others projected out |
//! | `inseparable.rs` | [`inseparable`]: a pair no motion separates (their columns share a direction once the base parameters are regrouped: the first joint's rotor and its link's inertia about the axis) |
//! | `design.rs` | [`design`], [`design_separating`], [`Options`], [`Design`]: the whole design |
//! | `check_data.rs` | [`check_data`]: what a recorded motion can and cannot identify, in words |
//! | `report.rs` | [`DesignReport`]: the design as JSON |

mod basis;
mod check_data;
mod clearance;
mod columns;
mod constraints;
mod criterion;
mod design;
mod error;
mod identifiability;
mod inseparable;
mod limits;
mod report;
mod search;
mod separate;

pub use basis::Fourier;
pub use check_data::{check_data, DataCheck, JointCoverage, WeakDirection};
pub use clearance::{Clearance, Clearances, Minimum};
pub use columns::BaseColumns;
pub use constraints::{check, room, Check};
pub use criterion::{Criterion, Figures};
pub use design::{design, design_separating, Design, Options};
pub use error::ExciteError;
pub use identifiability::{identifiability, Identifiability, Parameter};
pub use inseparable::inseparable;
pub use limits::Limits;
pub use report::DesignReport;
pub use separate::{separation_angles, Rival, BACKLASH_ZONE, STRIBECK_VS};
