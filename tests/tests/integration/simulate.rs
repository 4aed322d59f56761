//! Integration: energy conservation of the robots of the source works under DOPRI5, RK4's
//! order of convergence, event location, divergence errors.

use dynamics_runtime::ode::{locate_event, rk4_step, Dopri5, JointState, Tolerances};
use dynamics_runtime::{simulate, Robot, SimError};
use nalgebra::{SVector, Vector2, Vector3};

/// Free motion, no damping, no input: T + V is conserved.
fn energy_drift<R: Robot<3>>(r: &R, q0: Vector3<f64>) -> f64 {
    let tol = Tolerances {
        rtol: 1e-12,
        atol: 1e-12,
        ..Default::default()
    };
    let tr = simulate(
        r,
        q0,
        Vector3::zeros(),
        |_, _, _| Vector3::zeros(),
        10.0,
        0.05,
        tol,
    )
    .expect("simulates");
    let e0 = r.total_energy(&tr.q[0], &tr.qd[0]);
    let scale =
        tr.q.iter()
            .zip(&tr.qd)
            .map(|(q, qd)| r.kinetic_energy(q, qd))
            .fold(e0.abs(), f64::max);
    tr.q.iter()
        .zip(&tr.qd)
        .map(|(q, qd)| (r.total_energy(q, qd) - e0).abs() / scale)
        .fold(0.0, f64::max)
}

#[test]
fn energy_is_conserved_to_1e9_over_10_s() {
    let arm = energy_drift(&robots::Arm3r::default(), Vector3::new(0.3, -0.5, 0.8));
    let rrp = energy_drift(&robots::Rrp::rigid(), Vector3::new(0.2, 0.4, 0.1));
    let mar = energy_drift(&robots::Mar::default(), Vector3::new(0.3, 0.6, 0.05));
    for (name, d) in [("arm3r", arm), ("rrp", rrp), ("mar", mar)] {
        assert!(d <= 1e-9, "{name}: relative drift of T + V {d:e}");
    }
}

#[test]
fn damping_dissipates() {
    let r = robots::Arm3r::new(robots::Arm3rParams {
        m: 2.0,
        b1: 1.0,
        b2: 1.0,
        b3: 1.0,
    });
    let tr = simulate(
        &r,
        Vector3::new(0.3, -0.5, 0.8),
        Vector3::zeros(),
        |_, _, _| Vector3::zeros(),
        3.0,
        0.01,
        Tolerances::default(),
    )
    .expect("simulates");
    let e: Vec<f64> =
        tr.q.iter()
            .zip(&tr.qd)
            .map(|(q, qd)| r.total_energy(q, qd))
            .collect();
    assert!(
        e.windows(2).all(|w| w[1] <= w[0] + 1e-9),
        "energy never grows"
    );
    assert!(e[e.len() - 1] < e[0] - 1.0, "and it drops");
}

#[test]
fn rk4_converges_with_order_4() {
    // x'' = -x, x(0) = 1: x(1) = cos 1.
    let mut f = |_t: f64, y: &Vector2<f64>| Ok::<_, ()>(Vector2::new(y[1], -y[0]));
    let mut err = |steps: usize| {
        let h = 1.0 / steps as f64;
        let mut y = Vector2::new(1.0, 0.0);
        for k in 0..steps {
            y = rk4_step(&mut f, k as f64 * h, &y, h).expect("no error");
        }
        (y[0] - 1.0f64.cos()).abs()
    };
    let (e1, e2, e3) = (err(10), err(20), err(40));
    let order = ((e1 / e2).log2() + (e2 / e3).log2()) / 2.0;
    assert!((order - 4.0).abs() < 0.1, "measured order {order}");
}

#[test]
fn events_are_located_on_the_dense_output() {
    // x = cos t crosses zero at pi/2.
    let mut f = |_t: f64, y: &Vector2<f64>| Ok::<_, ()>(Vector2::new(y[1], -y[0]));
    let tol = Tolerances {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    };
    let mut ode = Dopri5::new(0.0, Vector2::new(1.0, 0.0), tol);
    let mut found = None;
    let mut g = |_t: f64, y: &Vector2<f64>| y[0];
    ode.run(&mut f, 3.0, |step| {
        let (g0, g1) = (step.y0[0], step.y1[0]);
        if g0 > 0.0 && g1 <= 0.0 {
            found = Some(locate_event(step, &mut g, g0, g1, 1e-13));
            return false;
        }
        true
    })
    .expect("integrates");
    let t = found.expect("an event");
    assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{t}");
}

