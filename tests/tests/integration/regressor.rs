//! The inertial regressor `Y_l = d tau / d pi_l` that `robot!` emits,
//! against independent truth: the emitted inverse dynamics (without
//! damping, friction and springs), Pinocchio's reference efforts, the
//! emitted parameter sensitivities (derived from the efforts by symbolic
//! differentiation, another route), and a second description of the same
//! robot through general transfer matrices (which takes the Jacobian
//! route instead of the Newton-Euler one).

use dynamics_runtime::{DynamicsError, Parameters, Robot};
use nalgebra::{SMatrix, SVector};
use robots::registry::{AnyRobot, ROBOTS};

/// A deterministic state generator (64-bit LCG, uniform in [-r, r]).
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self, r: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        r * (2.0 * ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 1.0)
    }
    fn vector<const N: usize>(&mut self, r: f64) -> SVector<f64, N> {
        SVector::from_fn(|_, _| self.uniform(r))
    }
}

pub fn regressor<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    qdd: &SVector<f64, N>,
) -> Vec<SMatrix<f64, N, 10>> {
    let mut y = vec![SMatrix::zeros(); R::LINK_NAMES.len()];
    r.inertial_regressor(q, qd, qdd, &mut y)
        .expect("right length");
    y
}

pub fn parameters<R: Robot<N>, const N: usize>(r: &R) -> Vec<SVector<f64, 10>> {
    let mut pi = vec![SVector::zeros(); R::LINK_NAMES.len()];
    r.inertial_parameters(&mut pi).expect("right length");
    pi
}

fn y_pi<const N: usize>(y: &[SMatrix<f64, N, 10>], pi: &[SVector<f64, 10>]) -> SVector<f64, N> {
    y.iter().zip(pi).map(|(y, p)| y * p).sum()
}

/// The rigid-body efforts: inverse dynamics plus the damping, friction and
/// spring forces it contains (`Q(0) + g` is exactly those).
fn rigid<R: Robot<N>, const N: usize>(
    r: &R,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    qdd: &SVector<f64, N>,
) -> SVector<f64, N> {
    r.inverse_dynamics(q, qd, qdd) + r.generalized_forces(q, qd) + r.gravity(q)
}

fn check_random_states<R: Robot<N>, const N: usize>(r: &R, name: &str) {
    let pi = parameters(r);
    assert!(!pi.is_empty(), "{name}: no link carries parameters");
    let mut rng = Lcg(7 + N as u64);
    for _ in 0..50 {
        let (q, qd, qdd) = (rng.vector(3.0), rng.vector(2.0), rng.vector(5.0));
        let y = regressor(r, &q, &qd, &qdd);
        let want = rigid(r, &q, &qd, &qdd);
        let err = (y_pi(&y, &pi) - want).abs().max();
        assert!(
            err <= 1e-10 * (1.0 + want.abs().max()),
            "{name}: Y pi - tau_rigid = {err:e} at q = {q:?}"
        );
    }
}

#[test]
fn y_pi_is_the_rigid_inverse_dynamics_of_every_robot() {
    for (name, _) in ROBOTS {
        let robot = AnyRobot::by_name(name).expect("listed robot");
        robots::each_robot!(&robot, r => check_random_states(r, name));
    }
}

fn check_pinocchio<R: Robot<N>, const N: usize>(r: &R, text: &str, name: &str) {
    let doc: serde_json::Value = serde_json::from_str(text).expect("reference JSON");
    let pi = parameters(r);
    let vec = |v: &serde_json::Value| -> SVector<f64, N> {
        let v: Vec<f64> = serde_json::from_value(v.clone()).expect("numbers");
        SVector::from_column_slice(&v)
    };
    let states = doc["states"].as_array().expect("states");
    assert_eq!(states.len(), 20);
    for s in states {
        let y = regressor(r, &vec(&s["q"]), &vec(&s["v"]), &vec(&s["a"]));
        let tau = vec(&s["tau"]);
        let err = (y_pi(&y, &pi) - tau).abs().max();
        assert!(
            err <= 1e-10 * (1.0 + tau.abs().max()),
            "{name}: Y pi - Pinocchio's tau = {err:e}"
        );
    }
}

#[test]
fn y_pi_matches_pinocchio_on_its_reference_states() {
    // The rigid robots Pinocchio models (its files carry no damping).
    for name in [
        "arm3r",
        "rrp-rigid",
        "mar",
        "ur5",
        "panda",
        "arm3r-urdf",
        "mar-urdf",
    ] {
        let robot = AnyRobot::by_name(name).expect("listed robot");
        let (_, text) = robot.reference();
        robots::each_robot!(&robot, r => check_pinocchio(r, text, name));
    }
}

