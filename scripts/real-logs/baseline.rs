//! The least-squares baseline of the real-log evaluation: per joint Coulomb
//! (sign of the smoothed velocity), viscous, offset and rotor inertia, plus
//! the 10 inertial parameters of every link (the emitted regressor), fitted
//! on the training data and applied to the held-out data, on signals
//! smoothed as the diagnosis smooths them (Savitzky-Golay, order 3, 40 ms
//! half-width). Rows weighted by each joint's training residual RMS;
//! unidentifiable combinations take the minimum-norm solution (SVD).
//! With `BASELINE_LINKS=moments`, each link's mass and first moments
//! alone (its first four parameters).

use dynamics_runtime::Robot;
use dynamics_sim2real::data::Measured;
use dynamics_sim2real::diagnose::SavitzkyGolay;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// Smoothed q, qd, qdd, tau and the nominal model's residual, away from the edges.
struct Signals<const N: usize> {
    q: Vec<SVector<f64, N>>,
    qd: Vec<SVector<f64, N>>,
    qdd: Vec<SVector<f64, N>>,
    residual: Vec<SVector<f64, N>>,
}

fn signals<R: Robot<N>, const N: usize>(robot: &R, m: &Measured<N>) -> Signals<N> {
    let dt = m.sample_interval();
    let sg = SavitzkyGolay::new(((0.04 / dt).round() as usize).max(3), dt);
    let col = |x: &[SVector<f64, N>], j: usize| x.iter().map(|v| v[j]).collect::<Vec<_>>();
    let mut out = Signals {
        q: vec![],
        qd: vec![],
        qdd: vec![],
        residual: vec![],
    };
    let f: Vec<[Vec<f64>; 4]> = (0..N)
        .map(|j| {
            let (q, qd, tau) = (col(&m.q, j), col(&m.qd, j), col(&m.tau, j));
            [
                sg.apply(&q, 0),
                sg.apply(&qd, 0),
                sg.apply(&qd, 1),
                sg.apply(&tau, 0),
            ]
        })
        .collect();
    for k in sg.half()..m.len() - sg.half() {
        let get = |i: usize| SVector::<f64, N>::from_fn(|j, _| f[j][i][k]);
        let (q, qd, qdd, tau) = (get(0), get(1), get(2), get(3));
        out.residual
            .push(tau - robot.inverse_dynamics(&q, &qd, &qdd));
        out.q.push(q);
        out.qd.push(qd);
        out.qdd.push(qdd);
    }
    out
}

/// The regressor rows of sample `k`: N x (10 links + 4 N).
fn rows<R: Robot<N>, const N: usize>(robot: &R, s: &Signals<N>, k: usize) -> DMatrix<f64> {
    let links = R::LINK_NAMES.len();
    let mut y = vec![SMatrix::<f64, N, 10>::zeros(); links];
    let mut out = DMatrix::zeros(N, 10 * links + 4 * N);
    if robot
        .inertial_regressor(&s.q[k], &s.qd[k], &s.qdd[k], &mut y)
        .is_ok()
    {
        // BASELINE_LINKS=moments: each link's mass and first moments alone.
        let moments = std::env::var_os("BASELINE_LINKS").is_some_and(|v| v == "moments");
        let width = if moments { 4 } else { 10 };
        for (l, yl) in y.iter().enumerate() {
            out.view_mut((0, 10 * l), (N, width))
                .copy_from(&yl.columns(0, width));
        }
    }
    for j in 0..N {
        let c = 10 * links + 4 * j;
        let v = s.qd[k][j];
        out[(j, c)] = if v > 0.0 {
            1.0
        } else if v < 0.0 {
            -1.0
        } else {
            0.0
        };
        out[(j, c + 1)] = v;
        out[(j, c + 2)] = 1.0;
        out[(j, c + 3)] = s.qdd[k][j];
    }
    out
}

/// Per joint: held-out residual RMS before and after the fit.
pub fn baseline<R: Robot<N>, const N: usize>(
    robot: &R,
    train: &Measured<N>,
    holdout: &Measured<N>,
) -> Option<(SVector<f64, N>, SVector<f64, N>)> {
    let (a, h) = (signals(robot, train), signals(robot, holdout));
    let rms = |r: &[SVector<f64, N>]| {
        SVector::<f64, N>::from_fn(|j, _| {
            (r.iter().map(|v| v[j] * v[j]).sum::<f64>() / r.len().max(1) as f64).sqrt()
        })
    };
    let weight = rms(&a.residual).map(|x| 1.0 / x.max(1e-6));
    let p = 10 * R::LINK_NAMES.len() + 4 * N;
    let (mut ata, mut atb) = (DMatrix::<f64>::zeros(p, p), DVector::<f64>::zeros(p));
    for k in 0..a.q.len() {
        let mut x = rows(robot, &a, k);
        let mut b = DVector::from_column_slice(a.residual[k].as_slice());
        for j in 0..N {
            x.row_mut(j).scale_mut(weight[j]);
            b[j] *= weight[j];
        }
        ata += x.transpose() * &x;
        atb += x.transpose() * b;
    }
    // Column scaling, then the minimum-norm solution.
    let scale = DVector::from_fn(p, |i, _| 1.0 / ata[(i, i)].sqrt().max(1e-12));
    let scaled = DMatrix::from_fn(p, p, |i, j| ata[(i, j)] * scale[i] * scale[j]);
    let rhs = DVector::from_fn(p, |i, _| atb[i] * scale[i]);
    let theta = scaled.svd(true, true).solve(&rhs, 1e-10).ok()?;
    let theta = theta.component_mul(&scale);
    let after: Vec<SVector<f64, N>> = (0..h.q.len())
        .map(|k| {
            let fit = rows(robot, &h, k) * &theta;
            h.residual[k] - SVector::<f64, N>::from_column_slice(fit.as_slice())
        })
        .collect();
    Some((rms(&h.residual), rms(&after)))
}
