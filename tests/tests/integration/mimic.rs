//! Mimic joints against the projection of their free twins: a robot whose
//! joint k follows `m q_i + o` must have the dynamics of the same robot
//! with joint k independent, restricted to `q = G q_red + offset`:
//! `M_red = G^T M G`, `g_red = G^T g`, `tau_red = G^T tau`,
//! `K_red = G^T K G`, `D_red = G^T D G` (G is constant), the Coriolis
//! matrix `G^T C G`, the inertial regressor `G^T Y`, the same energies,
//! frame poses, and point Jacobians `J G`. The twins are separate `robot!` expansions; the coupling matrix
//! G is written out here by hand (chains composed on paper).

use dynamics_macros::robot;
use dynamics_runtime::{Parameters, Robot};
use nalgebra::{SMatrix, SVector};
use proptest::prelude::*;

robot! {
    /// A 3-DOF arm with a parallel gripper, from a file written as description
    /// packages ship them (transmissions, gazebo, materials, meshes, a DTD
    /// entity, xacro leftovers); the right finger mimics the left one.
    pub robot GripperArm;
    gravity = [0.0, 0.0, -9.81];
    urdf = "urdf/gripper_arm.urdf";
}

robot! {
    /// The same arm, bare, with the right finger independent.
    pub robot GripperArmFree;
    gravity = [0.0, 0.0, -9.81];
    urdf = "urdf/gripper_arm_free.urdf";
}

robot! {
    /// Mimics written in the grammar: a chain (j3 follows j2 follows j1, one
    /// of them through a `transfer` chain), a prismatic mimic, and the
    /// forces a mimic joint carries (damping, spring, Coulomb friction) at
    /// its own position and speed.
    pub robot Linkage;
    gravity = [0.4, -9.81, 0.7];
    link base;
    link a { mass = 1.3; com = [0.05, 0.02, 0.1]; inertia = [0.02, 0.025, 0.015]; }
    link b { mass = 0.8; com = [0.1, 0.0, 0.02]; inertia = [0.004, 0.006, 0.005]; }
    link c { mass = 0.6; com = [0.08, 0.01, 0.0]; inertia = [0.002, 0.003, 0.0025]; }
    link d { mass = 0.4; com = [0.0, 0.03, 0.02]; inertia = [0.001, 0.0012, 0.0009]; }
    link e { mass = 0.3; com = [0.02, 0.0, 0.04]; inertia = [0.0008, 0.0007, 0.0006]; }
    link f { mass = 0.5; com = [0.06, 0.0, 0.0]; inertia = [0.001, 0.002, 0.002]; point tip = [0.12, 0.01, 0.0]; }
    joint j1 = revolute(base -> a) { origin = [0.0, 0.0, 0.1]; axis = [0.0, 0.0, 1.0]; damping = 0.2; }
    joint j2 = revolute(a -> b) {
        origin = [0.3, 0.0, 0.0]; rpy = [0.1, 0.0, 0.0]; axis = [0.0, 1.0, 0.0];
        mimic = j1; multiplier = 0.5; offset = 0.1;
        damping = 0.3; spring = 2.0; rest = 0.2;
    }
    joint j3 = revolute(b -> c) {
        transfer = [tu(0.25), rot_x(q)];
        mimic = j2; multiplier = -2.0; offset = 0.3; coulomb = 0.1;
    }
    joint j4 = revolute(c -> f) { origin = [0.2, 0.0, 0.0]; axis = [0.0, 0.6, 0.8]; }
    joint s1 = prismatic(a -> d) { origin = [0.0, 0.1, 0.0]; axis = [1.0, 0.0, 0.0]; damping = 1.5; }
    joint s2 = prismatic(d -> e) {
        origin = [0.0, 0.0, 0.05]; axis = [0.0, 0.0, 1.0];
        mimic = s1; multiplier = 1.5; offset = -0.02; damping = 0.4;
    }
    constraint reach = j3 + s2 - 0.1 * t;
}

robot! {
    /// Linkage with every joint independent.
    pub robot LinkageFree;
    gravity = [0.4, -9.81, 0.7];
    link base;
    link a { mass = 1.3; com = [0.05, 0.02, 0.1]; inertia = [0.02, 0.025, 0.015]; }
    link b { mass = 0.8; com = [0.1, 0.0, 0.02]; inertia = [0.004, 0.006, 0.005]; }
    link c { mass = 0.6; com = [0.08, 0.01, 0.0]; inertia = [0.002, 0.003, 0.0025]; }
    link d { mass = 0.4; com = [0.0, 0.03, 0.02]; inertia = [0.001, 0.0012, 0.0009]; }
    link e { mass = 0.3; com = [0.02, 0.0, 0.04]; inertia = [0.0008, 0.0007, 0.0006]; }
    link f { mass = 0.5; com = [0.06, 0.0, 0.0]; inertia = [0.001, 0.002, 0.002]; point tip = [0.12, 0.01, 0.0]; }
    joint j1 = revolute(base -> a) { origin = [0.0, 0.0, 0.1]; axis = [0.0, 0.0, 1.0]; damping = 0.2; }
    joint j2 = revolute(a -> b) {
        origin = [0.3, 0.0, 0.0]; rpy = [0.1, 0.0, 0.0]; axis = [0.0, 1.0, 0.0];
        damping = 0.3; spring = 2.0; rest = 0.2;
    }
    joint j3 = revolute(b -> c) { transfer = [tu(0.25), rot_x(q)]; coulomb = 0.1; }
    joint j4 = revolute(c -> f) { origin = [0.2, 0.0, 0.0]; axis = [0.0, 0.6, 0.8]; }
    joint s1 = prismatic(a -> d) { origin = [0.0, 0.1, 0.0]; axis = [1.0, 0.0, 0.0]; damping = 1.5; }
    joint s2 = prismatic(d -> e) { origin = [0.0, 0.0, 0.05]; axis = [0.0, 0.0, 1.0]; damping = 0.4; }
}

