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
