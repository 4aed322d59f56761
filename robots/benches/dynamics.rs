//! Time per call of the generated dynamics of the robots of the source works and the two
//! industrial arms, cycling over
//! 1000 pseudo-random states as the Pinocchio anchor does
//! (shared/anchors/pinocchio/bench.cpp), in thread CPU time as the anchors
//! measure (`support/cpu_time.rs`). Run: `cargo bench -p robots --bench dynamics`
//! (pinned like the anchors: `taskset -c 1 cargo bench ...`).

use std::hint::black_box;

use criterion::measurement::Measurement;
use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_runtime::{linearize, Robot};
use nalgebra::SVector;

/// The batch benches' states (`support/states.rs`), one `[q, v, a]` per
/// state.
fn states<const N: usize>() -> Vec<[SVector<f64, N>; 3]> {
    let [q, v, a] = states::states::<N>();
    q.into_iter()
        .zip(v)
        .zip(a)
        .map(|((q, v), a)| [q, v, a])
        .collect()
}

#[path = "support/cpu_time.rs"]
mod cpu_time;
#[path = "support/states.rs"]
mod states;
use states::STATES;

fn bench_robot<R: Robot<N>, const N: usize, M: Measurement>(
    c: &mut Criterion<M>,
    name: &str,
    r: &R,
) {
    let s = states::<N>();
    let mut group = c.benchmark_group(name);
    let mut k = 0usize;
    let mut next = || {
        k = (k + 1) % STATES;
        &s[k]
    };
    group.bench_function("mass_matrix", |b| {
        b.iter(|| {
            let [q, _, _] = next();
            black_box(r.mass_matrix(black_box(q)))
        })
    });
    group.bench_function("qqt1+qqt2", |b| {
        b.iter(|| {
            let [q, v, _] = next();
            black_box(r.qqt(black_box(q), black_box(v)))
        })
    });
    group.bench_function("gravity", |b| {
        b.iter(|| {
            let [q, _, _] = next();
            black_box(r.gravity(black_box(q)))
        })
    });
    group.bench_function("inverse_dynamics", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            black_box(r.inverse_dynamics(black_box(q), black_box(v), black_box(a)))
        })
    });
    group.bench_function("motion_terms (A+Qqt1+Qqt2+Q0)", |b| {
        b.iter(|| {
            let [q, v, _] = next();
            black_box(r.motion_terms(black_box(q), black_box(v)))
        })
    });
    group.bench_function("coriolis_matrix", |b| {
        b.iter(|| {
            let [q, v, _] = next();
            black_box(r.coriolis_matrix(black_box(q), black_box(v)))
        })
    });
    group.bench_function("perturbation_jacobians (dtau/dq, dtau/dqd)", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            black_box(r.perturbation_jacobians(black_box(q), black_box(v), black_box(a)))
        })
    });
    let mut y = vec![nalgebra::SMatrix::<f64, N, 10>::zeros(); R::LINK_NAMES.len()];
    group.bench_function("inertial_regressor", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            let done = r.inertial_regressor(black_box(q), black_box(v), black_box(a), &mut y);
            black_box(done.is_ok());
            black_box(&y);
        })
    });
    group.bench_function("forward_dynamics", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            black_box(r.forward_dynamics(black_box(q), black_box(v), black_box(a)))
        })
    });
    group.bench_function("forward_dynamics_derivatives (ddq/dq, ddq/dqd)", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            black_box(linearize::forward_dynamics_derivatives(
                r,
                black_box(q),
                black_box(v),
                black_box(a),
            ))
        })
    });
    group.bench_function("state_space (A_c, B_c)", |b| {
        b.iter(|| {
            let [q, v, a] = next();
            black_box(linearize::state_space(
                r,
                black_box(q),
                black_box(v),
                black_box(a),
            ))
        })
    });
    let models: Vec<_> = s
        .iter()
        .filter_map(|[q, v, a]| linearize::state_space(r, q, v, a).ok())
        .collect();
    let mut m = 0usize;
    group.bench_function("zero_order_hold (A_d, B_d, h = 1 ms)", |b| {
        b.iter(|| {
            m = (m + 1) % models.len();
            black_box(black_box(&models[m]).discretize(1e-3))
        })
    });
    group.finish();
}

fn seed_robots(c: &mut Criterion<cpu_time::ThreadCpuTime>) {
    bench_robot(c, "arm3r", &robots::Arm3r::default());
    bench_robot(c, "rrp", &robots::Rrp::rigid());
    bench_robot(c, "mar", &robots::Mar::default());
    bench_robot(c, "ur5", &robots::Ur5::default());
    bench_robot(c, "panda", &robots::Panda::rigid());
}

criterion_group! {
    name = benches;
    config = Criterion::default().with_measurement(cpu_time::ThreadCpuTime);
    targets = seed_robots
}
criterion_main!(benches);
