//! Real logs as they come (issue 15): jittered clocks, repeated samples,
//! holes, glitches, slow rates, unexcited and mislabelled data.

use dynamics_runtime::Robot;
use dynamics_sim2real::data::{read_csv_str, write_csv, Measured};
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, Damage, SynthOptions};
use robots::Arm3r;

const JOINTS: [&str; 3] = ["j1", "j2", "j3"];

fn arm() -> Arm3r {
    Arm3r::default()
}

fn opts(seed: u64, rate: f64, damage: Damage) -> SynthOptions<3> {
    SynthOptions {
        duration: 6.0,
        rate,
        home: [0.0, 0.4, -0.4].into(),
        amplitude: [0.6, 0.6, 0.6].into(),
        seed,
        damage,
        ..Default::default()
    }
}

fn csv(m: &Measured<3>) -> String {
    let mut out = Vec::new();
    write_csv(&mut out, m, &JOINTS).expect("writes");
    String::from_utf8(out).expect("utf8")
}

fn run(effects: &[Effect], rate: f64, damage: Damage, seed: u64) -> Report {
    let robot = arm();
    let a = synthesize(&robot, effects, &opts(seed, rate, damage)).expect("synth");
    let b = synthesize(&robot, effects, &opts(seed + 1, rate, damage)).expect("synth");
    let a = read_csv_str(&csv(&a), &JOINTS, "train.csv").expect("reads");
    let b = read_csv_str(&csv(&b), &JOINTS, "holdout.csv").expect("reads");
    diagnose(&robot, &a, &b, &Options::default(), &|_, _| {}).expect("diagnoses")
}

#[test]
fn explore() {
    let _ = Arm3r::NAME;
    for (name, damage, rate) in [
        ("clean", Damage::default(), 1000.0),
        (
            "jitter",
            Damage {
                jitter: 0.3,
                ..Damage::default()
            },
            1000.0,
        ),
        (
            "repeats",
            Damage {
                repeats: 0.056,
                ..Damage::default()
            },
            1000.0,
        ),
        (
            "holes",
            Damage {
                holes: 2,
                ..Damage::default()
            },
            1000.0,
        ),
        (
            "glitches",
            Damage {
                glitches: 3,
                ..Damage::default()
            },
            1000.0,
        ),
        ("100 Hz", Damage::default(), 100.0),
        (
            "100 Hz jitter",
            Damage {
                jitter: 0.3,
                ..Damage::default()
            },
            100.0,
        ),
    ] {
        for effects in [vec![], vec![Effect::CoulombFriction { joint: 1, fc: 0.3 }]] {
            let r = run(&effects, rate, damage, 5);
            let v = &r.which.verdict;
            eprintln!(
                "{name:14} {:?} -> {} {:?} {:?} shrink {:.2} ratios {:?}",
                effects.first().map(|e| e.kind().name()),
                v.kind,
                v.joint,
                v.status,
                r.shrink.fraction,
                r.where_
                    .joints
                    .iter()
                    .map(|j| (j.torque_ratio * 100.0).round() / 100.0)
                    .collect::<Vec<_>>()
            );
            for w in &r.warnings {
                eprintln!("    {w}");
            }
        }
    }
}
