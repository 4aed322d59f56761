//! The MAR modular manipulator of the vibration paper, Table 1: q1 turns the arm about
//! the horizontal x axis, q2 turns link 2 about z, link 3 slides along link
//! 2's x axis (its centre s3 = 0.18 m from the slide origin). Links are thin
//! rods: lengths 0.15, 0.18, 0.42 m, masses 12.7, 12.7, 15 kg.
//!
//! Table 1's drive stiffness and damping act between the drive (motor side,
//! position `q*_m`, a run-time parameter) and the link:
//! `Q = k (q_m - q) - d qd`. They default to zero (the rigid body of
//! `shared/reference/urdf/mar.urdf`); [`Mar::with_drives`] sets Table 1.

/// Table 1: static stiffness of the drives, N m/rad (q1, q2) and N/m (q3).
pub const DRIVE_STIFFNESS: [f64; 3] = [110066.0, 110066.0, 1604648.0];
/// Table 1: damping of the drives, N m s/rad (q1, q2) and N s/m (q3).
pub const DRIVE_DAMPING: [f64; 3] = [95.0, 76.0, 246.0];

dynamics_macros::robot! {
    /// MAR manipulator (vibration paper, Table 1), optionally with elastic drives.
    pub robot Mar;
    gravity = [0.0, -9.81, 0.0];

    const L1 = 0.15;
    const L2 = 0.18;
    const S3 = 0.18;
    /// Drive stiffness of q1.
    param k1 = 0.0;
    /// Drive stiffness of q2.
    param k2 = 0.0;
    /// Drive stiffness of q3.
    param k3 = 0.0;
    /// Drive damping of q1.
    param d1 = 0.0;
    /// Drive damping of q2.
    param d2 = 0.0;
    /// Drive damping of q3.
    param d3 = 0.0;
    /// Motor-side position of drive 1, rad.
    param q1_m = 0.0;
    /// Motor-side position of drive 2, rad.
    param q2_m = 0.0;
    /// Motor-side position of drive 3, m.
    param q3_m = 0.0;

    link base;
    link link1 { mass = 12.7; com = [0.0, L1 / 2.0, 0.0]; inertia = [0.0238125, 1e-6, 0.0238125]; }
    link link2 { mass = 12.7; com = [0.0, L2 / 2.0, 0.0]; inertia = [0.034290, 1e-6, 0.034290]; }
    link link3 { mass = 15.0; com = [S3, 0.0, 0.0]; inertia = [1e-6, 0.2205, 0.2205]; point gripper = [S3 + 0.21, 0.0, 0.0]; }

    joint q1 = revolute(base -> link1) { transfer = [rot_x(q)]; spring = k1; rest = q1_m; damping = d1; }
    joint q2 = revolute(link1 -> link2) { transfer = [trans_y(L1), rot_z(q)]; spring = k2; rest = q2_m; damping = d2; }
    joint q3 = prismatic(link2 -> link3) { transfer = [trans_y(L2), trans_x(q)]; spring = k3; rest = q3_m; damping = d3; }
}

impl Mar {
    /// The MAR with Table 1's drive stiffness and damping, motors at `q_m`.
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// let mar = robots::Mar::with_drives([0.0; 3]);
    /// // Holding still at the motor positions, the drives carry gravity only.
    /// let q = nalgebra::Vector3::zeros();
    /// let f = mar.generalized_forces(&q, &q);
    /// assert!((f + mar.gravity(&q)).norm() < 1e-9);
    /// ```
    pub fn with_drives(q_m: [f64; 3]) -> Self {
        let [k1, k2, k3] = DRIVE_STIFFNESS;
        let [d1, d2, d3] = DRIVE_DAMPING;
        Self::new(MarParams {
            k1,
            k2,
            k3,
            d1,
            d2,
            d3,
            q1_m: q_m[0],
            q2_m: q_m[1],
            q3_m: q_m[2],
        })
    }
}
