//! The planar arm of the dissertation, sec. 3.4 (Fig. 3.24): link OA turns by q1
//! about O, the cylinder turns by q2 about A, the piston slides by q3 in it
//! against a spring; its end point C works against the environment.
//!
//! Data of sec. 3.4: l1 = 0.5 m, l3 = 1 m (C at l3 + q3 from A);
//! m1 = m2 = m3 = 1 kg; c1 = c2 = 0, c3 = 0.5 m; J1 = 1, J2 = 0.1,
//! J3 = 0.1 kg m^2 (taken about the centres of mass, planar axis);
//! spring k = 650 N/m with rest l0 = 0.1 m; drag b1 = b2 = 0.1 N m s,
//! b3 = 0. Not in the dissertation, chosen and documented here: gravity
//! g = 10 m/s^2 (as in sec. 3.1.2, the same arm) and the slope a = 2 of the
//! line KL (eq. 3.89 leaves `a` open; sec. 3.1.2 uses 2). The tiny inertias
//! about the link axes (1e-5) only keep the 3-D inertia tensors valid.

dynamics_macros::robot! {
    /// Planar RRP arm whose piston end C follows the line KL (dissertation, sec. 3.4).
    ///
    /// ```
    /// use dynamics_runtime::{Constrained, Robot};
    /// let arm = robots::Piston::default();
    /// let q = nalgebra::Vector3::zeros();
    /// // At q = 0 the end point C = (l1 + l3, 0) is the point L of the line.
    /// assert!((arm.point_position(0, &q).unwrap() - nalgebra::Vector3::new(1.5, 0.0, 0.0)).norm() < 1e-15);
    /// assert!(arm.constraint_residual(0.0, &q)[0].abs() < 1e-15);
    /// ```
    pub robot Piston;
    gravity = [0.0, -10.0, 0.0];

    const L1 = 0.5;
    const L3 = 1.0;
    /// Slope a of the line KL, `y = a x - a (l1 + l3)` (eq. 3.89).
    const SLOPE = 2.0;
    /// Piston spring stiffness k, N/m.
    param k = 650.0;
    /// Spring rest position l0, m.
    param l0 = 0.1;
    /// Viscous drag of joint q1, N m s/rad.
    param b1 = 0.1;
    /// Viscous drag of joint q2, N m s/rad.
    param b2 = 0.1;
    /// Viscous drag of joint q3, N s/m.
    param b3 = 0.0;

    link base;
    link oa { mass = 1.0; inertia = [1e-5, 1.0, 1.0]; }
    link cylinder { mass = 1.0; inertia = [1e-5, 0.1, 0.1]; }
    link piston {
        mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-5, 0.1, 0.1];
        point c = [L3, 0.0, 0.0];
    }

    joint q1 = revolute(base -> oa) { transfer = [rot(q)]; damping = b1; }
    joint q2 = revolute(oa -> cylinder) { transfer = [tu(L1), rot(q)]; damping = b2; }
    joint q3 = prismatic(cylinder -> piston) { transfer = [tu(q)]; damping = b3; spring = k; rest = l0; }

    /// The program of sec. 3.4: C on the line KL, `y - a x + a (l1 + l3) = 0`
    /// (eq. 3.89) with C at `x = l1 cos q1 + (l3 + q3) cos(q1 + q2)`,
    /// `y = l1 sin q1 + (l3 + q3) sin(q1 + q2)`.
    constraint kl = L1 * sin(q1) + (L3 + q3) * sin(q1 + q2)
        - SLOPE * (L1 * cos(q1) + (L3 + q3) * cos(q1 + q2)) + SLOPE * (L1 + L3);
}
