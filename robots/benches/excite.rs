//! Designing an exciting motion (`dynamics_sim2real::excite::design`, issue
//! 28): 20 s for the Panda (7 joints, 69 base parameters with friction,
//! rotor inertia and offsets) within its URDF limits, the default options
//! (5 harmonics, period 5 s, 2000 evaluations of the criterion), on all
//! cores. Target: under 60 s on the 2-core machine.
//! Run: `cargo bench -p robots --bench excite`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_cli::excite::limits;
use dynamics_sim2real::excite::{design, Options};
use robots::registry::AnyRobot;
use robots::Panda;

fn excite(c: &mut Criterion) {
    let robot = Panda::rigid();
    let lim = limits::<7>(
        AnyRobot::by_name("panda").expect("panda").limits().as_ref(),
        &robots::builtin::motion("panda"),
    );
    let options = Options::new(20.0);
    let d = design(&robot, &lim, &options).expect("a design");
    eprintln!(
        "panda 20 s: condition number {:.2}, {} evaluations",
        d.figures.condition, d.evaluations
    );
    let mut group = c.benchmark_group("excite");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(30));
    group.bench_function("panda 20 s", |b| {
        b.iter(|| design(black_box(&robot), black_box(&lim), &options))
    });
    group.finish();
}

criterion_group!(benches, excite);
criterion_main!(benches);
