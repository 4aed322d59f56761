//! The noise floor made a chunk at a time against the noisy twin's whole
//! signals (the record copied, the noise added, its signals made over the
//! whole record): the same to the bit, with measured velocities and
//! without.

use super::*;
use crate::effects::Effect;
use crate::synth::{synthesize, SynthOptions};
use crate::test_robots::Arm2;

/// The floor from the whole noisy twin.
fn whole_twin<const N: usize, R: Robot<N>>(
    robot: &R,
    m: &Measured<N>,
    sig: &Signals<N>,
    levels: &[SVector<f64, N>; 3],
) -> SVector<f64, N> {
    let mut rng = Rng::new(0x5e_0015e);
    let mut noisy = m.clone();
    for k in 0..noisy.len() {
        noisy.q[k] += rng.normal_vec(&levels[0]);
        noisy.qd[k] += rng.normal_vec(&levels[1]);
        noisy.tau[k] += rng.normal_vec(&levels[2]);
    }
    let shaken = Signals::unfloored(robot, &noisy);
    let (a, z) = sig.range;
    let mut sum = SVector::<f64, N>::zeros();
    let mut count = 0usize;
    for k in (a..z).filter(|&k| sig.mask.usable(k)) {
        let d = shaken.residual[k] - sig.residual[k];
        sum += d.component_mul(&d);
        count += 1;
    }
    (sum / count.max(1) as f64).map(|s| s.sqrt().max(1e-12))
}

#[test]
fn the_floor_in_chunks_is_the_whole_twins() {
    let robot = Arm2::default();
    let opts = SynthOptions {
        // Longer than two chunks of the default size at 1 kHz.
        duration: 9.0,
        seed: 5,
        ..Default::default()
    };
    let effects = [Effect::ViscousFriction { joint: 0, fv: 0.2 }];
    let record = synthesize(&robot, &effects, &opts).expect("a generated record");
    for measured in [true, false] {
        let mut m = record.clone();
        m.qd_measured = measured && m.qd_measured;
        let sig = Signals::unfloored(&robot, &m);
        let levels = sensor_levels(&m, &sig);
        let (x, y) = (
            known_floor(&robot, &m, &sig, &levels),
            whole_twin(&robot, &m, &sig, &levels),
        );
        assert!(x.iter().all(|v| *v > 1e-9), "{x}");
        for (u, v) in x.iter().zip(y.iter()) {
            assert_eq!(
                u.to_bits(),
                v.to_bits(),
                "{x} against {y} (qd measured: {measured})"
            );
        }
    }
}

/// [`effort_sensor_noise`] from the whole record's fast parts (raw minus
/// smoothed, every sample, every joint, made before the blocks).
fn whole_record_effort_noise<const N: usize>(m: &Measured<N>, sig: &Signals<N>) -> SVector<f64, N> {
    let sg = &sig.sg;
    let (a, z) = sig.range;
    let fast = |v: &[SVector<f64, N>]| -> Vec<SVector<f64, N>> {
        let mut out = vec![SVector::<f64, N>::zeros(); v.len()];
        for j in 0..N {
            let x: Vec<f64> = v.iter().map(|s| s[j]).collect();
            for (k, y) in sg.apply(&x, 0).iter().enumerate() {
                out[k][j] = x[k] - y;
            }
        }
        out
    };
    let (eq, eqd, et) = (fast(&m.q), fast(&m.qd), fast(&m.tau));
    let cols = if m.qd_measured { 2 * N } else { N };
    let mut left: Vec<Vec<f64>> = vec![Vec::new(); N];
    let mut k0 = a;
    while k0 + BLOCK <= z {
        if !sig.mask.clear(k0, k0 + BLOCK) {
            k0 += BLOCK;
            continue;
        }
        let x = DMatrix::from_fn(BLOCK, cols, |r, c| {
            if c < N {
                eq[k0 + r][c]
            } else {
                eqd[k0 + r][c - N]
            }
        });
        let svd = x.clone().svd(true, true);
        for (j, l) in left.iter_mut().enumerate() {
            let y = DVector::from_fn(BLOCK, |r, _| et[k0 + r][j]);
            match svd.solve(&y, 1e-12) {
                Ok(theta) => l.extend((&y - &x * theta).iter()),
                Err(_) => l.extend(y.iter()),
            }
        }
        k0 += BLOCK;
    }
    SVector::from_fn(|j, _| {
        if left[j].is_empty() {
            robust_std(
                &(a..z)
                    .filter(|&k| sig.mask.usable(k))
                    .map(|k| et[k][j])
                    .collect::<Vec<_>>(),
            )
        } else {
            robust_std(&left[j])
        }
    })
}

/// The efforts' sensor noise from fast parts made a block at a time is
/// the whole record's to the bit: with measured velocities and without,
/// a record of many blocks and one shorter than a block (the spread of
/// every usable sample's fast part).
#[test]
fn the_effort_noise_a_block_at_a_time_is_the_whole_records() {
    let robot = Arm2::default();
    let effects = [Effect::ViscousFriction { joint: 0, fv: 0.2 }];
    for duration in [7.3, 0.4] {
        let opts = SynthOptions {
            duration,
            seed: 9,
            ..Default::default()
        };
        let record = synthesize(&robot, &effects, &opts).expect("a generated record");
        for measured in [true, false] {
            let mut m = record.clone();
            m.qd_measured = measured && m.qd_measured;
            let sig = Signals::unfloored(&robot, &m);
            let (x, y) = (
                effort_sensor_noise(&m, &sig),
                whole_record_effort_noise(&m, &sig),
            );
            assert!(x.iter().all(|v| *v > 0.0 && v.is_finite()), "{x}");
            for (u, v) in x.iter().zip(y.iter()) {
                assert_eq!(
                    u.to_bits(),
                    v.to_bits(),
                    "{x} against {y} ({duration} s, {measured})"
                );
            }
        }
    }
}
