//! Fitting the candidates that simulate a motor side, driven by the
//! measured effort: elasticity and backlash (grid search, refinement and
//! spreads over the motor-side parameters) and the stiff-rotor variant of
//! armature, which sees a plain rotor the way they see the joint.

mod refine;
mod spread;

use super::against::Against;
use super::motor_sim::{transmitted_each, Stretches};
use super::one::{whitened_nominal, Fit};
use crate::diagnose::candidates::{
    motor_feasible, motor_grid, signature_limit, Candidate, MotorGuess,
};
use dynamics_runtime::{JointKind, Robot};
use refine::{refine, refine_one};
use spread::motor_std;

/// Couplings of the stiff rotor, Hz (all above the 45 Hz the elastic
/// candidate may reach), and their damping ratio.
const STIFF_ROTOR: ([f64; 3], f64) = ([60.0, 120.0, 250.0], 0.7);

/// A rotor inertia seen the way the motor-side models see the joint: a
/// rotor of inertia jm on a stiff, well damped coupling driven by the
/// measured effort (the same simulation as elasticity, above the motion's
/// band and without a resonance to show). The controller's fast reaction
/// to sensor noise reaches the effort record but hides under the noise of
/// the measured velocity; the acceleration column misses it, and a
/// coupling passes less of the effort's own noise than the smoothing of
/// the measured effort does; a motor-side model has both, and would
/// otherwise win on a plain rotor's data for those reasons alone (by 12
/// to 37 AICc on three of 400 scored cases with one 250 Hz coupling).
/// Keeps the best of the fits of the one parameter.
pub(super) fn stiff_rotor<const N: usize>(linear: Fit, j: usize, on: &Against<N>) -> Fit {
    let p = on.p;
    let (w, base, own) = whitened_nominal(on, j);
    let (inertia, zeta) = (p.basis.inertia[j], STIFF_ROTOR.1);
    let guess = |jm: f64, f: f64| -> MotorGuess {
        let om = 2.0 * std::f64::consts::PI * f;
        let stiffness = om * om / (1.0 / jm + 1.0 / inertia);
        MotorGuess {
            jm,
            stiffness,
            damping: 2.0 * zeta * (stiffness * jm).sqrt(),
            half_width: 0.0,
        }
    };
    // Whitened SSE with each rotor of `gs` (simulated side by side) on
    // the search's stretches, and on the whole record.
    let search = Stretches::search(&p.sig, &p.rows);
    let whole = Stretches::whole(&p.sig, &p.rows);
    let costs_on = |stretches: &Stretches, gs: &[MotorGuess]| -> Vec<f64> {
        transmitted_each(on, j, gs, false, &p.basis.compliance, stretches, |t| {
            let sse: f64 = base - own
                + t.at_rows(&p.sig.sg)
                    .map(|(e, m)| ((e - m) * w).powi(2))
                    .sum::<f64>();
            if sse.is_finite() {
                sse
            } else {
                f64::INFINITY
            }
        })
    };
    let costs = |gs: &[MotorGuess]| costs_on(&search, gs);
    let start = linear
        .theta
        .first()
        .copied()
        .unwrap_or(0.0)
        .max(1e-3 * inertia);
    // The coupling that fits best at the linear fit's inertia (the
    // couplings barely move the inertia), then the inertia at it.
    // Only couplings the rate shows (none at 100 Hz: the linear fit).
    let limit = signature_limit(p.sig.dt);
    let couplings: Vec<f64> = STIFF_ROTOR.0.into_iter().filter(|&f| f <= limit).collect();
    let first = costs(
        &couplings
            .iter()
            .map(|&f| guess(start, f))
            .collect::<Vec<_>>(),
    );
    let best = couplings
        .into_iter()
        .zip(first)
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let Some((f, c_start)) = best else {
        return linear;
    };
    let (jm, mut c_best) = refine_one(start, c_start, |jms| {
        costs(&jms.iter().map(|&jm| guess(jm, f)).collect::<Vec<_>>())
    });
    if !search.is_whole() {
        c_best = costs_on(&whole, &[guess(jm, f)])
            .first()
            .copied()
            .unwrap_or(f64::INFINITY);
    }
    let best = c_best.is_finite().then(|| (guess(jm, f), c_best));
    match best {
        Some((g, sse)) if sse < linear.sse => Fit {
            theta: vec![g.jm],
            std: linear.std.clone(),
            motor: Some(g),
            sse,
            ..linear
        },
        _ => linear,
    }
}

