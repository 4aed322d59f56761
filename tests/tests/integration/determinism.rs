//! The compound explanation does not hang on the last bits of a sum: the
//! same data diagnosed on one thread and on two, and with every effort
//! moved by a relative 1e-15 (about what fused multiply-adds change in the
//! model between a build for a CPU with FMA and one without,
//! `dynamics_runtime::fma`), name the same effects with the same
//! parameters to 1e-6.

use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::synth::{
    draw_compound, synthesize, CompoundCase, ExcitationKind, Noise, Rng, SynthOptions,
};
use nalgebra::SVector;
use robots::Panda;

fn named(r: &Report) -> Vec<(String, String, Vec<f64>)> {
    r.which
        .effects
        .iter()
        .map(|e| {
            (
                e.kind.to_string(),
                e.joint.clone().or(e.point.clone()).unwrap_or_default(),
                e.parameters.iter().map(|p| p.value).collect(),
            )
        })
        .collect()
}

#[test]
fn the_explanation_does_not_depend_on_threads_or_rounding() {
    let robot = Panda::default();
    let m = robots::builtin::motion("panda");
    let opts = SynthOptions::<7> {
        duration: 4.0,
        excitation: ExcitationKind::Sines,
        home: SVector::from_fn(|k, _| m.home[k]),
        amplitude: SVector::from_fn(|k, _| m.amplitude[k]),
        noise: Noise {
            q: 2e-5,
            qd: 2e-3,
            tau_relative: 2e-3,
        },
        seed: 4141,
        ..Default::default()
    };
    let mut rng = Rng::new(17);
    let effects = draw_compound(&robot, CompoundCase::RealisticArm, &opts, &mut rng);
    let train = synthesize(&robot, &effects, &opts).expect("a stable run");
    let holdout = synthesize(
        &robot,
        &effects,
        &SynthOptions {
            seed: 4142,
            ..opts.clone()
        },
    )
    .expect("a stable run");
    let run = |train: &Measured<7>, threads: usize| {
        let options = Options {
            threads,
            ..Options::default()
        };
        named(&diagnose(&robot, train, &holdout, &options, &|_, _| {}).expect("a report"))
    };
    let one = run(&train, 1);
    assert!(!one.is_empty());
    let mut nudged = train.clone();
    for (k, tau) in nudged.tau.iter_mut().enumerate() {
        for j in 0..7 {
            tau[j] *= 1.0 + if (k + j) % 2 == 0 { 1e-15 } else { -1e-15 };
        }
    }
    for other in [run(&train, 2), run(&nudged, 2)] {
        assert_eq!(other.len(), one.len(), "{one:?}\n{other:?}");
        for (a, b) in one.iter().zip(&other) {
            assert_eq!((&a.0, &a.1), (&b.0, &b.1), "{one:?}\n{other:?}");
            for (x, y) in a.2.iter().zip(&b.2) {
                assert!((x - y).abs() <= 1e-6 * x.abs().max(1e-3), "{a:?} {b:?}");
            }
        }
    }
}
