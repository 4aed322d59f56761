//! The columns of the identification and the base parameters: the emitted
//! inertial regressor (ten parameters a link) with, per joint, Coulomb
//! friction (smooth sign of the velocity), viscous friction, rotor inertia
//! and an effort offset; the base parameters are the columns kept by an
//! order-preserving rank reduction of the regressor stacked over random
//! states (a pivoted Cholesky factorisation of its Gram matrix in column
//! order, joints' columns first), so they depend on the robot's structure
//! only, not on a motion. Rows are weighted per joint by the inverse of a
//! typical effort of that joint, so that every joint counts alike.

use nalgebra::{DMatrix, SMatrix, SVector};

use super::{ExciteError, Limits};
use crate::effects::SIGN_SMOOTHING;
use crate::regressor::Column;
use crate::rng::Rng;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// A column is kept when more than this fraction of its norm lies outside
/// the span of the columns kept before it (over random states).
const KEEP_TOLERANCE: f64 = 1e-5;

/// The base columns of a robot's identification and the row weights.
///
/// ```
/// use dynamics_sim2real::excite::{BaseColumns, Limits};
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
/// }
/// let limits = Limits::<2>::new([-1.0; 2], [1.0; 2], [2.0; 2], [50.0; 2]);
/// let cols = BaseColumns::of(&TwoLink::default(), &limits, 1).unwrap();
/// // A planar 2R arm with friction, rotor inertia and offsets: 8 joint
/// // columns (j1's rotor inertia absorbs l1's I_zz, the classical ZZ1R)
/// // and 5 of the links: l1's two first moments (with l2's mass folded
/// // in), l2's two first moments and its I_zz.
/// assert_eq!(cols.kept.len(), 8 + 5);
/// assert!(cols.names::<TwoLink>().iter().any(|n| n == "coulomb j2"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BaseColumns<const N: usize> {
    /// Every column, joints' first.
    pub all: Vec<Column>,
    /// Indices into `all` of the base columns, in order.
    pub kept: Vec<usize>,
    /// The other columns, each written as a combination of base columns
    /// (`x_dropped = sum c * x_kept`, `(index into all, c)`; empty for a
    /// column that is zero at every state).
    pub dropped: Vec<(usize, Vec<(usize, f64)>)>,
    /// Row weight per joint: the inverse of a typical effort of the joint
    /// (root mean square of the nominal model's efforts over the random
    /// states).
    pub weights: SVector<f64, N>,
    /// Velocity scale of the smooth sign of the Coulomb columns.
    pub sign_zone: f64,
}

impl<const N: usize> BaseColumns<N> {
    /// The base columns of `robot` within `limits`, from 400 random states
    /// drawn with `seed`: positions uniform in the limits, velocities
    /// uniform within the velocity limits, accelerations within `pi` times
    /// them.
    pub fn of<R: Robot<N>>(robot: &R, limits: &Limits<N>, seed: u64) -> Result<Self, ExciteError> {
        limits.require_finite(&R::JOINT_NAMES)?;
        let all = crate::regressor::all::<R, N>();
        let mut rng = Rng::new(seed);
        let states: Vec<Reference<N>> = (0..400)
            .map(|_| Reference {
                q: SVector::from_fn(|j, _| rng.uniform(limits.lower[j], limits.upper[j])),
                qd: SVector::from_fn(|j, _| rng.uniform(-1.0, 1.0) * limits.velocity[j]),
                qdd: SVector::from_fn(|j, _| {
                    rng.uniform(-1.0, 1.0) * limits.velocity[j] * std::f64::consts::PI
                }),
            })
            .collect();
        let mut sq = SVector::<f64, N>::zeros();
        for s in &states {
            let tau = robot.inverse_dynamics(&s.q, &s.qd, &s.qdd);
            sq += tau.component_mul(&tau);
        }
        let weights = sq.map(|v| {
            let rms = (v / states.len() as f64).sqrt();
            if rms > 0.0 && rms.is_finite() {
                1.0 / rms
            } else {
                1.0
            }
        });
        let mut cols = BaseColumns {
            kept: (0..all.len()).collect(),
            all,
            dropped: Vec::new(),
            weights,
            sign_zone: SIGN_SMOOTHING,
        };
        let x = cols.stack(robot, &states)?;
        let (kept, dropped) = reduce(&x)?;
        cols.kept = kept;
        cols.dropped = dropped;
        Ok(cols)
    }

    /// The names of the base columns (e.g. `coulomb panda_joint2`,
    /// `panda_link3 m c_x`).
    pub fn names<R: Robot<N>>(&self) -> Vec<String> {
        self.kept
            .iter()
            .map(|&c| self.all[c].name::<R, N>())
            .collect()
    }

