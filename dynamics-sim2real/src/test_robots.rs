//! Robots the unit tests share.

dynamics_macros::robot! {
    /// A planar two-link arm in the vertical plane (rods of 3 and 1.5 kg).
    pub robot Arm2;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link upper { mass = 3.0; com = [0.1, 0.0, 0.0]; inertia = [1e-5, 0.02, 0.02]; }
    link lower { mass = 1.5; com = [0.08, 0.0, 0.0]; inertia = [1e-5, 0.008, 0.008]; }
    joint j1 = revolute(base -> upper) { transfer = [rot(q)]; }
    joint j2 = revolute(upper -> lower) { transfer = [tu(0.25), rot(q)]; }
}

dynamics_macros::robot! {
    /// A pendulum in the vertical plane: a 1 kg rod, its centre of mass
    /// 0.2 m from the joint.
    pub robot Pendulum;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link rod { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
    joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
}