#[test]
fn link_names_follow_the_model() {
    // Panda: links 1-7 (link 8, the hand and the fingers weld into link 7;
    // link 0 is the root).
    let names: Vec<String> = (1..=7).map(|k| format!("panda_link{k}")).collect();
    assert_eq!(robots::Panda::LINK_NAMES, names);
    // The RRP's load hangs on a fixed joint but its mass is a parameter:
    // it keeps its own frame and columns.
    assert_eq!(
        robots::Rrp::LINK_NAMES,
        ["oa", "cylinder", "plunger", "load"]
    );
    // The Panda with a payload parameter: the hand keeps its own columns,
    // and so do the fingers (a parameter-dependent mass takes nothing in).
    assert_eq!(
        &robots::PandaPayload::LINK_NAMES[7..],
        ["panda_hand", "panda_leftfinger", "panda_rightfinger"]
    );
}

#[test]
fn wrong_lengths_are_errors_that_write_nothing() {
    let r = robots::Arm3r::default();
    let z = SVector::<f64, 3>::zeros();
    assert_eq!(
        robots::Arm3r::LINK_NAMES,
        ["link1", "link2", "link3", "payload"]
    );
    let mut y = vec![SMatrix::<f64, 3, 10>::repeat(7.0); 2];
    let err = r.inertial_regressor(&z, &z, &z, &mut y).unwrap_err();
    assert_eq!(
        err,
        DynamicsError::Length {
            quantity: "inertial_regressor",
            expected: 4,
            found: 2
        }
    );
    assert!(y.iter().all(|m| m.iter().all(|&x| x == 7.0)));
    let mut pi = vec![SVector::<f64, 10>::zeros(); 5];
    assert!(r.inertial_parameters(&mut pi).is_err());
}

/// `d tau / d p = sum_l Y_l d pi_l / d p` for a run-time parameter p, with
/// `d pi / d p` by central differences of the emitted nominal parameters and
/// `d tau / d p` the emitted symbolic sensitivity.
fn check_sensitivity<R: Robot<N> + Clone, const N: usize>(r: &R, param: &str, seed: u64) {
    let index = R::Params::NAMES
        .iter()
        .position(|n| *n == param)
        .expect("parameter");
    let p0 = r.params().get(param).expect("parameter");
    let h = 1e-6 * (1.0 + p0.abs());
    let at = |v: f64| {
        let mut s = r.clone();
        s.params_mut().set(param, v).expect("settable");
        parameters(&s)
    };
    let (plus, minus) = (at(p0 + h), at(p0 - h));
    let dpi: Vec<SVector<f64, 10>> = plus
        .iter()
        .zip(&minus)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect();
    let mut rng = Lcg(seed);
    for _ in 0..20 {
        let (q, qd, qdd) = (rng.vector(3.0), rng.vector(2.0), rng.vector(5.0));
        let y = regressor(r, &q, &qd, &qdd);
        let want = r
            .parameter_sensitivity(index, &q, &qd, &qdd)
            .expect("sensitivity");
        let err = (y_pi(&y, &dpi) - want).abs().max();
        assert!(
            err <= 1e-6 * (1.0 + want.abs().max()),
            "{param}: Y dpi/dp - dtau/dp = {err:e}"
        );
    }
}

dynamics_macros::robot! {
    /// A spatial 3-joint arm whose second link's mass properties (body and
    /// a point mass) are all run-time parameters.
    pub robot Parametric;
    gravity = [0.0, 0.0, -9.81];
    param m = 1.5;
    param cx = 0.2;
    param cy = -0.05;
    param cz = 0.03;
    param ixx = 0.02;
    param iyy = 0.03;
    param izz = 0.025;
    param ixy = 0.001;
    param ixz = -0.002;
    param iyz = 0.0015;
    param load = 0.4;
    link base;
    link l1 { mass = 2.0; com = [0.0, 0.0, 0.1]; inertia = [0.01, 0.01, 0.005]; }
    link l2 {
        mass = m; com = [cx, cy, cz]; inertia = [ixx, iyy, izz, ixy, ixz, iyz];
        point_mass tip = load at [0.4, 0.02, -0.01];
    }
    link l3 { mass = 0.7; com = [0.15, 0.0, 0.01]; inertia = [0.002, 0.004, 0.004, 0.0, 0.0005, 0.0]; }
    joint j1 = revolute(base -> l1) { axis = [0.0, 0.0, 1.0]; damping = 0.3; }
    joint j2 = revolute(l1 -> l2) { origin = [0.0, 0.05, 0.3]; rpy = [0.3, -0.2, 0.1]; axis = [0.0, 1.0, 0.0]; coulomb = 0.5; }
    joint j3 = prismatic(l2 -> l3) { origin = [0.4, 0.0, 0.0]; rpy = [0.0, 0.4, 0.0]; axis = [1.0, 0.0, 0.0]; spring = 20.0; }
}