/// `(joint, independent joint, multiplier, offset)` -> G and the offset,
/// rows in the free twin's coordinate order, columns in the reduced one's.
fn coupling<const N: usize, const M: usize>(
    reduced: [&str; N],
    free: [&str; M],
    mimics: &[(&str, &str, f64, f64)],
) -> (SMatrix<f64, M, N>, SVector<f64, M>) {
    let mut g = SMatrix::<f64, M, N>::zeros();
    let mut off = SVector::<f64, M>::zeros();
    for (k, name) in free.iter().enumerate() {
        if let Some(i) = reduced.iter().position(|r| r == name) {
            g[(k, i)] = 1.0;
            continue;
        }
        let (_, of, m, o) = mimics
            .iter()
            .find(|(j, ..)| j == name)
            .expect("every free joint is reduced or a mimic");
        let i = reduced.iter().position(|r| r == of).expect("independent");
        g[(k, i)] = *m;
        off[k] = *o;
    }
    (g, off)
}

fn close<const R: usize, const C: usize>(
    what: &str,
    got: SMatrix<f64, R, C>,
    want: SMatrix<f64, R, C>,
) {
    let scale = 1.0 + want.amax();
    let err = (got - want).amax();
    assert!(
        err <= 1e-10 * scale,
        "{what}: error {err:e}\n{got}\nvs\n{want}"
    );
}

/// Every output of `red` at (q, qd, qdd) against `free` at
/// (G q + offset, G qd, G qdd), projected.
fn projected<R, F, const N: usize, const M: usize>(
    red: &R,
    free: &F,
    (g, off): &(SMatrix<f64, M, N>, SVector<f64, M>),
    q: SVector<f64, N>,
    qd: SVector<f64, N>,
    qdd: SVector<f64, N>,
) where
    R: Robot<N>,
    F: Robot<M>,
{
    let (fq, fqd, fqdd) = (g * q + off, g * qd, g * qdd);
    let gt = g.transpose();
    close("M", red.mass_matrix(&q), gt * free.mass_matrix(&fq) * g);
    close("g", red.gravity(&q), gt * free.gravity(&fq));
    close(
        "tau",
        red.inverse_dynamics(&q, &qd, &qdd),
        gt * free.inverse_dynamics(&fq, &fqd, &fqdd),
    );
    close(
        "Q(0)",
        red.generalized_forces(&q, &qd),
        gt * free.generalized_forces(&fq, &fqd),
    );
    close("Qqt", red.qqt(&q, &qd), gt * free.qqt(&fq, &fqd));
    close("Qqt1", red.qqt1(&q, &qd), gt * free.qqt1(&fq, &fqd));
    close("Qqt2", red.qqt2(&q, &qd), gt * free.qqt2(&fq, &fqd));
    close(
        "C",
        red.coriolis_matrix(&q, &qd),
        gt * free.coriolis_matrix(&fq, &fqd) * g,
    );
    let (pr, pf) = (
        red.perturbation_jacobians(&q, &qd, &qdd),
        free.perturbation_jacobians(&fq, &fqd, &fqdd),
    );
    close("K", pr.k, gt * pf.k * g);
    close("D", pr.d, gt * pf.d * g);
    let terms = red.motion_terms(&q, &qd);
    close("motion_terms.a", terms.a, gt * free.mass_matrix(&fq) * g);
    for (k, name) in R::Params::NAMES.iter().enumerate() {
        let kf = F::Params::NAMES
            .iter()
            .position(|n| n == name)
            .expect("same parameters");
        let sr = red
            .parameter_sensitivity(k, &q, &qd, &qdd)
            .expect("a parameter");
        let sf = free
            .parameter_sensitivity(kf, &fq, &fqd, &fqdd)
            .expect("a parameter");
        close(&format!("dF/d{name}"), sr, gt * sf);
    }
    assert_eq!(R::LINK_NAMES, F::LINK_NAMES);
    let mut yr = vec![SMatrix::<f64, N, 10>::zeros(); R::LINK_NAMES.len()];
    let mut yf = vec![SMatrix::<f64, M, 10>::zeros(); F::LINK_NAMES.len()];
    red.inertial_regressor(&q, &qd, &qdd, &mut yr)
        .expect("one block per link");
    free.inertial_regressor(&fq, &fqd, &fqdd, &mut yf)
        .expect("one block per link");
    for (l, (a, b)) in yr.iter().zip(&yf).enumerate() {
        close(&format!("Y_{}", R::LINK_NAMES[l]), *a, gt * b);
    }
    let energy = |e: f64| SMatrix::<f64, 1, 1>::new(e);
    close(
        "T",
        energy(red.kinetic_energy(&q, &qd)),
        energy(free.kinetic_energy(&fq, &fqd)),
    );
    close(
        "Pi",
        energy(red.potential_energy(&q)),
        energy(free.potential_energy(&fq)),
    );
    assert_eq!(R::FRAME_NAMES, F::FRAME_NAMES);
    for k in 0..R::FRAME_NAMES.len() {
        let (a, b) = (red.frame_pose(k, &q), free.frame_pose(k, &fq));
        close(R::FRAME_NAMES[k], a.expect("a frame"), b.expect("a frame"));
    }
    for k in 0..R::POINT_NAMES.len() {
        close(
            "point",
            red.point_position(k, &q).expect("a point"),
            free.point_position(k, &fq).expect("a point"),
        );
        close(
            "point Jacobian",
            red.point_jacobian(k, &q).expect("a point"),
            free.point_jacobian(k, &fq).expect("a point") * g,
        );
    }
}

