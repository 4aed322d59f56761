//! What a recorded motion can and cannot identify, before any fit: per
//! joint the direction reversals, the velocity range and the time spent
//! slow; over the whole motion the condition number of the weighted base
//! regressor (friction, rotor inertia and offset columns included) and its
//! weak directions, named by the columns they mix; and the same in words.

use nalgebra::SVector;
use serde::Serialize;

use super::{BaseColumns, ExciteError};
use dynamics_runtime::control::Reference;
use dynamics_runtime::{JointKind, Robot};

/// Rows at most used for the regressor (evenly spaced samples).
const MAX_ROWS: usize = 1500;
/// A weak direction is reported when the largest singular value exceeds
/// its singular value this many times.
const WEAK_RATIO: f64 = 100.0;

/// How one joint moves.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointCoverage {
    /// The joint.
    pub joint: String,
    /// Direction reversals (sign changes of the velocity beyond a
    /// threshold of 0.01 rad/s or m/s, or 5 % of the peak, whichever is
    /// larger).
    pub reversals: usize,
    /// Largest velocity magnitude.
    pub peak_velocity: f64,
    /// Fraction of the samples below the slow speed (0.1 rad/s, 0.01 m/s)
    /// while the joint moves through a reversal.
    pub slow_fraction: f64,
    /// Smallest and largest position.
    pub range: [f64; 2],
}

/// A direction of the parameters the motion hardly excites.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WeakDirection {
    /// Largest singular value over this direction's (unit-norm columns).
    pub ratio: f64,
    /// The base columns it mixes most, with their weight in it (largest
    /// three, unit-norm columns).
    pub columns: Vec<(String, f64)>,
}

/// What the motion can and cannot identify.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DataCheck {
    /// Per joint.
    pub joints: Vec<JointCoverage>,
    /// Condition number of the unit-column weighted base regressor.
    pub condition: f64,
    /// Its weak directions, weakest first (at most five).
    pub weak: Vec<WeakDirection>,
    /// The findings in words.
    pub words: Vec<String>,
}

