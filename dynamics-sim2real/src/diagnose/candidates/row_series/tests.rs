//! The series kept at the rows and recomputed in chunks elsewhere against
//! the same filters run over the whole record at once (what the column
//! cache held at every sample): equal to the bit at every sample, for
//! chunks shorter than the filter's window, odd-sized and longer than the
//! record, with measured velocities and without.

use super::*;
use crate::data::Measured;
use crate::diagnose::candidates::force_filter::through_motion;
use crate::effects::Effect;
use crate::synth::{synthesize, SynthOptions};

use crate::test_robots::Arm2;

fn record() -> Measured<2> {
    let friction = [Effect::StribeckFriction {
        joint: 0,
        fc: 0.5,
        fs: 0.8,
        vs: 0.03,
    }];
    let opts = SynthOptions {
        duration: 3.0,
        seed: 7,
        ..Default::default()
    };
    synthesize(&Arm2::default(), &friction, &opts).expect("a generated record")
}

/// The same value, or both not finite.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (!a.is_finite() && !b.is_finite())
}

#[test]
fn chunks_and_rows_give_the_whole_records_values() {
    for measured in [true, false] {
        let mut m = record();
        m.qd_measured = measured && m.qd_measured;
        let sig = Signals::unfloored(&Arm2::default(), &m);
        let n = sig.t.len();
        let (a, z) = sig.range;
        // The whole record's filters, as the column cache held them.
        let whole: Vec<Vec<Vec<f64>>> = (0..LAWS)
            .map(|i| {
                (0..2)
                    .map(|j| {
                        let v = light(&sig, j, 0, n);
                        let f: Vec<f64> = (0..n).map(|k| raw(&v, i, k)).collect();
                        through_motion(&sig.sg, &f, sig.dt, sig.qd_measured)
                    })
                    .collect()
            })
            .collect();
        // The whole record's accelerations, filtered at once.
        let accel: Vec<Vec<f64>> = (0..2)
            .map(|j| {
                if sig.qd_measured {
                    sig.sg
                        .apply(&m.qd.iter().map(|v| v[j]).collect::<Vec<_>>(), 1)
                } else {
                    sig.sg
                        .apply(&m.q.iter().map(|v| v[j]).collect::<Vec<_>>(), 2)
                }
            })
            .collect();
        let qdd: Vec<Vec<f64>> = (0..2)
            .map(|j| {
                let x: Vec<f64> = accel[j][a..z].to_vec();
                let y = sig.sg.apply(&x, 0);
                (0..n)
                    .map(|k| match k.checked_sub(a).and_then(|i| y.get(i)) {
                        Some(v) if v.is_finite() => *v,
                        Some(_) => 0.0,
                        None => accel[j][k],
                    })
                    .collect()
            })
            .collect();
        let rows: Vec<usize> = (a + 3..z).step_by(17).collect();
        for chunk in [1, 5, 37, 1000, usize::MAX] {
            let s = RowSeries::new(&sig, &rows, chunk);
            for i in 0..LAWS {
                for j in 0..2 {
                    // Backwards too: chunks met in any order.
                    for k in (0..n).chain((0..n).rev()) {
                        let (got, want) = (s.law(&sig, i, k, j), whole[i][j][k]);
                        assert!(
                            same(got, want),
                            "qd measured {measured}, chunk {chunk}, law {i}, joint {j}, sample {k}: {got} against {want}"
                        );
                    }
                }
            }
            for j in 0..2 {
                // Backwards too: chunks met in any order.
                for k in (0..n).chain((0..n).rev()) {
                    assert!(same(s.qdd(&sig, k, j), qdd[j][k]), "qdd {chunk} {j} {k}");
                }
            }
        }
        // The laws do move: a test of zeros would pass on anything.
        let moving = whole[stribeck_law(0.03)][0][a..z]
            .iter()
            .filter(|v| v.abs() > 0.1)
            .count();
        assert!(moving > (z - a) / 10, "{moving}");
    }
}

#[test]
fn law_indices_follow_the_grids() {
    assert_eq!(coulomb_law(SIGN_SMOOTHING), 0);
    assert_eq!(coulomb_law(0.15), 2);
    assert_eq!(stribeck_law(0.01), 3);
    assert_eq!(stribeck_law(0.3), 6);
    assert_eq!(LAWS, 7);
    let v = 0.02;
    assert_eq!(law(1, v), (v / 0.05_f64).tanh());
    assert_eq!(law(4, v), (-(v / 0.03_f64).powi(2)).exp() * smooth_sign(v));
}

/// A velocity crossing a narrow bump `exp(-(v/vs)^2)` at a steady
/// acceleration, sampled every 10 ms: the interval means add up to the
/// bump's impulse, `vs sqrt(pi) / a` (a Gaussian integral), wherever
/// the samples fall; the values at the samples alone miss it or
/// overshoot it by far.
#[test]
fn interval_means_keep_a_narrow_bumps_impulse() {
    let (vs, a, dt) = (0.01, 5.0, 0.01);
    let f = |v: f64| (-(v / vs).powi(2)).exp();
    let exact = vs * std::f64::consts::PI.sqrt() / a;
    let mut point_errors: Vec<f64> = Vec::new();
    for shift in [0.0, 0.25, 0.5] {
        let v = |k: i64| a * (k as f64 + shift) * dt;
        let mean: f64 = (-50..50)
            .map(|k| interval_mean(&f, v(k - 1), v(k), v(k + 1)) * dt)
            .sum();
        assert!(
            (mean / exact - 1.0).abs() < 0.01,
            "shift {shift}: {mean} against {exact}"
        );
        let point: f64 = (-50..50).map(|k| f(v(k)) * dt).sum();
        point_errors.push((point / exact - 1.0).abs());
    }
    assert!(point_errors.iter().any(|e| *e > 0.5), "{point_errors:?}");
}
