//! The design matrix of the identification: per joint Coulomb friction
//! (smooth sign of the lightly smoothed velocity), viscous friction, a
//! constant offset and rotor inertia, and the ten inertial parameters of
//! every link (the emitted regressor), each column smoothed by the same
//! Savitzky-Golay filter as the measured efforts, at the rows used.

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::diagnose::Signals;
use crate::regressor::Column;
use dynamics_runtime::Robot;

/// The rows of `sig` the fit uses: every `stride` samples with a full
/// window of the second smoothing.
pub fn rows<const N: usize>(sig: &Signals<N>, stride: usize) -> Vec<usize> {
    let h = sig.sg.half();
    let (a, z) = sig.range;
    (a + h..z.saturating_sub(h))
        .step_by(stride.max(1))
        .collect()
}

/// The design matrix (row `r * N + j` = joint j at sample `rows[r]`) and
/// the torque residual `tau - model` there.
pub fn design<R: Robot<N>, const N: usize>(
    robot: &R,
    sig: &Signals<N>,
    rows: &[usize],
    columns: &[Column],
    sign_zone: f64,
) -> (DMatrix<f64>, DVector<f64>) {
    let (a, z) = sig.range;
    let n = sig.t.len();
    let links = R::LINK_NAMES.len();
    // Series over every sample of the valid range (NaN outside), per
    // column and joint, to be smoothed at the rows.
    let mut y = vec![SMatrix::<f64, N, 10>::zeros(); links];
    let mut series: Vec<Option<Vec<f64>>> = vec![None; columns.len() * N];
    let mut coulomb = vec![SVector::<f64, N>::zeros(); n];
    for (k, c) in coulomb.iter_mut().enumerate() {
        *c = sig.qd_light(k).map(|v| (v / sign_zone).tanh());
    }
    for k in a..z {
        let (q, qd, qdd) = (sig.q(k), sig.qd(k), sig.qdd(k));
        let have = robot.inertial_regressor(&q, &qd, &qdd, &mut y).is_ok();
        for (c, col) in columns.iter().enumerate() {
            for j in 0..N {
                let v = match *col {
                    Column::Coulomb(i) if i == j => coulomb[k][j],
                    Column::Viscous(i) if i == j => qd[j],
                    Column::Armature(i) if i == j => qdd[j],
                    Column::Link(l, p) if have => y[l][(j, p)],
                    _ => 0.0,
                };
                let slot = &mut series[c * N + j];
                if v != 0.0 || slot.is_some() {
                    // Zero before the first non-zero value (NaN outside the range).
                    let s = slot.get_or_insert_with(|| {
                        (0..n)
                            .map(|i| if i >= a && i < z { 0.0 } else { f64::NAN })
                            .collect()
                    });
                    s[k] = v;
                }
            }
        }
    }
    let mut x = DMatrix::zeros(rows.len() * N, columns.len());
    let mut r = DVector::zeros(rows.len() * N);
    for (ri, &k) in rows.iter().enumerate() {
        for j in 0..N {
            r[ri * N + j] = sig.residual[k][j];
            for c in 0..columns.len() {
                // Constant and zero columns stay exact.
                x[(ri * N + j, c)] = match (columns[c], &series[c * N + j]) {
                    (Column::Offset(i), _) => f64::from(u8::from(i == j)),
                    (_, Some(s)) => sig.sg.at(s, 0, k),
                    (_, None) => 0.0,
                };
            }
        }
    }
    (x, r)
}
