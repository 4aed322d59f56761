//! A diagnosis that evaluates the model along each record a few samples at
//! a time (and holds the link columns' regressors a chunk at a time) names
//! the same effects with the same parameters as one that evaluates each
//! record whole: the chunked path of long logs (issue 31), checked on
//! short data.

use dynamics_sim2real::diagnose::{diagnose, Options, Report};
use dynamics_sim2real::synth::{
    draw_compound, synthesize, CompoundCase, ExcitationKind, Noise, Rng, SynthOptions,
};
use nalgebra::SVector;
use robots::Panda;

/// Each effect: kind, place, and its parameters' values and spreads.
type Named = Vec<(String, String, Vec<(f64, f64)>)>;

fn named(r: &Report) -> Named {
    r.which
        .effects
        .iter()
        .map(|e| {
            (
                e.kind.to_string(),
                e.joint.clone().or(e.point.clone()).unwrap_or_default(),
                e.parameters.iter().map(|p| (p.value, p.std)).collect(),
            )
        })
        .collect()
}

#[test]
fn a_diagnosis_in_small_chunks_equals_one_of_whole_records() {
    let robot = Panda::default();
    let m = robots::builtin::motion("panda");
    let opts = SynthOptions::<7> {
        duration: 3.0,
        excitation: ExcitationKind::Sines,
        home: SVector::from_fn(|k, _| m.home[k]),
        amplitude: SVector::from_fn(|k, _| m.amplitude[k]),
        noise: Noise {
            q: 2e-5,
            qd: 2e-3,
            tau_relative: 2e-3,
        },
        seed: 3131,
        ..Default::default()
    };
    let effects = draw_compound(&robot, CompoundCase::RealisticArm, &opts, &mut Rng::new(31));
    let train = synthesize(&robot, &effects, &opts).expect("a stable run");
    let hold = SynthOptions {
        seed: 3132,
        ..opts.clone()
    };
    let holdout = synthesize(&robot, &effects, &hold).expect("a stable run");
    let run = |chunk: usize| {
        let options = Options {
            chunk,
            ..Options::default()
        };
        diagnose(&robot, &train, &holdout, &options, &|_, _| {}).expect("a report")
    };
    // Whole records against chunks of 5 samples: far shorter than a row's
    // smoothing window (81 samples at 1 kHz), so every window straddles
    // chunks, and not a divisor of the record's length.
    let (whole, small) = (run(usize::MAX), run(5));
    let (a, b) = (named(&whole), named(&small));
    assert!(!a.is_empty());
    assert_eq!(a.len(), b.len(), "{a:?}\n{b:?}");
    for (x, y) in a.iter().zip(&b) {
        assert_eq!((&x.0, &x.1), (&y.0, &y.1), "{a:?}\n{b:?}");
        for ((v, s), (w, t)) in x.2.iter().zip(&y.2) {
            let close = |p: f64, q: f64| (p - q).abs() <= 1e-9 * p.abs().max(q.abs()).max(1e-12);
            assert!(close(*v, *w) && close(*s, *t), "{x:?} {y:?}");
        }
    }
    assert_eq!(whole.which.verdict.kind, small.which.verdict.kind);
    let ranked = |r: &Report| -> Vec<String> {
        r.which
            .ranked
            .iter()
            .map(|c| format!("{} {:?} {:?}", c.kind, c.joint, c.point))
            .collect()
    };
    assert_eq!(ranked(&whole), ranked(&small));
    let close = |p: f64, q: f64| (p - q).abs() <= 1e-9 * p.abs().max(q.abs()).max(1e-12);
    assert!(close(whole.shrink.fraction, small.shrink.fraction));
}