    /// The weighted rows of the base columns at `states`, stacked: row `s
    /// * N + j` is joint `j` at state `s`.
    pub fn stack<R: Robot<N>>(
        &self,
        robot: &R,
        states: &[Reference<N>],
    ) -> Result<DMatrix<f64>, ExciteError> {
        let links = R::LINK_NAMES.len();
        let mut y = vec![SMatrix::<f64, N, 10>::zeros(); links];
        let mut x = DMatrix::zeros(states.len() * N, self.kept.len());
        for (s, st) in states.iter().enumerate() {
            robot
                .inertial_regressor(&st.q, &st.qd, &st.qdd, &mut y)
                .map_err(|e| ExciteError::Regressor {
                    robot: R::NAME,
                    cause: e.to_string(),
                })?;
            for (c, &k) in self.kept.iter().enumerate() {
                for j in 0..N {
                    let v = match self.all[k] {
                        Column::Coulomb(i) if i == j => (st.qd[j] / self.sign_zone).tanh(),
                        Column::Viscous(i) if i == j => st.qd[j],
                        Column::Offset(i) if i == j => 1.0,
                        Column::Armature(i) if i == j => st.qdd[j],
                        Column::Link(l, p) => y[l][(j, p)],
                        _ => 0.0,
                    };
                    x[(s * N + j, c)] = v * self.weights[j];
                }
            }
        }
        Ok(x)
    }
}

/// The kept columns of `x` (in order) and every dropped one as a
/// combination of kept ones.
type Reduced = (Vec<usize>, Vec<(usize, Vec<(usize, f64)>)>);

/// Order-preserving rank reduction of `x` through the Cholesky
/// factorisation of the Gram matrix of its unit-norm columns: column `c` is
/// kept when the squared norm of its part outside the kept columns' span
/// exceeds `KEEP_TOLERANCE^2`.
fn reduce(x: &DMatrix<f64>) -> Result<Reduced, ExciteError> {
    let p = x.ncols();
    let norms: Vec<f64> = (0..p).map(|c| x.column(c).norm()).collect();
    let g = x.transpose() * x;
    let unit = |a: usize, b: usize| g[(a, b)] / (norms[a] * norms[b]);
    let mut kept: Vec<usize> = Vec::new();
    // Rows of the Cholesky factor of the kept columns' Gram matrix.
    let mut l: Vec<Vec<f64>> = Vec::new();
    let mut zero = Vec::new();
    for c in 0..p {
        if norms[c] == 0.0 || !norms[c].is_finite() {
            zero.push(c);
            continue;
        }
        let z = forward(&l, &kept.iter().map(|&k| unit(k, c)).collect::<Vec<_>>());
        let rest = 1.0 - z.iter().map(|v| v * v).sum::<f64>();
        if rest > KEEP_TOLERANCE * KEEP_TOLERANCE {
            let d = rest.sqrt();
            let mut row = z;
            row.push(d);
            l.push(row);
            kept.push(c);
        } else {
            zero.push(c);
        }
    }
    if kept.is_empty() {
        return Err(ExciteError::Numeric {
            place: "base columns",
            cause: "every column of the regressor is zero".into(),
        });
    }
    let mut dropped = Vec::new();
    for c in zero {
        if norms[c] == 0.0 || !norms[c].is_finite() {
            dropped.push((c, Vec::new()));
            continue;
        }
        // Gram-system solve: L L^T b = G[kept, c] (unit columns).
        let z = forward(&l, &kept.iter().map(|&k| unit(k, c)).collect::<Vec<_>>());
        let b = backward(&l, &z);
        let big = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let combo = kept
            .iter()
            .zip(&b)
            .filter(|(_, v)| v.abs() > 1e-6 * big)
            .map(|(&k, v)| (k, v * norms[c] / norms[k]))
            .collect();
        dropped.push((c, combo));
    }
    Ok((kept, dropped))
}

/// Solves `L z = v` for the lower-triangular `L` given by rows.
fn forward(l: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
    let mut z = Vec::with_capacity(v.len());
    for (i, row) in l.iter().enumerate() {
        let s: f64 = (0..i).map(|k| row[k] * z[k]).sum();
        z.push((v[i] - s) / row[i]);
    }
    z
}

/// Solves `L^T b = z`.
fn backward(l: &[Vec<f64>], z: &[f64]) -> Vec<f64> {
    let n = z.len();
    let mut b = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|k| l[k][i] * b[k]).sum();
        b[i] = (z[i] - s) / l[i][i];
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_combination_is_found_and_written_in_kept_columns() {
        // Columns a, b, 2 a - 3 b, 0, c.
        let x = DMatrix::from_fn(60, 5, |r, c| {
            let (a, b, d) = (
                (r as f64 * 0.3).sin(),
                (r as f64 * 0.7).cos(),
                (r as f64 * 1.1).sin(),
            );
            [a, b, 2.0 * a - 3.0 * b, 0.0, d][c]
        });
        let (kept, dropped) = reduce(&x).unwrap();
        assert_eq!(kept, vec![0, 1, 4]);
        assert_eq!(dropped[0].0, 2);
        let combo = &dropped[0].1;
        assert_eq!(combo.len(), 2);
        assert!((combo[0].1 - 2.0).abs() < 1e-9 && (combo[1].1 + 3.0).abs() < 1e-9);
        assert_eq!(dropped[1], (3, Vec::new()));
    }
}
