//! The per-state figures of `benches/batch.rs` measured for a loaded
//! machine: each round runs every variant (the scalar methods called once
//! per state, then the batch function at each lane level this CPU has) on
//! the same 1000 states once, in turn, timed in thread CPU time
//! (`support/cpu_time.rs`); a figure is the minimum over the rounds (the
//! run least disturbed by other processes sharing the core's caches and
//! its sibling thread), beside the median. Interleaving the variants
//! exposes them to the same load, so their ratios hold better than those
//! of runs taken one after the other.
//!
//! Run: `taskset -c 1 cargo bench -p robots --bench batch_min` (rounds:
//! `BATCH_MIN_ROUNDS`, default 200).

use std::hint::black_box;

use dynamics_runtime::batch::{self, Level};
use dynamics_runtime::{linearize, Robot};
use nalgebra::SVector;
use rustix::time::{clock_gettime, ClockId};

#[path = "support/states.rs"]
mod states;
use states::{states, STATES};

fn now_ns() -> u64 {
    let t = clock_gettime(ClockId::ThreadCPUTime);
    t.tv_sec as u64 * 1_000_000_000 + t.tv_nsec as u64
}

/// One timed variant: a name and the work of one run over the states.
type Variant<'a> = (String, Box<dyn FnMut() + 'a>);

fn report(robot: &str, output: &str, variants: &mut [Variant<'_>], rounds: usize) {
    let mut times = vec![Vec::with_capacity(rounds); variants.len()];
    for (_, run) in variants.iter_mut() {
        run(); // warm-up
    }
    for _ in 0..rounds {
        for (k, (_, run)) in variants.iter_mut().enumerate() {
            let t0 = now_ns();
            run();
            times[k].push(now_ns().saturating_sub(t0));
        }
    }
    let per_state = |t: u64| t as f64 / STATES as f64;
    let mut scalar_min = f64::NAN;
    for (k, (name, _)) in variants.iter().enumerate() {
        let t = &mut times[k];
        t.sort_unstable();
        let (min, median) = (per_state(t[0]), per_state(t[t.len() / 2]));
        if k == 0 {
            scalar_min = min;
        }
        println!(
            "{robot:6} {output:30} {name:8} min {min:8.1} ns/state  median {median:8.1}  scalar/this (min) {:5.2}",
            scalar_min / min
        );
    }
}

fn levels() -> Vec<Level> {
    let best = Level::detect();
    [Level::Scalar, Level::Avx2, Level::Avx512]
        .into_iter()
        .filter(|l| *l <= best)
        .collect()
}

fn bench_robot<R: Robot<N>, const N: usize>(name: &str, r: &R, rounds: usize) {
    let [q, v, a] = states::<N>();
    let (q, v, a) = (&q, &v, &a);

    let tau = std::cell::RefCell::new(vec![SVector::<f64, N>::zeros(); STATES]);
    let mut vs: Vec<Variant<'_>> = vec![(
        "calls".into(),
        Box::new(|| {
            let mut tau = tau.borrow_mut();
            for k in 0..STATES {
                tau[k] = r.inverse_dynamics(black_box(&q[k]), &v[k], &a[k]);
            }
            black_box(&*tau);
        }),
    )];
    for l in levels() {
        let tau = &tau;
        vs.push((
            format!("{l:?}"),
            Box::new(move || {
                let mut tau = tau.borrow_mut();
                let done = batch::inverse_dynamics(r, l, black_box(q), v, a, &mut tau);
                black_box((done.is_ok(), &*tau));
            }),
        ));
    }
    report(name, "inverse_dynamics", &mut vs, rounds);

    let m = std::cell::RefCell::new(vec![nalgebra::SMatrix::<f64, N, N>::zeros(); STATES]);
    let mut vs: Vec<Variant<'_>> = vec![(
        "calls".into(),
        Box::new(|| {
            let mut m = m.borrow_mut();
            for k in 0..STATES {
                m[k] = r.mass_matrix(black_box(&q[k]));
            }
            black_box(&*m);
        }),
    )];
    for l in levels() {
        let m = &m;
        vs.push((
            format!("{l:?}"),
            Box::new(move || {
                let mut m = m.borrow_mut();
                let done = batch::mass_matrix(r, l, black_box(q), &mut m);
                black_box((done.is_ok(), &*m));
            }),
        ));
    }
    report(name, "mass_matrix", &mut vs, rounds);

    let kd = std::cell::RefCell::new(vec![r.perturbation_jacobians(&q[0], &v[0], &a[0]); STATES]);
    let mut vs: Vec<Variant<'_>> = vec![(
        "calls".into(),
        Box::new(|| {
            let mut kd = kd.borrow_mut();
            for k in 0..STATES {
                kd[k] = r.perturbation_jacobians(black_box(&q[k]), &v[k], &a[k]);
            }
            black_box(&*kd);
        }),
    )];
    for l in levels() {
        let kd = &kd;
        vs.push((
            format!("{l:?}"),
            Box::new(move || {
                let mut kd = kd.borrow_mut();
                let done = batch::perturbation_jacobians(r, l, black_box(q), v, a, &mut kd);
                black_box((done.is_ok(), &*kd));
            }),
        ));
    }
    report(name, "perturbation_jacobians", &mut vs, rounds);

    let Ok(first) = linearize::forward_dynamics_derivatives(r, &q[0], &v[0], &a[0]) else {
        return;
    };
    let fd = std::cell::RefCell::new(vec![first; STATES]);
    let mut vs: Vec<Variant<'_>> = vec![(
        "calls".into(),
        Box::new(|| {
            let mut fd = fd.borrow_mut();
            for k in 0..STATES {
                if let Ok(d) =
                    linearize::forward_dynamics_derivatives(r, black_box(&q[k]), &v[k], &a[k])
                {
                    fd[k] = d;
                }
            }
            black_box(&*fd);
        }),
    )];
    for l in levels() {
        let fd = &fd;
        vs.push((
            format!("{l:?}"),
            Box::new(move || {
                let mut fd = fd.borrow_mut();
                let done = batch::forward_dynamics_derivatives(r, l, black_box(q), v, a, &mut fd);
                black_box((done.is_ok(), &*fd));
            }),
        ));
    }
    report(name, "forward_dynamics_derivatives", &mut vs, rounds);
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is read.
    let rounds = std::env::var("BATCH_MIN_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    bench_robot("panda", &robots::Panda::rigid(), rounds);
    bench_robot("ur5", &robots::Ur5::default(), rounds);
}
