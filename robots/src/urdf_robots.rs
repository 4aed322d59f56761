//! Robots read from URDF files at compile time: the two industrial arms,
//! and URDF twins of the robots of the source works that tests compare with the
//! hand-written descriptions.

dynamics_macros::robot! {
    /// Universal Robots UR5 (6 DOF), from `data/urdf/ur5.urdf`
    /// (example-robot-data 6.0.0, inertials and kinematics only).
    pub robot Ur5;
    gravity = [0.0, 0.0, -9.81];
    urdf = "data/urdf/ur5.urdf";
}

dynamics_macros::robot! {
    /// The Panda with a symbolic payload: the URDF's hand link (welded to
    /// link 8) gets its mass from the run-time parameter `payload`
    /// (default: the file's 0.73 kg), so the payload can be changed, fitted
    /// or differentiated (`parameter_sensitivity`) at run time.
    pub robot PandaPayload;
    gravity = [0.0, 0.0, -9.81];
    urdf = "data/urdf/panda.urdf";
    /// Mass of the hand and what it holds, kg.
    param payload = 0.73;
    link panda_hand { mass = payload; }
}

dynamics_macros::robot! {
    /// Franka Emika Panda (7 DOF, fingers fixed), from `data/urdf/panda.urdf`.
    ///
    /// URDF joint damping (0.003) is the run-time parameter
    /// `damping_panda_jointK`; set it to 0 for the rigid body Pinocchio models.
    pub robot Panda;
    gravity = [0.0, 0.0, -9.81];
    urdf = "data/urdf/panda.urdf";
}

dynamics_macros::robot! {
    /// The Panda without its hand and fingers, from `data/urdf/panda_arm.urdf`
    /// (`panda.urdf` with those links and joints removed): the arm as Gaz et
    /// al. 2019 logged it (README, "Real logs").
    pub robot PandaArm;
    gravity = [0.0, 0.0, -9.81];
    urdf = "data/urdf/panda_arm.urdf";
}

dynamics_macros::robot! {
    /// The arm3r robot of the source works read from its URDF (twin of [`crate::Arm3r`]).
    pub robot Arm3rUrdf;
    gravity = [0.0, -9.8, 0.0];
    urdf = "data/urdf/arm3r.urdf";
}

dynamics_macros::robot! {
    /// The RRP robot of the source works read from its URDF (twin of [`crate::Rrp::rigid`]
    /// when its damping parameters are zero).
    pub robot RrpUrdf;
    gravity = [0.0, -10.0, 0.0];
    urdf = "data/urdf/rrp.urdf";
}

dynamics_macros::robot! {
    /// The MAR robot of the source works read from its URDF (twin of [`crate::Mar`]).
    pub robot MarUrdf;
    gravity = [0.0, -9.81, 0.0];
    urdf = "data/urdf/mar.urdf";
}

impl Panda {
    /// The rigid body alone (URDF damping off), as Pinocchio models it.
    ///
    /// ```
    /// use dynamics_runtime::{Parameters, Robot};
    /// let p = robots::Panda::rigid();
    /// assert!(p.params().get("damping_panda_joint1") == Some(0.0));
    /// assert_eq!(robots::Panda::JOINT_NAMES[6], "panda_joint7");
    /// ```
    pub fn rigid() -> Self {
        Self::new(zeroed())
    }
}

impl PandaArm {
    /// The rigid body alone (URDF damping off).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// let arm = robots::PandaArm::rigid();
    /// let full = robots::Panda::rigid();
    /// let q = nalgebra::SVector::<f64, 7>::from([0.0, 1.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
    /// let z = nalgebra::SVector::<f64, 7>::zeros();
    /// // Held still, leaning forward: without the hand and fingers (0.76 kg
    /// // about 0.5 m out) the shoulder holds some 3 N m less.
    /// let (a, f) = (arm.inverse_dynamics(&q, &z, &z), full.inverse_dynamics(&q, &z, &z));
    /// assert!((f[1] - a[1]).abs() > 2.0 && (f[1] - a[1]).abs() < 5.0, "{}", f[1] - a[1]);
    /// ```
    pub fn rigid() -> Self {
        Self::new(zeroed())
    }
}

impl RrpUrdf {
    /// The rigid body alone (URDF damping off).
    pub fn rigid() -> Self {
        Self::new(zeroed())
    }
}

/// Parameters all set to zero (the URDF's damping and friction off).
fn zeroed<P: dynamics_runtime::Parameters>() -> P {
    let mut p = P::default();
    for i in 0..P::NAMES.len() {
        p.set_value(i, 0.0);
    }
    p
}
