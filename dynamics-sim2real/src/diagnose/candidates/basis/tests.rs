//! The model's outputs kept at the rows and recomputed in chunks elsewhere
//! against the same quantities evaluated and smoothed over the whole
//! record at once (what the basis held at every sample): equal to the bit
//! at every sample, for chunks shorter than the filter's window,
//! odd-sized and longer than the record.

use super::*;
use crate::data::Measured;
use crate::effects::Effect;
use crate::synth::{synthesize, SynthOptions};

use crate::test_robots::Arm2;

fn record() -> Measured<2> {
    let friction = [Effect::ViscousFriction { joint: 1, fv: 0.3 }];
    let opts = SynthOptions {
        duration: 2.0,
        seed: 11,
        ..Default::default()
    };
    synthesize(&Arm2::default(), &friction, &opts).expect("a generated record")
}

/// Every entry of `v` smoothed over `range` by the filter run over the
/// range at once (zero where the window does not fit or the value is not
/// finite).
fn smooth_whole<const R: usize, const C: usize>(
    sg: &SavitzkyGolay,
    v: &mut [SMatrix<f64, R, C>],
    (a, z): (usize, usize),
) {
    for i in 0..R * C {
        let x: Vec<f64> = (a..z).map(|k| v[k].as_slice()[i]).collect();
        let y = sg.apply(&x, 0);
        for (k, y) in (a..z).zip(y) {
            v[k].as_mut_slice()[i] = if y.is_finite() { y } else { 0.0 };
        }
    }
}

fn same<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn chunks_and_rows_give_the_whole_records_outputs() {
    let robot = Arm2::default();
    let sig = Signals::unfloored(&robot, &record());
    let n = sig.t.len();
    let (a, z) = sig.range;
    let tip = Tip::of::<Arm2, 2>();
    assert!(matches!(tip, Tip::Frame(_)));
    let whole = sig.motion.stretch(0, n);
    let motion = [&whole[0][..], &whole[1][..], &whole[2][..]];
    let mut k = vec![SMatrix::<f64, 2, 2>::zeros(); n];
    along::perturbation_k(&robot, motion, a..z, usize::MAX, &mut k);
    let mut jac = vec![SMatrix::<f64, 3, 2>::zeros(); n];
    let mut acc = vec![Vector3::zeros(); n];
    along::tip_motion(&robot, &tip, motion, a..z, usize::MAX, &mut jac, &mut acc);
    let mut rot = vec![Matrix3::identity(); n];
    let mut jac_w = vec![SMatrix::<f64, 3, 2>::zeros(); n];
    let mut alpha = vec![Vector3::zeros(); n];
    along::tip_rotation(&robot, &tip, motion, a..z, &mut rot, &mut jac_w, &mut alpha);
    smooth_whole(&sig.sg, &mut k, (a, z));
    smooth_whole(&sig.sg, &mut acc, (a, z));
    smooth_whole(&sig.sg, &mut alpha, (a, z));
    let h = sig.sg.half();
    let rows: Vec<usize> = (a + h..z - h).step_by(h).collect();
    let mut moving = 0usize;
    for chunk in [5, 97, 4096, usize::MAX] {
        let b = Basis::new(&robot, &sig, &rows, chunk);
        assert!(b.framed());
        // Backwards, so that each chunk is recomputed more than once
        // between the rows.
        for s in (0..n).rev() {
            let t = b.tip_at(s);
            let f = t.frame.expect("a frame tip");
            assert!(same(&b.k(s), &k[s]), "K, chunk {chunk}, sample {s}");
            for j in 0..2 {
                let col = k[s].column(j).into_owned();
                assert!(
                    same(&b.k_column(s, j), &col),
                    "K_{j}, chunk {chunk}, sample {s}"
                );
            }
            assert!(same(&t.jac, &jac[s]), "J, chunk {chunk}, sample {s}");
            assert!(same(&t.acc, &acc[s]), "a, chunk {chunk}, sample {s}");
            assert!(same(&f.rot, &rot[s]), "R, chunk {chunk}, sample {s}");
            assert!(same(&f.jac_w, &jac_w[s]), "J_w, chunk {chunk}, sample {s}");
            assert!(
                same(&f.alpha, &alpha[s]),
                "alpha, chunk {chunk}, sample {s}"
            );
            moving += usize::from(k[s].norm() > 1e-3 && acc[s].norm() > 1e-3);
        }
    }
    // Not a comparison of zeros.
    assert!(moving > 2 * (z - a), "{moving}");
}
