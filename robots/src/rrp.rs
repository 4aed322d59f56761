//! The planar RRP arm of the dissertation, sec. 3.1.2: link OA turns by q1 about O,
//! cylinder AD turns by q2 about A, plunger CB slides by q3 inside it and
//! carries the load M at l3 + q3 from A.
//!
//! Data: l1 = 0.5, l3 = 1 m; m1 = m2 = m3 = 1, M = 10 kg; c1 = c2 = 0,
//! c3 = 0.5 m; J1 = 0.02, J2 = 0.01, J3 = 0.05 kg m^2; drag b1 = b2 = 0.15,
//! b3 = 0.25; plunger spring c = 350 N/m with rest l0 = 0; g = 10 m/s^2.
//! The tiny inertias the dissertation leaves out are those of
//! `shared/reference/urdf/rrp.urdf`.

dynamics_macros::robot! {
    /// Planar RRP arm with plunger spring and viscous drag (dissertation, sec. 3.1.2).
    ///
    /// The spring and drag are run-time parameters with the dissertation's values;
    /// [`Rrp::rigid`] sets them to zero (the rigid body that Pinocchio models).
    pub robot Rrp;
    gravity = [0.0, -10.0, 0.0];

    const L1 = 0.5;
    const L3 = 1.0;
    /// Load mass M, kg.
    param m = 10.0;
    /// Plunger spring stiffness c, N/m.
    param c = 350.0;
    /// Spring rest position l0, m.
    param l0 = 0.0;
    /// Viscous drag of joint q1, N m s/rad.
    param b1 = 0.15;
    /// Viscous drag of joint q2, N m s/rad.
    param b2 = 0.15;
    /// Viscous drag of joint q3, N s/m.
    param b3 = 0.25;

    link base;
    link oa { mass = 1.0; inertia = [1e-5, 0.02, 0.02]; }
    link cylinder { mass = 1.0; inertia = [1e-5, 0.01, 0.01]; }
    link plunger { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-5, 0.05, 0.05]; }
    link load { mass = m; inertia = [1e-6, 1e-6, 1e-6]; point tip = [0.0, 0.0, 0.0]; }

    joint q1 = revolute(base -> oa) { transfer = [rot(q)]; damping = b1; }
    joint q2 = revolute(oa -> cylinder) { transfer = [tu(L1), rot(q)]; damping = b2; }
    joint q3 = prismatic(cylinder -> plunger) { transfer = [tu(q)]; damping = b3; spring = c; rest = l0; }
    joint load_mount = fixed(plunger -> load) { transfer = [tu(L3)]; }

    /// The program of sec. 3.1.2: the load M moves along the line KL,
    /// `y - 2 x + 2 (l1 + l3) = 0` (eq. 3.7) with the load at
    /// `x = l1 cos q1 + (l3 + q3) cos(q1 + q2)`, `y = l1 sin q1 + (l3 + q3) sin(q1 + q2)`
    /// (eq. 3.14; the available text prints `2 (l1 + l2)` for the constant, but only
    /// `2 (l1 + l3)` = OK puts the start q = 0, the point L, on the line).
    constraint kl = L1 * sin(q1) + (L3 + q3) * sin(q1 + q2)
        - 2.0 * (L1 * cos(q1) + (L3 + q3) * cos(q1 + q2)) + 2.0 * (L1 + L3);
}

impl Rrp {
    /// The rigid body alone: no spring, no drag.
    ///
    /// ```
    /// let r = robots::Rrp::rigid();
    /// assert_eq!((r.params.c, r.params.b1), (0.0, 0.0));
    /// ```
    pub fn rigid() -> Self {
        Self::new(RrpParams {
            c: 0.0,
            b1: 0.0,
            b2: 0.0,
            b3: 0.0,
            ..RrpParams::default()
        })
    }
}
