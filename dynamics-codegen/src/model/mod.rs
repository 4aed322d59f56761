//! Stage 2, model: the parsed input turned into a validated kinematic tree.
//!
//! Every name is resolved, every shape checked, the tree has one root and no
//! cycle, and links and joints are in depth-first order from the root (the
//! order of the generalized coordinates, as in Pinocchio). Errors of all
//! items are collected before failing.

mod build;
mod inertia;
mod joint;
mod link;
pub mod merge;
mod mimic;
mod normalize;
pub mod scalar;
mod transfer;
mod tree;

pub use build::build;
use scalar::Scalar;
use syn::{Attribute, Ident, Visibility};

/// A validated robot.
pub struct Model {
    /// Attributes and docs of the robot item.
    pub attrs: Vec<Attribute>,
    /// Visibility of the generated items.
    pub vis: Visibility,
    /// The robot's type name.
    pub name: Ident,
    /// Gravity in the world frame.
    pub gravity: [f64; 3],
    /// Run-time parameters, in declaration order.
    pub params: Vec<Param>,
    /// Links, depth-first from the root (index 0).
    pub links: Vec<Link>,
    /// Joints, depth-first (the joint of `links[k]` comes before its subtree).
    pub joints: Vec<Joint>,
    /// Program constraints f(t, q) = 0, in declaration order.
    pub constraints: Vec<Constraint>,
    /// The URDF file read, if any (its absolute path).
    pub urdf: Option<std::path::PathBuf>,
    /// Joint limits from the URDF, by joint name.
    pub limits: std::collections::HashMap<String, crate::urdf::Limits>,
}

/// A program constraint `f(t, q) = 0`.
pub struct Constraint {
    /// Its name.
    pub name: Ident,
    /// f, with joint names resolved to coordinates.
    pub f: Scalar,
}

/// A run-time parameter.
pub struct Param {
    /// Doc comments.
    pub attrs: Vec<Attribute>,
    /// Its name (a field of the parameter struct).
    pub name: Ident,
    /// Its default value.
    pub default: f64,
}

/// A rigid link.
pub struct Link {
    /// Its name.
    pub name: Ident,
    /// Index of its parent link (None for the root).
    pub parent: Option<usize>,
    /// Index (into `Model::joints`) of the joint that carries it.
    pub joint: Option<usize>,
    /// Mass properties, if it has any.
    pub inertial: Option<Inertial>,
    /// Named points (point masses are named points too).
    pub points: Vec<Point>,
}

/// Mass, centre of mass and inertia about the centre of mass, link frame.
pub struct Inertial {
    /// Mass, kg.
    pub mass: Scalar,
    /// Centre of mass in the link frame, m.
    pub com: [Scalar; 3],
    /// [ixx, iyy, izz, ixy, ixz, iyz] about the centre of mass, kg m^2.
    pub inertia: [Scalar; 6],
}

/// A named point of a link, possibly carrying a point mass.
pub struct Point {
    /// Its name.
    pub name: Ident,
    /// Position in the link frame.
    pub at: [Scalar; 3],
    /// The point mass there, kg.
    pub mass: Option<Scalar>,
}

/// The kind of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation; q in rad.
    Revolute,
    /// Translation; q in m.
    Prismatic,
    /// No motion; the child is welded to the parent.
    Fixed,
}

/// One elementary transfer matrix of a joint's chain (dissertation, eqs. 2.1-2.5).
#[derive(Debug, Clone)]
pub enum Elem {
    /// Rotation about the unit axis by the angle.
    Rot([f64; 3], Scalar),
    /// Translation along x, y, z.
    Trans([Scalar; 3]),
    /// A general homogeneous matrix (rows of the 3x3 rotation, then translation).
    Matrix(Box<[[Scalar; 3]; 3]>, [Scalar; 3]),
}

/// A joint between two links.
pub struct Joint {
    /// Its name.
    pub name: Ident,
    /// Its kind.
    pub kind: JointKind,
    /// Parent link index.
    pub parent: usize,
    /// Child link index.
    pub child: usize,
    /// Transfer chain from the parent frame to the child frame.
    pub chain: Vec<Elem>,
    /// Coordinate index (None for fixed joints).
    pub coord: Option<usize>,
    /// Dissipative and spring terms of Q(0).
    pub forces: JointForces,
    /// `mimic = other;` as written: the joint this one follows.
    pub mimic: Option<Mimic>,
    /// A mimic joint's position in terms of an independent coordinate (set
    /// once the tree is ordered; chains of mimics composed).
    pub follows: Option<Follow>,
}

/// `mimic = other; multiplier = m; offset = o;`: the joint's position is
/// `m q_other + o`; it has no coordinate of its own.
pub struct Mimic {
    /// The joint followed.
    pub of: Ident,
    /// Multiplier (default 1).
    pub multiplier: f64,
    /// Offset (default 0).
    pub offset: f64,
}

/// A joint's own position as `multiplier * q[coord] + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Follow {
    /// The independent coordinate.
    pub coord: usize,
    /// d(position)/d(q[coord]).
    pub multiplier: f64,
    /// Position at q[coord] = 0.
    pub offset: f64,
}

impl Joint {
    /// The joint's own position in terms of a coordinate: itself for an
    /// independent moving joint, the composed coupling for a mimic joint,
    /// `None` for a fixed one.
    pub fn position(&self) -> Option<Follow> {
        match (self.coord, self.follows) {
            (Some(coord), _) => Some(Follow {
                coord,
                multiplier: 1.0,
                offset: 0.0,
            }),
            (None, f) => f,
        }
    }
}

/// The forces a joint adds to Q(0).
#[derive(Default)]
pub struct JointForces {
    /// Viscous damping b: -b qd.
    pub damping: Option<Scalar>,
    /// Coulomb friction Fc: -Fc tanh(qd / smoothing).
    pub coulomb: Option<Scalar>,
    /// The velocity scale of the smooth sign (default 1e-3).
    pub coulomb_smoothing: Option<Scalar>,
    /// Linear spring: stiffness c and rest position l0, force c (l0 - q).
    pub spring: Option<(Scalar, Scalar)>,
}

impl Model {
    /// Moving joints (indices into `joints`) in coordinate order.
    pub fn coords(&self) -> Vec<usize> {
        let mut v: Vec<(usize, usize)> = self
            .joints
            .iter()
            .enumerate()
            .filter_map(|(j, joint)| joint.coord.map(|c| (c, j)))
            .collect();
        v.sort();
        v.into_iter().map(|(_, j)| j).collect()
    }
}
