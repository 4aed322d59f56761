//! The two-link arm with a clearance in its second joint, dissertation, sec. 3.2
//! (Figs. 3.12-3.13): link 1 (OA) turns by phi1 about O and ends in a ring
//! of radius r1 at A; link 2 ends in a pin of radius r2 < r1 that sits in
//! the ring. Two sets of coordinates describe the same bodies:
//!
//! - [`ClearanceArm`], the dissertation's `(phi1, psi, u, phi2)`: the line of
//!   centres from A turns by psi against link 1, the pin centre lies at u
//!   along it, link 2 turns by phi2 against that line (so link 2's angle to
//!   link 1 is `psi + phi2`). In contact (eq. 3.25) `u = r1 - r2` and the pin
//!   rolls without slipping; these polar coordinates are singular at u = 0.
//! - [`ClearanceArmFree`], `(phi1, x, y, phi)`: the pin centre at (x, y)
//!   from A in link 1's frame and link 2's angle phi to link 1, regular
//!   everywhere inside the ring: the free flight inside the clearance. Its
//!   constraints x = y = 0 give the joint without clearance.
//!
//! Data of sec. 3.2: l1 = 1.25 m, l2 = 0.5 m; m1 = 1 kg (the dissertation's `m`),
//! m2 = 0.5 kg; c1 = 0, c2 = 0.2 m; J1 = J2 = 0.1 kg m^2 (taken about the
//! centres of mass); r1 = 0.0025 m, r2 = 0.00245 m; g = 10 m/s^2.

dynamics_macros::robot! {
    /// Two-link arm with joint clearance in the dissertation's coordinates (phi1, psi, u, phi2).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// use nalgebra::Vector4;
    /// let arm = robots::ClearanceArm::default();
    /// // The pin centre at u along the line of centres, which points down.
    /// let q = Vector4::new(0.0, -std::f64::consts::FRAC_PI_2, 5e-5, std::f64::consts::FRAC_PI_2);
    /// let tip = arm.point_position(0, &q).unwrap();
    /// assert!((tip.x - 1.75).abs() < 1e-12 && (tip.y + 5e-5).abs() < 1e-12);
    /// ```
    pub robot ClearanceArm;
    gravity = [0.0, -10.0, 0.0];

    const L1 = 1.25;
    const L2 = 0.5;

    link base;
    link arm1 { mass = 1.0; inertia = [1e-5, 0.1, 0.1]; }
    link centre_line;
    link pin;
    link arm2 { mass = 0.5; com = [0.2, 0.0, 0.0]; inertia = [1e-5, 0.1, 0.1]; point tip = [L2, 0.0, 0.0]; }

    joint phi1 = revolute(base -> arm1) { transfer = [rot(q)]; }
    joint psi = revolute(arm1 -> centre_line) { transfer = [tu(L1), rot(q)]; }
    joint u = prismatic(centre_line -> pin) { transfer = [tu(q)]; }
    joint phi2 = revolute(pin -> arm2) { transfer = [rot(q)]; }
}

dynamics_macros::robot! {
    /// The same arm with the pin centre in Cartesian coordinates (phi1, x, y, phi).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// use nalgebra::Vector4;
    /// let arm = robots::ClearanceArmFree::default();
    /// let tip = arm.point_position(0, &Vector4::new(0.0, 0.0, -5e-5, 0.0)).unwrap();
    /// assert!((tip.x - 1.75).abs() < 1e-12 && (tip.y + 5e-5).abs() < 1e-12);
    /// ```
    pub robot ClearanceArmFree;
    gravity = [0.0, -10.0, 0.0];

    const L1 = 1.25;
    const L2 = 0.5;

    link base;
    link arm1 { mass = 1.0; inertia = [1e-5, 0.1, 0.1]; }
    link slide;
    link pin;
    link arm2 { mass = 0.5; com = [0.2, 0.0, 0.0]; inertia = [1e-5, 0.1, 0.1]; point tip = [L2, 0.0, 0.0]; }

    joint phi1 = revolute(base -> arm1) { transfer = [rot(q)]; }
    joint x = prismatic(arm1 -> slide) { transfer = [tu(L1), tu(q)]; }
    joint y = prismatic(slide -> pin) { transfer = [tv(q)]; }
    joint phi = revolute(pin -> arm2) { transfer = [rot(q)]; }

    /// No clearance (delta = 0): the pin centre stays at A.
    constraint pin_x = x;
    /// No clearance (delta = 0): the pin centre stays at A.
    constraint pin_y = y;
}