/// Checks the motion sampled at `t` with positions `q` and velocities
/// `qd` (accelerations by central differences of `qd`).
///
/// ```
/// use dynamics_sim2real::excite::{check_data, BaseColumns, Limits};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let cols = BaseColumns::of(&p, &Limits::new([-1.0], [1.0], [3.0], [50.0]), 1).unwrap();
/// // Swinging one way only: a ramp up at 0.05 rad/s.
/// let t: Vec<f64> = (0..2000).map(|k| k as f64 * 0.005).collect();
/// let q: Vec<_> = t.iter().map(|&t| nalgebra::Vector1::new(0.05 * t)).collect();
/// let qd = vec![nalgebra::Vector1::new(0.05); t.len()];
/// let c = check_data(&p, &cols, &t, &q, &qd).unwrap();
/// assert_eq!(c.joints[0].reversals, 0);
/// assert!(c.words.iter().any(|w| w.contains("never reverses")));
/// assert!(c.words.iter().any(|w| w.contains("viscous friction is weak")));
/// ```
pub fn check_data<R: Robot<N>, const N: usize>(
    robot: &R,
    columns: &BaseColumns<N>,
    t: &[f64],
    q: &[SVector<f64, N>],
    qd: &[SVector<f64, N>],
) -> Result<DataCheck, ExciteError> {
    let n = t.len();
    if n < 3 || q.len() != n || qd.len() != n {
        return Err(ExciteError::Options {
            option: "data",
            cause: format!(
                "{n} times, {} positions, {} velocities: need at least 3 of each, as many",
                q.len(),
                qd.len()
            ),
        });
    }
    let mut joints = Vec::new();
    let mut words = Vec::new();
    for j in 0..N {
        let name = R::JOINT_NAMES[j];
        let (slow, unit): (f64, &str) = match R::JOINT_KINDS[j] {
            JointKind::Revolute => (0.1, "rad/s"),
            JointKind::Prismatic => (0.01, "m/s"),
        };
        let peak = qd.iter().fold(0.0_f64, |m, v| m.max(v[j].abs()));
        let threshold = (0.1 * slow).max(0.05 * peak);
        let (mut sign, mut reversals) = (0.0_f64, 0);
        for v in qd {
            let s = if v[j] > threshold {
                1.0
            } else if v[j] < -threshold {
                -1.0
            } else {
                continue;
            };
            if sign != 0.0 && s != sign {
                reversals += 1;
            }
            sign = s;
        }
        let slow_fraction = qd.iter().filter(|v| v[j].abs() < slow).count() as f64 / n as f64;
        let range = q.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |r, v| {
            [r[0].min(v[j]), r[1].max(v[j])]
        });
        if reversals == 0 {
            words.push(format!(
                "joint {name} never reverses direction: Coulomb friction and an effort offset cannot be told apart"
            ));
        } else if reversals < 4 {
            words.push(format!(
                "joint {name} reverses direction only {reversals} time{}: Coulomb friction and an effort offset are hard to tell apart",
                if reversals == 1 { "" } else { "s" }
            ));
        }
        if peak < 2.0 * slow {
            words.push(format!(
                "joint {name} never exceeds {:.2} {unit}: viscous friction is weak (it looks like Coulomb friction)",
                2.0 * slow
            ));
        }
        if reversals > 0 && slow_fraction < 0.02 {
            words.push(format!(
                "joint {name} spends {:.1} % of the time below {slow} {unit}: Stribeck friction cannot be told from Coulomb friction (slow velocity reversals separate them)",
                100.0 * slow_fraction
            ));
        }
        joints.push(JointCoverage {
            joint: name.to_string(),
            reversals,
            peak_velocity: peak,
            slow_fraction,
            range,
        });
    }
    // The regressor at evenly spaced samples (not the two ends, where the
    // central difference has no neighbour).
    let stride = ((n - 2) / MAX_ROWS).max(1);
    let states: Vec<Reference<N>> = (1..n - 1)
        .step_by(stride)
        .map(|k| {
            let dt = t[k + 1] - t[k - 1];
            Reference {
                q: q[k],
                qd: qd[k],
                qdd: if dt > 0.0 {
                    (qd[k + 1] - qd[k - 1]) / dt
                } else {
                    SVector::zeros()
                },
            }
        })
        .collect();
    let x = columns.stack(robot, &states)?;
    let norms: Vec<f64> = (0..x.ncols()).map(|c| x.column(c).norm()).collect();
    let names = columns.names::<R>();
    for (c, &nc) in norms.iter().enumerate() {
        if nc == 0.0 {
            words.push(format!(
                "{}: this motion does not excite it at all",
                names[c]
            ));
        }
    }
    let unit = nalgebra::DMatrix::from_fn(x.nrows(), x.ncols(), |r, c| {
        if norms[c] > 0.0 {
            x[(r, c)] / norms[c]
        } else {
            0.0
        }
    });
    let svd = unit.svd(false, true);
    let v_t = svd.v_t.as_ref().ok_or(ExciteError::Numeric {
        place: "check-data",
        cause: "the singular value decomposition gave no vectors".into(),
    })?;
    let s = &svd.singular_values;
    let big = s.max();
    let small = s.min();
    let condition = if small > 0.0 {
        big / small
    } else {
        f64::INFINITY
    };
    let mut order: Vec<usize> = (0..s.len()).collect();
    order.sort_by(|&a, &b| s[a].total_cmp(&s[b]));
    let mut weak = Vec::new();
    for &i in order.iter().take(5) {
        let ratio = if s[i] > 0.0 {
            big / s[i]
        } else {
            f64::INFINITY
        };
        if ratio < WEAK_RATIO {
            break;
        }
        let mut comps: Vec<(usize, f64)> = (0..v_t.ncols()).map(|c| (c, v_t[(i, c)])).collect();
        comps.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        let columns: Vec<(String, f64)> = comps
            .iter()
            .take(3)
            .map(|&(c, w)| (names[c].clone(), w))
            .collect();
        words.push(format!(
            "weak direction ({}x weaker than the strongest): {}",
            if ratio.is_finite() {
                format!("{ratio:.0}")
            } else {
                "infinitely".into()
            },
            columns
                .iter()
                .map(|(c, w)| format!("{w:+.2} {c}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
        weak.push(WeakDirection { ratio, columns });
    }
    Ok(DataCheck {
        joints,
        condition,
        weak,
        words,
    })
}
