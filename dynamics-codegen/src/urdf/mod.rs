//! URDF input: `urdf = "path.urdf";` reads the file at expansion time
//! (relative to the using crate's `CARGO_MANIFEST_DIR`) and turns its links
//! and joints into the same items a hand-written description has, so that
//! every later stage (checks, derivation, emission) is shared.
//!
//! Read: `revolute`, `continuous`, `prismatic` and `fixed` joints with
//! `origin xyz rpy`, `axis` (default `1 0 0`), `limit`, `dynamics damping
//! friction`, `mimic joint multiplier offset` (the items `mimic`,
//! `multiplier`, `offset`: see `model/mimic.rs`); links' `inertial` (origin
//! xyz rpy, mass, inertia: a rotated inertial frame is rotated into the
//! link frame, `I = R I' R^T`). Read past: the prolog, comments, internal
//! DTD entities, and every other element (`visual`, `collision`,
//! `material`, `transmission`, `gazebo`, `safety_controller`,
//! `calibration`, xacro leftovers). Refused, naming the file, the element
//! and the line: floating and planar joints, a link that is the child of
//! two joints (closed loop), unknown links, cycles, zero axes, bad mimics
//! (unknown, fixed or the joint itself, a cycle), non-finite numbers (with
//! a hint for an unexpanded `${..}`). Non-zero `damping`/`friction` become
//! run-time parameters `damping_<joint>` / `friction_<joint>` with the
//! file's values as defaults, so the rigid body alone stays one assignment
//! away.

mod joint;
mod link;
mod mimic;
mod read;
mod reader;
mod tokens;
mod tree;

pub use joint::Limits;
pub use read::load;
