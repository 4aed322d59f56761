//! The planar 3R loading arm of the dissertation, sec. 3.1.1 and chapter 4.
//!
//! Data: l1 = l2 = 0.2 m, payload at l3 = 0.1 m on link 3; centres of mass
//! c1 = 0.0635, c2 = 0.07475, c3 = 0.06067 m; m1 = 4.08, m2 = 2.34,
//! m3 = 0.73 kg; J1 = 0.031, J2 = 0.013, J3 = 0.0013 kg m^2; payload m = 2 kg;
//! g = 9.8 m/s^2. The geometry and the tiny inertias that the dissertation leaves
//! out (1e-5 about the link axis, 1e-6 for the payload) are those of
//! `shared/reference/urdf/arm3r.urdf`, so the model matches the Pinocchio
//! reference values. Joints placed by the planar transfer matrices of the
//! dissertation, eq. 2.4 (tu = translate along the link, rot = rotate).

dynamics_macros::robot! {
    /// Planar 3R loading arm (dissertation, sec. 3.1.1; chapter 4 with `b1..b3 = 1`).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// let arm = robots::Arm3r::default();
    /// let g = arm.gravity(&nalgebra::Vector3::zeros());
    /// assert!((g[0] - 21.93518418).abs() < 1e-8); // hand derivation, reference README
    /// ```
    pub robot Arm3r;
    gravity = [0.0, -9.8, 0.0];

    const L1 = 0.2;
    const L2 = 0.2;
    const L3 = 0.1;
    /// Payload mass at the tip of link 3, kg.
    param m = 2.0;
    /// Viscous damping of joint 1, N m s/rad.
    param b1 = 0.0;
    /// Viscous damping of joint 2, N m s/rad.
    param b2 = 0.0;
    /// Viscous damping of joint 3, N m s/rad.
    param b3 = 0.0;

    link base;
    link link1 { mass = 4.08; com = [0.0635, 0.0, 0.0]; inertia = [1e-5, 0.031, 0.031]; }
    link link2 { mass = 2.34; com = [0.07475, 0.0, 0.0]; inertia = [1e-5, 0.013, 0.013]; }
    link link3 {
        mass = 0.73; com = [0.06067, 0.0, 0.0]; inertia = [1e-5, 0.0013, 0.0013];
        point tip = [L3, 0.0, 0.0];
    }
    link payload { mass = m; inertia = [1e-6, 1e-6, 1e-6]; }

    joint j1 = revolute(base -> link1) { transfer = [rot(q)]; damping = b1; }
    joint j2 = revolute(link1 -> link2) { transfer = [tu(L1), rot(q)]; damping = b2; }
    joint j3 = revolute(link2 -> link3) { transfer = [tu(L2), rot(q)]; damping = b3; }
    joint payload_mount = fixed(link3 -> payload) { transfer = [tu(L3)]; }
}
