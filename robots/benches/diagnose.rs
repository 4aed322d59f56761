//! The whole gap diagnosis on 8 s of 1 kHz data (training and held-out
//! files of 8001 samples each, generated in the setup by `robots::builtin::synth`
//! with Coulomb friction withheld at one joint): every candidate of the
//! vocabulary on every joint fitted and ranked, the where and shrink
//! sections, on all cores. Robots: arm3r (3 joints), UR5 (6) and Panda (7).
//! Target (issue 7): at most 2 s on the 2-core machine.
//! Run: `cargo bench -p robots --bench diagnose`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_cli::gap::SynthRequest;
use dynamics_runtime::Robot;
use dynamics_sim2real::data::{read_csv_str, Measured};
use dynamics_sim2real::diagnose::{diagnose, Options};
use dynamics_sim2real::effects::EffectKind;
use robots::builtin::synth;
use robots::{Arm3r, Panda, Ur5};

/// Training and held-out data of `robot` with Coulomb friction at `joint`.
fn data<R: Robot<N>, const N: usize>(robot: &str, joint: &str) -> (Measured<N>, Measured<N>) {
    let out = synth(&SynthRequest {
        robot: robot.into(),
        kind: Some(EffectKind::CoulombFriction),
        joint: Some(joint.into()),
        magnitude: None,
        seed: 3,
        excitation: "sines".parse().expect("an excitation"),
        duration: 8.0,
        noise: Default::default(),
    })
    .expect("synthesised");
    let read = |text: &str, file: &str| read_csv_str(text, &R::JOINT_NAMES, file).expect("CSV");
    (read(&out.train, "train"), read(&out.holdout, "holdout"))
}

fn case<R: Robot<N> + Clone + Sync, const N: usize>(
    c: &mut Criterion,
    name: &str,
    robot: &R,
    joint: &str,
) {
    let (train, holdout) = data::<R, N>(name, joint);
    let options = Options::default();
    let report = diagnose(robot, &train, &holdout, &options, &|_, _| {}).expect("enough data");
    eprintln!(
        "{name}: {} + {} samples, {} candidates ranked, verdict {} {}",
        train.len(),
        holdout.len(),
        report.which.ranked.len(),
        report.which.verdict.kind,
        report.which.verdict.joint.clone().unwrap_or_default()
    );
    let mut group = c.benchmark_group("diagnose 8 s at 1 kHz");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(15));
    group.bench_function(name, |b| {
        b.iter(|| {
            diagnose(
                black_box(robot),
                black_box(&train),
                black_box(&holdout),
                &options,
                &|_, _| {},
            )
        })
    });
    group.finish();
}

fn diagnosis(c: &mut Criterion) {
    case(c, "arm3r", &Arm3r::default(), "j2");
    case(c, "ur5", &Ur5::default(), "shoulder_lift_joint");
    case(c, "panda", &Panda::default(), "panda_joint4");
}

criterion_group!(benches, diagnosis);
criterion_main!(benches);