#[test]
fn divergence_is_an_error_that_says_when_and_where() {
    let r = robots::Arm3r::default();
    let err = simulate(
        &r,
        Vector3::zeros(),
        Vector3::zeros(),
        |t, _, _| {
            if t > 0.5 {
                Vector3::new(0.0, f64::NAN, 0.0)
            } else {
                Vector3::zeros()
            }
        },
        1.0,
        0.1,
        Tolerances::default(),
    )
    .expect_err("a NaN input must stop the run");
    match err {
        SimError::Input { t, joint } => {
            assert!(t > 0.5 && t < 0.7, "{t}");
            assert_eq!(joint, "j2");
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(simulate(
        &r,
        Vector3::zeros(),
        Vector3::zeros(),
        |_, _, _| Vector3::zeros(),
        -1.0,
        0.1,
        Tolerances::default()
    )
    .is_err());
    let _ = JointState::<3> {
        q: SVector::zeros(),
        qd: SVector::zeros(),
    };
}

#[test]
fn csv_has_the_design_columns() {
    let r = robots::Mar::default();
    let tr = simulate(
        &r,
        Vector3::zeros(),
        Vector3::zeros(),
        |_, _, _| Vector3::zeros(),
        0.1,
        0.01,
        Tolerances::default(),
    )
    .expect("simulates");
    let mut out = Vec::new();
    tr.write_csv(&mut out, &robots::Mar::JOINT_NAMES)
        .expect("writes");
    let text = String::from_utf8(out).expect("utf8");
    let header = text.lines().next().expect("header");
    assert!(header.starts_with("t,q_q1,q_q2,q_q3,qd_q1"), "{header}");
    assert_eq!(text.lines().count(), 12);
}

#[test]
fn linearised_response_matches_the_nonlinear_one_to_second_order() {
    use dynamics_runtime::perturbation_response;
    let r = robots::Arm3r::new(robots::Arm3rParams {
        m: 2.0,
        b1: 1.0,
        b2: 1.0,
        b3: 1.0,
    });
    let tol = Tolerances {
        rtol: 1e-11,
        atol: 1e-13,
        ..Default::default()
    };
    let u = |t: f64, _: &Vector3<f64>, _: &Vector3<f64>| {
        Vector3::new(20.0 + t.sin(), 8.0 * t.cos(), 2.0)
    };
    let pulse = |t: f64| {
        if t < 0.2 {
            Vector3::new(1.0, -0.5, 0.3)
        } else {
            Vector3::zeros()
        }
    };
    let q0 = Vector3::new(0.2, 0.3, -0.4);
    let zero = JointState {
        q: Vector3::zeros(),
        qd: Vector3::zeros(),
    };
    let lin = perturbation_response(&r, q0, Vector3::zeros(), u, pulse, zero, 1.0, 0.01, tol)
        .expect("linear");
    let err = |eps: f64| {
        let dist = simulate(
            &r,
            q0,
            Vector3::zeros(),
            |t, q, qd| u(t, q, qd) + pulse(t) * eps,
            1.0,
            0.01,
            tol,
        )
        .expect("nonlinear");
        dist.q
            .iter()
            .zip(&lin.nominal.q)
            .zip(&lin.dx)
            .map(|((qd, qn), dx)| (qd - qn - dx * eps).abs().max())
            .fold(0.0, f64::max)
    };
    let (e1, e2, e3) = (err(4e-2), err(2e-2), err(1e-2));
    let slope = ((e1 / e2).log2() + (e2 / e3).log2()) / 2.0;
    eprintln!("second-order check: errors {e1:e} {e2:e} {e3:e}, slope {slope}");
    assert!(
        (slope - 2.0).abs() < 0.2,
        "errors {e1:e} {e2:e} {e3:e}: slope {slope}"
    );
    assert!(
        lin.dx.iter().any(|d| d.abs().max() > 1e-3),
        "the pulse moves the arm"
    );
}