pub(super) fn fit_motor<R: Robot<N>, const N: usize>(c: Candidate, on: &Against<N>) -> Fit {
    let p = on.p;
    let (j, backlash) = match c {
        Candidate::Backlash(j) => (j, true),
        Candidate::Elasticity(j) => (j, false),
        _ => (0, false),
    };
    let (w, base, own) = whitened_nominal(on, j);
    let revolute = R::JOINT_KINDS[j] != JointKind::Prismatic;
    // Whitened SSE with the motor side `g` at joint j (smoothing only the
    // rows' windows of the transmitted effort).
    let inertia = p.basis.inertia[j];
    let limit = signature_limit(p.sig.dt);
    let feasible = |g: &MotorGuess| motor_feasible(g, backlash, inertia, revolute, limit);
    // Whitened rows of joint j with each guess of `gs` (simulated side by
    // side) on the search's stretches, or on the whole record.
    let search = Stretches::search(&p.sig, &p.rows);
    let whole = Stretches::whole(&p.sig, &p.rows);
    let rows_on = |stretches: &Stretches, gs: &[MotorGuess]| -> Vec<Vec<f64>> {
        transmitted_each(on, j, gs, backlash, &p.basis.compliance, stretches, |t| {
            t.at_rows(&p.sig.sg).map(|(e, m)| (e - m) * w).collect()
        })
    };
    let rows = |gs: &[MotorGuess]| rows_on(&search, gs);
    // Whitened SSE of each guess (infinite outside the physical box,
    // which is not simulated).
    let costs_on = |stretches: &Stretches, gs: &[MotorGuess]| -> Vec<f64> {
        let inside: Vec<MotorGuess> = gs.iter().copied().filter(feasible).collect();
        let mut simulated = rows_on(stretches, &inside).into_iter();
        gs.iter()
            .map(|g| {
                if !feasible(g) {
                    return f64::INFINITY;
                }
                let sse_j: f64 = simulated
                    .next()
                    .map_or(f64::NAN, |r| r.iter().map(|r| r * r).sum());
                let sse = base - own + sse_j;
                if sse.is_finite() {
                    sse
                } else {
                    f64::INFINITY
                }
            })
            .collect()
    };
    let costs = |gs: &[MotorGuess]| costs_on(&search, gs);
    let mut start: Option<(MotorGuess, f64)> = None;
    let grid = motor_grid(backlash, inertia, revolute, limit);
    for (g, sse) in grid.iter().zip(costs(&grid)) {
        if sse < start.map_or(f64::INFINITY, |s| s.1) {
            start = Some((*g, sse));
        }
    }
    let (motor, motor_std, sse) = match start {
        Some((g, sse)) => {
            let (g, mut sse) = refine(g, sse, backlash, costs);
            // Its spread, from the data it was searched on. (The
            // Gauss-Newton step `motor_std` also offers is not taken: from
            // a searched optimum it can carry a wrong motor side further
            // into data a plain rotor explains.)
            let sd = motor_std(&g, backlash, rows).0;
            if !search.is_whole() {
                sse = costs_on(&whole, &[g])
                    .first()
                    .copied()
                    .unwrap_or(f64::INFINITY);
            }
            (Some(g), Some(sd), sse)
        }
        None => (None, None, f64::INFINITY),
    };
    Fit {
        candidate: c,
        theta: vec![],
        std: vec![],
        motor,
        motor_std,
        sse,
        k: if backlash { 4 } else { 3 },
    }
}
