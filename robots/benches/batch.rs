//! Per-state cost of the batch functions (`dynamics_runtime::batch`) on
//! 1000 states, at each lane level this CPU has, beside the scalar methods
//! called once per state: in thread CPU time (`support/cpu_time.rs`), each
//! figure the time of the whole batch (divide by 1000 for a state).
//! Run: `taskset -c 1 cargo bench -p robots --bench batch`; for the
//! baseline-x86-64 build: `RUSTFLAGS= taskset -c 1 cargo bench -p robots
//! --bench batch` (the run-time CPU check still picks AVX2 or AVX-512).

use std::hint::black_box;

use criterion::measurement::Measurement;
use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_runtime::batch::{self, Level};
use dynamics_runtime::{linearize, Robot};
use nalgebra::SVector;

#[path = "support/cpu_time.rs"]
mod cpu_time;
#[path = "support/states.rs"]
mod states;
use states::{states, STATES};

fn bench_robot<R: Robot<N>, const N: usize, M: Measurement>(
    c: &mut Criterion<M>,
    name: &str,
    r: &R,
) {
    let [q, v, a] = states::<N>();
    let best = Level::detect();
    let levels: Vec<Level> = [Level::Scalar, Level::Avx2, Level::Avx512]
        .into_iter()
        .filter(|l| *l <= best)
        .collect();
    let mut group = c.benchmark_group(format!("{name} x{STATES}"));
    let mut tau = vec![SVector::<f64, N>::zeros(); STATES];
    group.bench_function("inverse_dynamics: scalar calls", |b| {
        b.iter(|| {
            for k in 0..STATES {
                tau[k] = r.inverse_dynamics(black_box(&q[k]), &v[k], &a[k]);
            }
            black_box(&tau);
        })
    });
    for &l in &levels {
        group.bench_function(format!("inverse_dynamics: batch {l:?}"), |b| {
            b.iter(|| {
                let done = batch::inverse_dynamics(r, l, black_box(&q), &v, &a, &mut tau);
                black_box((done.is_ok(), &tau));
            })
        });
    }
    let mut m = vec![nalgebra::SMatrix::<f64, N, N>::zeros(); STATES];
    group.bench_function("mass_matrix: scalar calls", |b| {
        b.iter(|| {
            for k in 0..STATES {
                m[k] = r.mass_matrix(black_box(&q[k]));
            }
            black_box(&m);
        })
    });
    for &l in &levels {
        group.bench_function(format!("mass_matrix: batch {l:?}"), |b| {
            b.iter(|| {
                let done = batch::mass_matrix(r, l, black_box(&q), &mut m);
                black_box((done.is_ok(), &m));
            })
        });
    }
    let mut kd = vec![r.perturbation_jacobians(&q[0], &v[0], &a[0]); STATES];
    group.bench_function("perturbation_jacobians: scalar calls", |b| {
        b.iter(|| {
            for k in 0..STATES {
                kd[k] = r.perturbation_jacobians(black_box(&q[k]), &v[k], &a[k]);
            }
            black_box(&kd);
        })
    });
    for &l in &levels {
        group.bench_function(format!("perturbation_jacobians: batch {l:?}"), |b| {
            b.iter(|| {
                let done = batch::perturbation_jacobians(r, l, black_box(&q), &v, &a, &mut kd);
                black_box((done.is_ok(), &kd));
            })
        });
    }
    let Ok(first) = linearize::forward_dynamics_derivatives(r, &q[0], &v[0], &a[0]) else {
        return;
    };
    let mut fd = vec![first; STATES];
    group.bench_function("forward_dynamics_derivatives: scalar calls", |b| {
        b.iter(|| {
            for k in 0..STATES {
                if let Ok(d) =
                    linearize::forward_dynamics_derivatives(r, black_box(&q[k]), &v[k], &a[k])
                {
                    fd[k] = d;
                }
            }
            black_box(&fd);
        })
    });
    for &l in &levels {
        group.bench_function(format!("forward_dynamics_derivatives: batch {l:?}"), |b| {
            b.iter(|| {
                let done =
                    batch::forward_dynamics_derivatives(r, l, black_box(&q), &v, &a, &mut fd);
                black_box((done.is_ok(), &fd));
            })
        });
    }
    group.finish();
}

fn arms(c: &mut Criterion<cpu_time::ThreadCpuTime>) {
    bench_robot(c, "panda", &robots::Panda::rigid());
    bench_robot(c, "ur5", &robots::Ur5::default());
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .with_measurement(cpu_time::ThreadCpuTime)
        .sample_size(20)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = arms
}
criterion_main!(benches);
