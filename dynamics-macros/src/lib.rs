//! `robot!`: a declarative robot description turned, at compile time, into
//! straight-line Rust for the robot's equations of motion.
//!
//! The pipeline (parse -> model -> derive -> emit) lives in the plain
//! library `dynamics-codegen`; this crate is its proc-macro entry point and
//! the user-facing documentation of the grammar. See [`robot!`].

use proc_macro::TokenStream;

/// Declares a robot and generates its equations of motion.
///
/// The macro derives symbolically, at compile time, the inertia matrix A(q)
/// (from link Jacobians), the inertial forces of the matrix Lagrange form
/// (`Qqt1_i = 1/2 qd^T dA/dq_i qd`, `Qqt2 = -sum_i dA/dq_i qd qd_i`), the
/// Christoffel Coriolis matrix, gravity, the generalized forces Q(0), the
/// energies, frame poses and point Jacobians, and emits them as straight-line
/// code (every shared subexpression computed once, `sin`/`cos` of each angle
/// once, no heap) in an implementation of `dynamics_runtime::Robot<N>`.
///
/// # Grammar
///
/// ```text
/// input      := item*
/// item       := attr* vis "robot" NAME ";"              // exactly one: the type name
///             | "gravity" "=" "[" e "," e "," e "]" ";"  // m/s^2, world frame, constants
///             | "urdf" "=" STRING ";"                    // links and joints from a URDF file, path
///                                                        // relative to CARGO_MANIFEST_DIR; a `link`
///                                                        // item naming one of its links overrides
///                                                        // that link's properties (`mass = payload;`)
///             | "const" NAME "=" e ";"                   // folded into the code
///             | "param" NAME "=" e ";"                   // run-time, default e (a field of NAMEParams)
///             | "constraint" NAME "=" e ";"              // program constraint f(t, q) = 0: joint names
///                                                        // stand for their coordinates, `t` for time
///             | "link" NAME ";"                          // a massless frame (e.g. the base)
///             | "link" NAME "{" link_prop* "}"
///             | "joint" NAME "=" KIND "(" PARENT "->" CHILD ")" ( ";" | "{" joint_prop* "}" )
/// KIND       := "revolute" | "continuous" | "prismatic" | "fixed"
/// link_prop  := "mass" "=" e ";"                         // kg
///             | "com" "=" "[" e "," e "," e "]" ";"      // centre of mass, link frame
///             | "inertia" "=" "[" ixx, iyy, izz ( , ixy, ixz, iyz )? "]" ";"  // about the COM
///             | "point" NAME "=" "[" e "," e "," e "]" ";"              // named point
///             | "point_mass" NAME "=" e "at" "[" e "," e "," e "]" ";"  // point mass (also a named point)
/// joint_prop := "transfer" "=" "[" elem ("," elem)* "]" ";"   // parent frame -> child frame
///             | "origin" "=" "[" x "," y "," z "]" ";"        // URDF style: Trans(origin)
///             | "rpy" "=" "[" roll "," pitch "," yaw "]" ";"  //   Rz(yaw) Ry(pitch) Rx(roll)
///             | "axis" "=" "[" x "," y "," z "]" ";"          //   then motion about/along axis
///             | "damping" "=" e ";"             // viscous: -b qd
///             | "coulomb" "=" e ";"             // Coulomb: -Fc tanh(qd / eps)
///             | "coulomb_smoothing" "=" e ";"   // eps of the smooth sign (default 1e-3)
///             | "spring" "=" e ";"              // linear spring c: force c (rest - q)
///             | "rest" "=" e ";"                // its rest position (default 0)
///             | "mimic" "=" JOINT ";"           // no coordinate of its own: its position is
///             | "multiplier" "=" e ";"          //   multiplier q_JOINT + offset (constants,
///             | "offset" "=" e ";"              //   defaults 1 and 0; chains of mimics compose)
/// elem       := "rot_x(" e ")" | "rot_y(" e ")" | "rot_z(" e ")"          // spatial 4x4
///             | "trans_x(" e ")" | "trans_y(" e ")" | "trans_z(" e ")"
///             | "tu(" e ")" | "tv(" e ")" | "rot(" e ")"                  // planar 3x3, dissertation, eq. 2.4
///             | "matrix([[..],[..],[..]])"                                // general planar 3x3
///             | "matrix([[..],[..],[..],[..]])"                           // general homogeneous 4x4
/// e          := number | NAME | "q" | "pi" | e ("+"|"-"|"*"|"/") e | "-" e | "(" e ")"
///             | ("sin"|"cos"|"sqrt"|"tanh"|"abs") "(" e ")"
/// ```
///
/// `q` is the joint's own coordinate and may appear only in its transfer
/// chain. A `mimic` joint (a gripper's second finger, a linkage) has no
/// coordinate of its own: its `q` stands for `multiplier * q_JOINT +
/// offset`, the robot has one coordinate per independent joint, and the
/// efforts are those of the independent joints (a mimic joint's damping,
/// friction and spring act at its own position and speed and reach its
/// leader's effort times the multiplier). In a `constraint` a mimic
/// joint's name stands for its position. With `constraint` items the robot also implements
/// `dynamics_runtime::Constrained<N, M>` (residual, Jacobian and the
/// acceleration bias of the constraints, derived symbolically). The link frame is the frame at the end of its joint's chain; `com`,
/// `inertia` and points are given in it. Coordinates are numbered depth-first
/// from the root link (as Pinocchio does); fixed joints weld their child to
/// the parent. Every error of an input is reported at once, each at the token
/// at fault.
///
/// # Example
///
/// ```
/// use dynamics_runtime::Robot;
/// use nalgebra::Vector2;
///
/// dynamics_macros::robot! {
///     /// A planar two-link arm with a payload parameter.
///     pub robot TwoLink;
///     gravity = [0.0, -9.81, 0.0];
///     const L1 = 0.5;
///     param payload = 0.2;
///     link base;
///     link upper { mass = 1.0; com = [L1 / 2.0, 0.0, 0.0]; inertia = [1e-4, 0.02, 0.02]; }
///     link fore {
///         mass = 0.8; com = [0.2, 0.0, 0.0]; inertia = [1e-4, 0.01, 0.01];
///         point_mass load = payload at [0.4, 0.0, 0.0];
///     }
///     joint shoulder = revolute(base -> upper) { transfer = [rot_z(q)]; damping = 0.1; }
///     joint elbow = revolute(upper -> fore) { transfer = [tu(L1), rot(q)]; }
/// }
///
/// let arm = TwoLink::default();
/// let q = Vector2::new(0.1, 0.2);
/// let a = arm.mass_matrix(&q);
/// assert!((a - a.transpose()).norm() < 1e-15);
/// let tip = arm.point_position(0, &q).unwrap();
/// assert!((tip.norm() - (0.5f64.powi(2) + 0.4f64.powi(2) + 2.0 * 0.5 * 0.4 * 0.2f64.cos()).sqrt()).abs() < 1e-12);
/// ```
///
/// A parallel gripper whose right finger mirrors the left one: one
/// coordinate, and the effort that drives both fingers.
///
/// ```
/// use dynamics_runtime::Robot;
/// use nalgebra::Vector1;
///
/// dynamics_macros::robot! {
///     pub robot Gripper;
///     gravity = [0.0, 0.0, -9.81];
///     link palm;
///     link left { mass = 0.05; }
///     link right { mass = 0.05; }
///     joint finger_left = prismatic(palm -> left) { axis = [0.0, 1.0, 0.0]; }
///     joint finger_right = prismatic(palm -> right) {
///         axis = [0.0, 1.0, 0.0]; mimic = finger_left; multiplier = -1.0;
///     }
/// }
///
/// assert_eq!(Gripper::JOINT_NAMES, ["finger_left"]);
/// let hand = Gripper::default();
/// let q = Vector1::new(0.01);
/// // Both fingers move with the one coordinate: A = 0.05 + (-1)^2 0.05.
/// assert!((hand.mass_matrix(&q)[(0, 0)] - 0.1).abs() < 1e-15);
/// ```
#[proc_macro]
pub fn robot(input: TokenStream) -> TokenStream {
    dynamics_codegen::expand(input.into(), &options()).into()
}

/// URDF paths relative to the using crate; the IR dump where
/// `DYNAMICS_IR_DIR` says.
fn options() -> dynamics_codegen::Options {
    dynamics_codegen::Options {
        base_dir: std::env::var_os("CARGO_MANIFEST_DIR")
            .map(Into::into)
            .unwrap_or_default(),
        ir_dir: std::env::var_os("DYNAMICS_IR_DIR").map(Into::into),
    }
}
