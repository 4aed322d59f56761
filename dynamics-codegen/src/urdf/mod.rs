//! URDF input: `urdf = "path.urdf";` reads the file at expansion time
//! (relative to the using crate's `CARGO_MANIFEST_DIR`) and turns its links
//! and joints into the same items a hand-written description has, so that
//! every later stage (checks, derivation, emission) is shared.
//!
//! Read: `revolute`, `continuous`, `prismatic` and `fixed` joints with
//! `origin xyz rpy`, `axis` (default `1 0 0`), `limit`, `dynamics damping
//! friction`; links' `inertial` (origin xyz rpy, mass, inertia: a rotated
//! inertial frame is rotated into the link frame, `I = R I' R^T`).
//! Refused, naming the element: floating and planar joints, `mimic`, a link
//! that is the child of two joints (closed loop), unknown links, cycles,
//! zero axes. Non-zero `damping`/`friction` become run-time parameters
//! `damping_<joint>` / `friction_<joint>` with the file's values as
//! defaults, so the rigid body alone stays one assignment away.

mod joint;
mod link;
mod mimic;
mod read;
mod reader;
mod tokens;
mod tree;

pub use read::{load, Limits};
