//! The columns of the identification regressor, named: per joint Coulomb
//! and viscous friction, a constant effort offset and rotor inertia, and
//! the ten inertial parameters of every link. The identification
//! (`identify`) fits them; the designer of exciting motions (`excite`)
//! conditions them.

use crate::inertial::PARAMETER_NAMES;
use dynamics_runtime::Robot;

/// What one column stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Column {
    /// `sign(qd_j)` (smooth): a Coulomb level on joint j (positive:
    /// friction, the drive pushes harder than the model says).
    Coulomb(usize),
    /// `qd_j`: viscous friction of joint j (positive: friction).
    Viscous(usize),
    /// `1` on joint j: a constant effort offset.
    Offset(usize),
    /// `qdd_j` on joint j: rotor inertia.
    Armature(usize),
    /// Parameter k (Pinocchio's order) of link l (`Robot::LINK_NAMES`).
    Link(usize, usize),
}

impl Column {
    /// A readable name, e.g. `coulomb panda_joint1`, `panda_link3 m c_x`.
    pub fn name<R: Robot<N>, const N: usize>(self) -> String {
        match self {
            Column::Coulomb(j) => format!("coulomb {}", R::JOINT_NAMES[j]),
            Column::Viscous(j) => format!("viscous {}", R::JOINT_NAMES[j]),
            Column::Offset(j) => format!("offset {}", R::JOINT_NAMES[j]),
            Column::Armature(j) => format!("armature {}", R::JOINT_NAMES[j]),
            Column::Link(l, k) => format!("{} {}", R::LINK_NAMES[l], PARAMETER_NAMES[k]),
        }
    }
}

/// Every column, joints' first (so that they are kept when a link
/// parameter duplicates them).
pub fn all<R: Robot<N>, const N: usize>() -> Vec<Column> {
    let mut c = Vec::new();
    for j in 0..N {
        c.extend([
            Column::Coulomb(j),
            Column::Viscous(j),
            Column::Offset(j),
            Column::Armature(j),
        ]);
    }
    for l in 0..R::LINK_NAMES.len() {
        c.extend((0..10).map(|k| Column::Link(l, k)));
    }
    c
}
