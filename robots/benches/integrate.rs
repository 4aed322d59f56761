//! The runtime's Dormand-Prince 5(4) against the `ode_solvers` crate's on
//! the same problem (arm3r released from rest, 0.5 s, rtol 1e-8, atol 1e-10):
//! time per run, from which steps/s and right-hand-side evaluations/s
//! follow (the counts are printed once). Also the cost of one right-hand
//! side (forward dynamics). Run: `cargo bench -p robots --bench integrate`.

use std::cell::Cell;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_runtime::ode::{Dopri5, JointState, Tolerances};
use dynamics_runtime::Robot;
use nalgebra::Vector3;

const T_END: f64 = 0.5;
const RTOL: f64 = 1e-8;
const ATOL: f64 = 1e-10;

fn ours<R: Robot<3>>(r: &R, evals: &Cell<usize>) -> (usize, Vector3<f64>) {
    let x0 = JointState {
        q: Vector3::new(0.3, -0.5, 0.8),
        qd: Vector3::zeros(),
    };
    let tol = Tolerances {
        rtol: RTOL,
        atol: ATOL,
        ..Default::default()
    };
    let mut ode = Dopri5::new(0.0, x0, tol);
    let mut f = |_t: f64, x: &JointState<3>| {
        evals.set(evals.get() + 1);
        r.forward_dynamics(&x.q, &x.qd, &Vector3::zeros())
            .map(|qdd| JointState { q: x.qd, qd: qdd })
    };
    let mut steps = 0;
    ode.run(&mut f, T_END, |_| {
        steps += 1;
        true
    })
    .expect("integrates");
    (steps, ode.y().q)
}

struct Crate<'a, R> {
    robot: &'a R,
    evals: &'a Cell<usize>,
}

impl<R: Robot<3>> ode_solvers::System<f64, ode_solvers::Vector6<f64>> for Crate<'_, R> {
    fn system(&self, _t: f64, y: &ode_solvers::Vector6<f64>, dy: &mut ode_solvers::Vector6<f64>) {
        self.evals.set(self.evals.get() + 1);
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let qdd = self
            .robot
            .forward_dynamics(&q, &qd, &Vector3::zeros())
            .unwrap_or_else(|_| Vector3::repeat(f64::NAN));
        for i in 0..3 {
            dy[i] = qd[i];
            dy[i + 3] = qdd[i];
        }
    }
}

fn theirs<R: Robot<3>>(r: &R, evals: &Cell<usize>) -> (usize, f64) {
    let y0 = ode_solvers::Vector6::new(0.3, -0.5, 0.8, 0.0, 0.0, 0.0);
    let mut s =
        ode_solvers::Dopri5::new(Crate { robot: r, evals }, 0.0, T_END, 0.25, y0, RTOL, ATOL);
    let stats = s.integrate().expect("integrates");
    let last = s.y_out().last().map(|y| y[0]).unwrap_or(f64::NAN);
    if std::env::var_os("SHOW_OUTPUT").is_some() {
        eprintln!(
            "ode_solvers x_out = {:?}, y_out = {:?}",
            s.x_out(),
            s.y_out()
        );
    }
    (stats.accepted_steps as usize, last)
}

fn integrate(c: &mut Criterion) {
    // One robot today; the loop is where the next one goes.
    #[allow(clippy::single_element_loop)]
    for (name, robot) in [("arm3r", robots::Arm3r::default())] {
        let evals = Cell::new(0);
        let (steps, q) = ours(&robot, &evals);
        let ours_evals = evals.replace(0);
        let (their_steps, q1) = theirs(&robot, &evals);
        let their_evals = evals.replace(0);
        eprintln!(
            "{name}: ours {steps} steps, {ours_evals} rhs evaluations, q1(end) = {:.12}; ode_solvers {their_steps} steps, {their_evals} evaluations, q1(end) = {q1:.12}",
            q[0]
        );
        c.bench_function(&format!("{name}/dopri5 0.5 s (ours)"), |b| {
            b.iter(|| black_box(ours(&robot, &evals)))
        });
        c.bench_function(&format!("{name}/dopri5 0.5 s (ode_solvers)"), |b| {
            b.iter(|| black_box(theirs(&robot, &evals)))
        });
        c.bench_function(&format!("{name}/rhs (forward dynamics)"), |b| {
            let (q, qd, u) = (
                Vector3::new(0.3, -0.5, 0.8),
                Vector3::new(0.1, 0.2, 0.3),
                Vector3::zeros(),
            );
            b.iter(|| black_box(robot.forward_dynamics(black_box(&q), black_box(&qd), &u)))
        });
    }
    let mar = robots::Mar::default();
    c.bench_function("mar/rhs (forward dynamics)", |b| {
        let (q, qd, u) = (
            Vector3::new(0.3, -0.5, 0.1),
            Vector3::new(0.1, 0.2, 0.3),
            Vector3::zeros(),
        );
        b.iter(|| black_box(mar.forward_dynamics(black_box(&q), black_box(&qd), &u)))
    });
    let evals = Cell::new(0);
    let x0 = JointState {
        q: Vector3::new(0.3, -0.5, 0.05),
        qd: Vector3::zeros(),
    };
    c.bench_function("mar/dopri5 0.5 s (ours)", |b| {
        b.iter(|| {
            let mut ode = Dopri5::new(
                0.0,
                x0,
                Tolerances {
                    rtol: RTOL,
                    atol: ATOL,
                    ..Default::default()
                },
            );
            let mut f = |_t: f64, x: &JointState<3>| {
                evals.set(evals.get() + 1);
                mar.forward_dynamics(&x.q, &x.qd, &Vector3::zeros())
                    .map(|qdd| JointState { q: x.qd, qd: qdd })
            };
            ode.run(&mut f, T_END, |_| true).expect("integrates");
            black_box(ode.y().q)
        })
    });
}

criterion_group!(benches, integrate);
criterion_main!(benches);
