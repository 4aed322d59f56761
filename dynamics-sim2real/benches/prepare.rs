//! Reading and preparing a real log: 60 s at 1 kHz, 7 joints (positions,
//! velocities, efforts), from CSV text, on a clean clock and on a clock
//! with +-30 % jitter, 5 % repeated efforts and a few glitches (which takes
//! the grid path).

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_sim2real::data::read_csv_str;
use dynamics_sim2real::synth::Rng;

const JOINTS: [&str; 7] = ["j1", "j2", "j3", "j4", "j5", "j6", "j7"];

fn log(jitter: f64) -> String {
    let mut rng = Rng::new(42);
    let mut text = String::from("t");
    for p in ["q", "qd", "tau"] {
        for j in JOINTS {
            text.push_str(&format!(",{p}_{j}"));
        }
    }
    text.push('\n');
    let mut t = 0.0;
    let mut last_tau = [0.0; 7];
    for k in 0..60_000 {
        let mut row = format!("{t}");
        for j in 0..7 {
            let w = 1.0 + 0.3 * j as f64;
            row.push_str(&format!(",{}", 0.5 * (w * t).sin() + 2e-5 * rng.normal()));
        }
        for j in 0..7 {
            let w = 1.0 + 0.3 * j as f64;
            row.push_str(&format!(
                ",{}",
                0.5 * w * (w * t).cos() + 2e-3 * rng.normal()
            ));
        }
        for (j, last) in last_tau.iter_mut().enumerate() {
            let w = 1.0 + 0.3 * j as f64;
            let mut tau = 10.0 * (w * t).sin() + 0.02 * rng.normal();
            if jitter > 0.0 && k % 20 == 3 {
                tau = *last; // repeated
            }
            if jitter > 0.0 && k % 9973 == 500 {
                tau = 1e300;
            }
            *last = tau;
            row.push_str(&format!(",{tau}"));
        }
        text.push_str(&row);
        text.push('\n');
        t += 1e-3
            * if jitter > 0.0 {
                rng.uniform(1.0 - jitter, 1.0 + jitter)
            } else {
                1.0
            };
    }
    text
}

fn bench(c: &mut Criterion) {
    let clean = log(0.0);
    let rough = log(0.3);
    let mut g = c.benchmark_group("read_and_prepare_60s_1kHz_7_joints");
    g.sample_size(10);
    g.bench_function("clean", |b| {
        b.iter(|| read_csv_str::<7>(&clean, &JOINTS, "clean.csv").expect("reads"))
    });
    g.bench_function("jitter_repeats_glitches", |b| {
        b.iter(|| {
            let m = read_csv_str::<7>(&rough, &JOINTS, "rough.csv").expect("reads");
            assert!(m.warnings.len() >= 3);
            m
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