#[test]
fn the_regressor_is_the_derivative_of_the_efforts_in_every_inertial_parameter() {
    let r = Parametric::default();
    check_random_states(&r, "parametric");
    for (k, p) in [
        "m", "cx", "cy", "cz", "ixx", "iyy", "izz", "ixy", "ixz", "iyz", "load",
    ]
    .iter()
    .enumerate()
    {
        check_sensitivity(&r, p, 100 + k as u64);
    }
    // The 10 x 10 map from (m, c, I_c) to pi_l2 is invertible, so the 10
    // checks above pin down all 10 columns of Y_l2.
}

#[test]
fn a_changed_mass_is_y_times_the_changed_parameters() {
    let r = Parametric::default();
    let mut heavier = r;
    heavier.params.m += 0.8;
    heavier.params.load += 0.3;
    let mut rng = Lcg(42);
    for _ in 0..20 {
        let (q, qd, qdd) = (rng.vector(3.0), rng.vector(2.0), rng.vector(5.0));
        let y = regressor(&r, &q, &qd, &qdd);
        // The regressor does not depend on mass properties.
        let y2 = regressor(&heavier, &q, &qd, &qdd);
        assert!(y.iter().zip(&y2).all(|(a, b)| a == b));
        let want = rigid(&heavier, &q, &qd, &qdd);
        let got = y_pi(&y, &parameters(&heavier));
        assert!((got - want).abs().max() <= 1e-10 * (1.0 + want.abs().max()));
    }
}

#[test]
fn point_masses_and_payloads_are_part_of_their_links_parameters() {
    check_sensitivity(&robots::Rrp::rigid(), "m", 5);
    check_sensitivity(&robots::PandaPayload::default(), "payload", 6);
}

dynamics_macros::robot! {
    /// A planar 2R arm through the elementary planar matrices.
    pub robot Planar;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link a { mass = 1.2; com = [0.3, 0.02, 0.0]; inertia = [0.001, 0.05, 0.06]; }
    link b { mass = 0.9; com = [0.25, -0.01, 0.0]; inertia = [0.001, 0.03, 0.035]; }
    joint j1 = revolute(base -> a) { transfer = [rot(q)]; }
    joint j2 = revolute(a -> b) { transfer = [tu(0.6), rot(q)]; }
}

dynamics_macros::robot! {
    /// The same arm through general planar matrices that move with q:
    /// the Newton-Euler pass does not take these, the regressor comes from
    /// the body Jacobians and their derivatives.
    pub robot PlanarMatrix;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link a { mass = 1.2; com = [0.3, 0.02, 0.0]; inertia = [0.001, 0.05, 0.06]; }
    link b { mass = 0.9; com = [0.25, -0.01, 0.0]; inertia = [0.001, 0.03, 0.035]; }
    joint j1 = revolute(base -> a) { transfer = [matrix([[cos(q), -sin(q), 0.0], [sin(q), cos(q), 0.0], [0.0, 0.0, 1.0]])]; }
    joint j2 = revolute(a -> b) { transfer = [matrix([[cos(q), -sin(q), 0.6], [sin(q), cos(q), 0.0], [0.0, 0.0, 1.0]])]; }
}

#[test]
fn general_moving_matrices_give_the_same_regressor() {
    let (r, m) = (Planar::default(), PlanarMatrix::default());
    check_random_states(&m, "planar-matrix");
    let mut rng = Lcg(3);
    for _ in 0..20 {
        let (q, qd, qdd) = (rng.vector(3.0), rng.vector(2.0), rng.vector(5.0));
        let (a, b) = (regressor(&r, &q, &qd, &qdd), regressor(&m, &q, &qd, &qdd));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs().max() < 1e-11, "{x} vs {y}");
        }
    }
}
