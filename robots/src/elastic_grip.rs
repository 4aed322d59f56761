//! The planar arm with an elastic grip of the dissertation, sec. 3.3 (Fig. 3.19):
//! arm OA turns by phi = q1 about O, arm AB by theta = q2 about A, the push
//! rod CD slides along AB by u = q3 = AC against a spring, and its free end
//! D, where the object M sits, deflects by y = q4 across the rod (the rod
//! as a cantilever clamped at C). M is at
//! `r = R(q1) [l1, 0] + R(q1 + q2) [l3 + q3, q4]` (transfer matrices 3.49),
//! so that its height is the bracket of the potential (3.56):
//! `Pi = m g [l1 sin q1 + (q3 + l3) sin(q1 + q2) + q4 cos(q1 + q2)]
//!  + c1 q1^2 / 2 + c2 q2^2 / 2 + c3 (q3 - l)^2 / 2 + c4 q4^2 / 2`.
//!
//! Data of sec. 3.3: m = 1 kg; J1 = J2 = 4 kg m^2 (the arms, about O and
//! A); c3 = 125 N/m, l = 0.15 m; l1 = 0.3 m, l3 = 0.5 m; drag
//! beta1 = beta2 = 0.01 N m s, beta3 = 0.05 N s/m; g = 10 m/s^2;
//! E = 6.626e10 N/m^2, I = 1.14197e-8 m^4. Derived here (the available text drops
//! it): the rod's bending stiffness at D is that of a cantilever with an end
//! load, c4 = 3 E I / l3^3 = 18 160 N/m. Not in the dissertation, chosen here:
//! c1 = c2 = 0 (no torsion springs are given), the arms' own masses 0 (the
//! dissertation gives only their inertias; parameter `arm2_mass` at A if wanted).

dynamics_macros::robot! {
    /// Planar arm with a sliding, elastic push rod carrying M (dissertation, sec. 3.3).
    ///
    /// ```
    /// use dynamics_runtime::Robot;
    /// use nalgebra::Vector4;
    /// let g = robots::ElasticGrip::default();
    /// // Rod stiffness 3 E I / l3^3 of the dissertation's E, I, l3:
    /// assert!((g.params.c4 - 3.0 * 6.626e10 * 1.14197e-8 / 0.125).abs() < 1e-9);
    /// // M sits at (l1 + l3 + u, y) when both arms are horizontal.
    /// let d = g.point_position(0, &Vector4::new(0.0, 0.0, 0.1, 0.01)).unwrap();
    /// assert!((d.x - 0.9).abs() < 1e-15 && (d.y - 0.01).abs() < 1e-15);
    /// ```
    pub robot ElasticGrip;
    gravity = [0.0, -10.0, 0.0];

    const L1 = 0.3;
    const L3 = 0.5;
    /// Mass at D, kg (with the handle's mass: m + km m0, eq. 3.58).
    param m = 1.0;
    /// Mass of arm AB, at A, kg (not given in the dissertation).
    param arm2_mass = 0.0;
    /// Torsion spring at O, N m/rad (not given in the dissertation).
    param c1 = 0.0;
    /// Torsion spring at A, N m/rad (not given in the dissertation).
    param c2 = 0.0;
    /// Push-rod spring, N/m.
    param c3 = 125.0;
    /// Its rest position l, m.
    param l = 0.15;
    /// Bending stiffness of the rod at D, 3 E I / l3^3, N/m.
    param c4 = 3.0 * 6.626e10 * 1.14197e-8 / (L3 * L3 * L3);
    /// Drag at O, N m s/rad.
    param beta1 = 0.01;
    /// Drag at A, N m s/rad.
    param beta2 = 0.01;
    /// Drag of the push rod, N s/m.
    param beta3 = 0.05;

    link base;
    link oa { mass = 1.0; inertia = [1e-5, 4.0, 4.0]; }
    link ab { mass = arm2_mass; inertia = [1e-5, 4.0, 4.0]; }
    link rod;
    link grip { mass = m; point d = [0.0, 0.0, 0.0]; }

    joint phi = revolute(base -> oa) { transfer = [rot(q)]; damping = beta1; spring = c1; }
    joint theta = revolute(oa -> ab) { transfer = [tu(L1), rot(q)]; damping = beta2; spring = c2; }
    joint u = prismatic(ab -> rod) { transfer = [tu(q)]; damping = beta3; spring = c3; rest = l; }
    joint y = prismatic(rod -> grip) { transfer = [tu(L3), tv(q)]; spring = c4; }
}
