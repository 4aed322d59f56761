//! A diagnosis that evaluates the model along each record a few samples at
//! a time (and holds the link columns' regressors a chunk at a time) names
//! the same effects with the same parameters as one that evaluates each
//! record whole: the chunked path of long logs (issue 31), checked on
//! short data. And the column cache, which keeps the friction laws and
//! the smoothed accelerations at the fit's rows and recomputes them a
//! chunk at a time elsewhere, gives every candidate's columns at every
//! sample as when each record is one chunk.

use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::{diagnose, Candidate, Options, Prepared, Report};
use dynamics_sim2real::effects::SIGN_SMOOTHING;
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

/// A compound Panda case (friction on every joint among its effects):
/// training and held-out records of 3 s at 1 kHz.
fn records() -> (Measured<7>, Measured<7>) {
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
    (train, holdout)
}

#[test]
fn a_diagnosis_in_small_chunks_equals_one_of_whole_records() {
    let robot = Panda::default();
    let (train, holdout) = records();
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

/// Whether `c`'s columns are built from the signals alone.
fn from_signals(c: &Candidate) -> bool {
    matches!(
        c,
        Candidate::Viscous(_)
            | Candidate::Armature(_)
            | Candidate::Coulomb(..)
            | Candidate::Stribeck(..)
    )
}

/// Every column a correction along the whole record reads, at every
/// sample of the record, in chunks of 5 samples and 4096 against the
/// record as one chunk: the same to the bit (the rows hold the stored
/// values, the other samples recomputed ones; the friction laws' running
/// integrals are carried across every chunk's start).
#[test]
fn columns_at_every_sample_do_not_depend_on_the_chunk() {
    let robot = Panda::default();
    let (train, _) = records();
    let whole = Prepared::chunked(&robot, &train, None, usize::MAX);
    let mut candidates = vec![Candidate::Payload, Candidate::LatePositions];
    for j in 0..7 {
        candidates.push(Candidate::Viscous(j));
        candidates.push(Candidate::Armature(j));
        candidates.push(Candidate::EncoderOffset(j));
        for w in [SIGN_SMOOTHING, 0.05, 0.15] {
            candidates.push(Candidate::Coulomb(j, w));
        }
        for vs in [0.01, 0.03, 0.1, 0.3] {
            candidates.push(Candidate::Stribeck(j, vs));
        }
    }
    let (a, z) = whole.sig.range;
    let mut moving = 0usize;
    for chunk in [5, 4096] {
        let p = Prepared::chunked(&robot, &train, None, chunk);
        assert_eq!(p.rows, whole.rows);
        for c in &candidates {
            for k in a..z {
                let x = c.columns(&whole.sig, &whole.basis, k);
                let y = c.columns(&p.sig, &p.basis, k);
                for (u, v) in x.iter().zip(&y) {
                    for (s, t) in u.iter().zip(v.iter()) {
                        // The friction laws and the accelerations come
                        // from the signals by the same operations: to the
                        // bit. The model's outputs (K, the tip's motion)
                        // come from its batch evaluation, which may group
                        // the samples of a chunk differently: to rounding.
                        let same = if from_signals(c) {
                            s.to_bits() == t.to_bits()
                        } else {
                            (s - t).abs() <= 1e-12 * s.abs().max(t.abs()).max(1.0)
                        };
                        assert!(same, "{c:?}, chunk {chunk}, sample {k}: {s} against {t}");
                        moving += usize::from(s.abs() > 1e-3);
                    }
                }
            }
        }
    }
    // Not a comparison of zeros.
    assert!(moving > (z - a) * candidates.len() / 2, "{moving}");
}