#[test]
fn the_reduced_robots_have_one_coordinate_per_independent_joint() {
    assert_eq!(
        GripperArm::JOINT_NAMES,
        [
            "shoulder_pan",
            "shoulder_lift",
            "elbow",
            "finger_left_joint"
        ]
    );
    assert_eq!(Linkage::JOINT_NAMES, ["j1", "j4", "s1"]);
    // Limits of the independent joints only; the mimic's damping is a
    // parameter of its own.
    assert_eq!(GripperArm::UPPER, [f64::INFINITY, 2.0, 2.6, 0.04]);
    assert_eq!(GripperArm::EFFORT, [40.0, 40.0, 20.0, 20.0]);
    let p = GripperArm::default();
    assert_eq!(p.params().get("damping_finger_left_joint"), Some(0.8));
    assert_eq!(p.params().get("damping_finger_right_joint"), Some(0.5));
}

/// A mimic joint's damping b acts at its own speed m qd and enters the
/// effort of the joint it follows as m^2 b qd.
#[test]
fn a_mimic_joints_damping_counts_with_the_square_of_its_multiplier() {
    let arm = GripperArm::default();
    let q = SVector::from([0.1, -0.3, 0.4, 0.01]);
    let mut qd = SVector::<f64, 4>::zeros();
    let rest = arm.generalized_forces(&q, &qd);
    qd[3] = 0.05;
    let moving = arm.generalized_forces(&q, &qd);
    let want = -(0.8 + 1.0 * 0.5) * 0.05;
    assert!(((moving[3] - rest[3]) - want).abs() < 1e-15);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn the_gripper_arm_is_its_free_twin_projected(
        q in prop::array::uniform4(-3.0f64..3.0),
        qd in prop::array::uniform4(-2.0f64..2.0),
        qdd in prop::array::uniform4(-3.0f64..3.0),
    ) {
        let g = coupling(
            GripperArm::JOINT_NAMES,
            GripperArmFree::JOINT_NAMES,
            &[("finger_right_joint", "finger_left_joint", -1.0, 0.002)],
        );
        let mut q = SVector::from(q);
        q[3] *= 0.01;
        let arm = GripperArm::default();
        projected(&arm, &GripperArmFree::default(), &g, q, qd.into(), qdd.into());
    }

    #[test]
    fn a_chain_of_mimics_and_a_prismatic_mimic_are_their_free_twin_projected(
        q in prop::array::uniform3(-3.0f64..3.0),
        qd in prop::array::uniform3(-2.0f64..2.0),
        qdd in prop::array::uniform3(-3.0f64..3.0),
    ) {
        // j3 = -2 (0.5 j1 + 0.1) + 0.3 = -j1 + 0.1
        let g = coupling(
            Linkage::JOINT_NAMES,
            LinkageFree::JOINT_NAMES,
            &[("j2", "j1", 0.5, 0.1), ("j3", "j1", -1.0, 0.1), ("s2", "s1", 1.5, -0.02)],
        );
        projected(&Linkage::default(), &LinkageFree::default(), &g, q.into(), qd.into(), qdd.into());
    }
}

/// A constraint may name a mimic joint: it stands for its position.
#[test]
fn a_constraint_on_a_mimic_joint_uses_its_coupled_position() {
    use dynamics_runtime::Constrained;
    let robot = Linkage::default();
    let q = SVector::from([0.7, -0.2, 0.05]);
    let t = 0.3;
    // j3 = -j1 + 0.1, s2 = 1.5 s1 - 0.02
    let want = (-0.7 + 0.1) + (1.5 * 0.05 - 0.02) - 0.1 * t;
    let got = robot.constraint_residual(t, &q);
    assert!((got[0] - want).abs() < 1e-15, "{got} vs {want}");
}
