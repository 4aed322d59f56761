//! Motions that tell two rival effects apart: for each ambiguous pair, the
//! smallest principal angle between the two effects' column spaces after
//! every other base column is projected out. Zero: some combination of one
//! effect's columns is, as far as this motion shows, a combination of the
//! other's; 90 degrees: they cannot be mistaken. The design maximises the
//! smallest such angle over the pairs.
//!
//! Linear effects have their regressor columns: Coulomb, Stribeck and
//! viscous friction, an effort offset, a joint spring (the position), rotor
//! inertia and a link's inertial parameters. The effects the diagnosis fits by simulation have a
//! first-order signature on the efforts along the motion instead, used as
//! their column (the same criterion then applies):
//!
//! - a time delay `d` of positions and velocities against the effort: the
//!   model evaluated `d` late misses `d dtau/dt`, so its column is the time
//!   derivative of the nominal efforts (every joint);
//! - joint elasticity at joint j (motor and link joined by a spring of
//!   stiffness k): the motor leads the link by `tau_j / k`, so beyond a
//!   rigid rotor (`qdd_j`, projected out with the others) the motor effort
//!   carries `J_m / k d^2 tau_j / dt^2`: the second derivative of the
//!   joint's nominal effort;
//! - backlash at joint j (a gap of half-width delta): the motor leads the
//!   link by `delta sign(tau_j)`, so beyond the rigid rotor the effort
//!   carries `J_m delta d^2 sign(tau_j) / dt^2`, the sign smoothed over 5 %
//!   of the joint's typical effort.
//!
//! Derivatives along the motion are differences between neighbouring
//! states: the states must be equally spaced in time (their spacing does
//! not matter: an angle does not depend on a column's scale).
//!
//! A nested pair, Coulomb friction and the Stribeck friction that contains
//! it at the same joint, is judged otherwise: the diagnosis tells them
//! apart by the interval of the extra parameter, the breakaway excess
//! `fs - fc` (`diagnose/select/nesting.rs`), so the design minimises its
//! predicted standard deviation, with every other column (Coulomb friction
//! included) in the fit. The angle would work against this pair: the
//! excess column lives where the speed is below the Stribeck velocity, the
//! Coulomb column everywhere, and their cosine is about the square root of
//! the share of slow samples, so a larger angle means fewer slow samples,
//! where the excess is measured. See [`breakaway_separation`].
//!
//! A payload at the tip is refused: it is a change of the distal link's
//! inertial parameters (its column lies in their span: no motion separates
//! them); the diagnosis can prefer it only by parsimony (one parameter
//! against ten), which is not a question of the motion.

use nalgebra::{DMatrix, SVector};

use super::{BaseColumns, ExciteError};
use crate::regressor::Column;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// The velocity scale of the Stribeck column, rad/s or m/s.
pub const STRIBECK_VS: f64 = 0.1;

/// The effort scale of the smoothed sign in the backlash signature, as a
/// fraction of the joint's typical effort (the inverse of its row weight).
pub const BACKLASH_ZONE: f64 = 0.05;

/// An effect whose columns (or first-order signature) follow from the
/// motion alone.
///
/// ```
/// use dynamics_sim2real::excite::Rival;
/// let names = ["j1", "j2"];
/// let links = ["l1", "l2"];
/// assert_eq!(Rival::named("coulomb_friction", Some("j2"), &names, &links), Ok(Rival::Coulomb(1)));
/// assert_eq!(Rival::named("inertial_parameters", Some("l1"), &names, &links), Ok(Rival::Link(0)));
/// assert_eq!(Rival::named("backlash", Some("j1"), &names, &links), Ok(Rival::Backlash(0)));
/// assert_eq!(Rival::named("time_delay", None, &names, &links), Ok(Rival::Delay));
/// assert_eq!(Rival::named("joint_spring", Some("j1"), &names, &links), Ok(Rival::Spring(0)));
/// assert!(Rival::named("payload_mass", Some("l2"), &names, &links).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rival {
    /// Coulomb friction of joint j (smooth sign of the velocity).
    Coulomb(usize),
    /// Stribeck friction of joint j: its part beyond Coulomb friction,
    /// `sign(qd) exp(-(qd / vs)^2)`, `vs` = [`STRIBECK_VS`] (the Coulomb
    /// column it also holds is the rival's, or projected out with the
    /// others: Stribeck friction contains Coulomb friction, so the angle
    /// that tells them apart is that of the extra column).
    Stribeck(usize),
    /// Viscous friction of joint j.
    Viscous(usize),
    /// A constant effort offset on joint j.
    Offset(usize),
    /// A spring on joint j: an effort that grows with the position (its
    /// preload is an offset; the rival's column is the position).
    Spring(usize),
    /// Rotor inertia of joint j.
    Armature(usize),
    /// The inertial parameters of link l (its base columns).
    Link(usize),
    /// Positions and velocities recorded late against the effort: the time
    /// derivative of the nominal efforts.
    Delay,
    /// Joint elasticity at joint j beyond its rigid rotor: the second time
    /// derivative of the joint's nominal effort.
    Elasticity(usize),
    /// Backlash at joint j beyond its rigid rotor: the second time
    /// derivative of the smoothed sign of the joint's nominal effort
    /// (see [`BACKLASH_ZONE`]).
    Backlash(usize),
}

impl Rival {
    /// The effect a report names by `kind` (the vocabulary's names) and
    /// place (a joint of `joints`, or a link of `links` for
    /// `inertial_parameters`). The error says why a kind has no columns here.
    pub fn named(
        kind: &str,
        place: Option<&str>,
        joints: &[&str],
        links: &[&str],
    ) -> Result<Rival, String> {
        let joint = || {
            place
                .and_then(|p| joints.iter().position(|j| *j == p))
                .ok_or_else(|| format!("{kind}: no joint of the robot named {place:?}"))
        };
        Ok(match kind {
            "coulomb_friction" => Rival::Coulomb(joint()?),
            "stribeck_friction" => Rival::Stribeck(joint()?),
            "viscous_friction" => Rival::Viscous(joint()?),
            "effort_offset" => Rival::Offset(joint()?),
            "joint_spring" => Rival::Spring(joint()?),
            "armature" => Rival::Armature(joint()?),
            "inertial_parameters" => Rival::Link(
                place
                    .and_then(|p| links.iter().position(|l| *l == p))
                    .ok_or_else(|| format!("{kind}: no link of the robot named {place:?}"))?,
            ),
            "time_delay" => Rival::Delay,
            "joint_elasticity" => Rival::Elasticity(joint()?),
            "backlash" => Rival::Backlash(joint()?),
            "payload_mass" => {
                return Err("payload_mass: a payload at the tip is a change of the distal link's inertial parameters (its columns lie in theirs); no motion separates the two, only a preference for the simpler explanation".into())
            }
            other => {
                return Err(format!(
                    "{other}: no columns or signature here; `excite --separate` separates friction, offsets, springs, rotor and link inertia, a time delay, elasticity and backlash"
                ))
            }
        })
    }

    /// Whether base column `c` belongs to this effect (and is therefore
    /// not projected out).
    pub(super) fn owns(&self, c: Column) -> bool {
        match (*self, c) {
            (Rival::Coulomb(j), Column::Coulomb(i)) => i == j,
            (Rival::Viscous(j), Column::Viscous(i)) => i == j,
            (Rival::Offset(j), Column::Offset(i)) => i == j,
            (Rival::Armature(j), Column::Armature(i)) => i == j,
            (Rival::Link(l), Column::Link(m, _)) => l == m,
            _ => false,
        }
    }
}

/// The weighted columns of `rival` over the motion `states` (one
/// `Vec` of `states.len() * N` rows a column), with `x` the weighted base
/// columns stacked over the states and `tau` the nominal efforts there.
fn rival_columns<const N: usize>(
    rival: Rival,
    columns: &BaseColumns<N>,
    states: &[Reference<N>],
    x: &DMatrix<f64>,
    tau: &[SVector<f64, N>],
) -> Vec<Vec<f64>> {
    let w = &columns.weights;
    let n = states.len();
    let rows = n * N;
    // A column acting on joint j only, of value f(i) at state i.
    let at_joint = |j: usize, f: &dyn Fn(usize) -> f64| {
        let mut c = vec![0.0; rows];
        for i in 0..n {
            c[i * N + j] = f(i) * w[j];
        }
        vec![c]
    };
    // Neighbours of state i for differences (the ends repeat their
    // neighbour's difference).
    let mid = |i: usize| i.clamp(1, n.saturating_sub(2).max(1));
    let second = |v: &dyn Fn(usize) -> f64, i: usize| {
        if n < 3 {
            return 0.0;
        }
        let m = mid(i);
        v(m + 1) - 2.0 * v(m) + v(m - 1)
    };
    match rival {
        Rival::Coulomb(j) => at_joint(j, &|i| (states[i].qd[j] / columns.sign_zone).tanh()),
        Rival::Stribeck(j) => at_joint(j, &|i| {
            let v = states[i].qd[j];
            (v / columns.sign_zone).tanh() * (-(v / STRIBECK_VS).powi(2)).exp()
        }),
        Rival::Viscous(j) => at_joint(j, &|i| states[i].qd[j]),
        Rival::Offset(j) => at_joint(j, &|_| 1.0),
        Rival::Spring(j) => at_joint(j, &|i| states[i].q[j]),
        Rival::Armature(j) => at_joint(j, &|i| states[i].qdd[j]),
        Rival::Link(l) => columns
            .kept
            .iter()
            .enumerate()
            .filter(|(_, &k)| matches!(columns.all[k], Column::Link(m, _) if m == l))
            .map(|(c, _)| x.column(c).iter().copied().collect())
            .collect(),
        Rival::Delay => {
            let mut c = vec![0.0; rows];
            if n >= 3 {
                for i in 0..n {
                    let m = mid(i);
                    for j in 0..N {
                        c[i * N + j] = (tau[m + 1][j] - tau[m - 1][j]) * w[j];
                    }
                }
            }
            vec![c]
        }
        Rival::Elasticity(j) => at_joint(j, &|i| second(&|k| tau[k][j], i)),
        Rival::Backlash(j) => {
            let zone = BACKLASH_ZONE / w[j].max(f64::MIN_POSITIVE);
            at_joint(j, &|i| second(&|k| (tau[k][j] / zone).tanh(), i))
        }
    }
}

/// The smallest principal angle (rad) between the columns of `a` and `b`
/// after the columns of every other base parameter are projected out, for
/// each pair, over the motion `states`. A column that keeps less than
/// [`EXCITED_SHARE`] of itself after the projection counts as not
/// excited; a rival with no column left has angle zero. A pair of
/// Coulomb and Stribeck friction at the same joint (nested: Stribeck adds
/// the breakaway excess) gets, in place of the angle, how well the motion
/// determines that excess, also in `[0, pi/2]`: the arcsine of the
/// excess column's norm after every other column (Coulomb friction
/// included) is projected out, over the norm of a constant effort at the
/// joint (see the module's docs). A rigid rotor against the elasticity or
/// backlash that nests it at its joint gets how strongly the motion shows
/// the richer one's signature beyond the rotor, `atan` of its size against
/// the joint's typical effort, also in `[0, pi/2)`.
///
/// ```
/// use dynamics_sim2real::excite::{separation_angles, BaseColumns, Fourier, Limits, Rival};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let cols = BaseColumns::of(&p, &Limits::new([-1.0], [1.0], [3.0], [50.0]), 1).unwrap();
/// let mut f = Fourier::<1>::new([0.0].into(), 4.0, 4);
/// f.set_flat(&[0.3, 0.0, 0.2, 0.1, 0.1, -0.1, 0.05, 0.0]);
/// f.to_rest();
/// let states: Vec<_> = (0..400).map(|k| f.at(k as f64 * 0.01)).collect();
/// let pairs = [(Rival::Coulomb(0), Rival::Offset(0))];
/// let a = separation_angles(&p, &cols, &pairs, &states).unwrap();
/// assert!(a[0] > 0.1); // a swinging joint tells a friction level from an offset
/// // Elasticity and backlash: a spring's lead follows the effort, a gap's
/// // its sign; a swing that keeps the effort of one sign hardly shows a gap.
/// let b = separation_angles(&p, &cols, &[(Rival::Elasticity(0), Rival::Backlash(0))], &states).unwrap();
/// assert!(b[0] > 0.0);
/// ```
pub fn separation_angles<R: Robot<N>, const N: usize>(
    robot: &R,
    columns: &BaseColumns<N>,
    pairs: &[(Rival, Rival)],
    states: &[Reference<N>],
) -> Result<Vec<f64>, ExciteError> {
    let k = columns.kept.len();
    // The weighted base columns, stacked state by state.
    let x = columns.stack(robot, states)?;
    let tau: Vec<SVector<f64, N>> = states
        .iter()
        .map(|s| robot.inverse_dynamics(&s.q, &s.qd, &s.qdd))
        .collect();
    let mut out = Vec::new();
    for &(a, b) in pairs {
        let others: Vec<usize> = (0..k)
            .filter(|&c| {
                !a.owns(columns.all[columns.kept[c]]) && !b.owns(columns.all[columns.kept[c]])
            })
            .collect();
        let rows = states.len() * N;
        if let Some(j) = breakaway_joint(a, b) {
            out.push(breakaway_separation(j, columns, states, &x, &tau, &others));
            continue;
        }
        if let Some((j, extra)) = motor_side(a, b) {
            out.push(motor_separation(robot, j, extra, columns, states, &x, &tau));
            continue;
        }
        let xa = rival_columns(a, columns, states, &x, &tau);
        let xb = rival_columns(b, columns, states, &x, &tau);
        let to_matrix = |cols: &[Vec<f64>]| DMatrix::from_fn(rows, cols.len(), |r, c| cols[c][r]);
        let xo = DMatrix::from_fn(rows, others.len(), |r, c| x[(r, others[c])]);
        let qo = orthonormal(&xo);
        let perp = |m: DMatrix<f64>| match &qo {
            Some(q) => &m - q * (q.transpose() * &m),
            None => m,
        };
        let (ma, mb) = (to_matrix(&xa), to_matrix(&xb));
        let (pa, pb) = (left(&ma, &perp(ma.clone())), left(&mb, &perp(mb.clone())));
        let angle = match (orthonormal(&pa), orthonormal(&pb)) {
            (Some(qa), Some(qb)) => {
                let s = (qa.transpose() * qb).singular_values();
                s.max().clamp(-1.0, 1.0).acos()
            }
            // An effect the motion does not excite at all.
            _ => 0.0,
        };
        out.push(angle);
    }
    Ok(out)
}

/// Whether the pair nests (Stribeck over Coulomb friction, a motor side
/// over its rotor, at one joint): its value is then how well the motion
/// determines the richer one's extra, not an angle.
pub(crate) fn nested(a: Rival, b: Rival) -> bool {
    breakaway_joint(a, b).is_some() || motor_side(a, b).is_some()
}

/// The joint of a nested friction pair: Coulomb friction and Stribeck
/// friction at the same joint (either order).
fn breakaway_joint(a: Rival, b: Rival) -> Option<usize> {
    match (a, b) {
        (Rival::Coulomb(i), Rival::Stribeck(j)) | (Rival::Stribeck(j), Rival::Coulomb(i))
            if i == j =>
        {
            Some(j)
        }
        _ => None,
    }
}

/// How well a motion determines the Stribeck breakaway excess at joint
/// `j` (the extra parameter of Stribeck over Coulomb friction), as an
/// angle in `[0, pi/2]` so that it ranks with the other pairs' angles:
/// `asin(r)`, `r` the norm of the excess column after every other base
/// column and the joint's Coulomb column are projected out, over the norm
/// of a constant effort at the joint on every state (the most a friction
/// column can hold). The excess's predicted standard deviation is the
/// effort noise over that projected norm, so at a given number of states
/// a larger `r` is a proportionally tighter interval of the excess, which
/// is what the diagnosis's verdict on the pair reads. `r` is the smallest
/// over the Stribeck velocities the diagnosis searches
/// ([`crate::effects::STRIBECK_GRID`]): the narrowest, 0.01 rad/s, is
/// fitted too and must be determined as well.
///
/// The excess `exp(-(v/vs)^2) sign(v)` is narrow in time (crossed in
/// `vs / |qdd|`, often less than a state's spacing), so each state's value
/// is its root mean square over the state's interval (the velocity taken
/// linear from the state to the midpoints with its neighbours, as the
/// diagnosis takes it), with the sign of its mean: the sum of squares is
/// then the excess's energy over the motion whatever the spacing, like
/// that of a constant column.
fn breakaway_separation<const N: usize>(
    j: usize,
    columns: &BaseColumns<N>,
    states: &[Reference<N>],
    x: &DMatrix<f64>,
    tau: &[SVector<f64, N>],
    others: &[usize],
) -> f64 {
    let n = states.len();
    let rows = n * N;
    let coulomb = rival_columns(Rival::Coulomb(j), columns, states, x, tau);
    let mut base: Vec<Vec<f64>> = others
        .iter()
        .map(|&c| x.column(c).iter().copied().collect())
        .collect();
    base.extend(coulomb);
    let m = DMatrix::from_fn(rows, base.len(), |r, c| base[c][r]);
    let q = orthonormal(&m);
    let full = columns.weights[j].abs() * (n as f64).sqrt();
    if full == 0.0 || n == 0 {
        return 0.0;
    }
    let v = |i: usize| states[i].qd[j];
    crate::effects::STRIBECK_GRID
        .iter()
        .map(|&vs| {
            let f = |u: f64| (-(u / vs).powi(2)).exp() * (u / columns.sign_zone).tanh();
            let mut s = nalgebra::DVector::zeros(rows);
            for i in 0..n {
                let prev = v(i.saturating_sub(1));
                let next = v((i + 1).min(n - 1));
                let (mean, square) = interval_moments(&f, prev, v(i), next);
                s[i * N + j] = square.sqrt() * mean.signum() * columns.weights[j];
            }
            let left = match &q {
                Some(q) => &s - q * (q.transpose() * &s),
                None => s,
            };
            (left.norm() / full).min(1.0).asin()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The joint and the richer effect of a nested motor-side pair: a rigid
/// rotor and the elasticity or backlash that contains it at the same joint
/// (either order).
fn motor_side(a: Rival, b: Rival) -> Option<(usize, Rival)> {
    match (a, b) {
        (Rival::Armature(i), e @ (Rival::Elasticity(j) | Rival::Backlash(j)))
        | (e @ (Rival::Elasticity(j) | Rival::Backlash(j)), Rival::Armature(i))
            if i == j =>
        {
            Some((j, e))
        }
        _ => None,
    }
}

/// A rotor's inertia as a fraction of its joint's inertia, a backlash's
/// half-width (rad) and an elastic joint's natural frequency (Hz): the
/// nominal sizes that put a motor side's extra signature in efforts (the
/// middle of the ranges of geared robot joints: a few arcminutes of play,
/// a drive's first mode at 5-30 Hz). They scale the measure of every
/// motion alike, so the motion it prefers for one pair does not depend on
/// them; they weigh a motor-side pair against the others in a design of
/// several pairs.
const NOMINAL_ROTOR: f64 = 0.2;
const NOMINAL_GAP: f64 = 1e-3;
const NOMINAL_MODE_HZ: f64 = 15.0;

/// How strongly a motion shows a motor side's extra beyond its rigid rotor
/// at joint `j` (elasticity or backlash, which nest the rotor: the
/// diagnosis names the richer one only when its signature earns its extra
/// parameters over the rotor), as an angle in `[0, pi/2)`: `atan(r)`, `r`
/// the root mean square over the states of the extra's first-order
/// signature in efforts at its nominal size, after every base column (the
/// rotor included) is projected out, in units of the joint's typical
/// effort (the rows' weights). The signature is the second time derivative
/// of the joint's effort (elasticity: the motor leads by `tau / k`, times
/// `J_m`, about `tau'' / omega^2`) or of its smoothed sign (backlash:
/// `J_m delta sign(tau)''`); the time step is read from the states
/// (second differences of the positions against the accelerations).
fn motor_separation<R: Robot<N>, const N: usize>(
    robot: &R,
    j: usize,
    extra: Rival,
    columns: &BaseColumns<N>,
    states: &[Reference<N>],
    x: &DMatrix<f64>,
    tau: &[SVector<f64, N>],
) -> f64 {
    let n = states.len();
    if n < 3 {
        return 0.0;
    }
    // h^2 from q(i+1) - 2 q(i) + q(i-1) = h^2 qdd(i), least squares.
    let (mut num, mut den) = (0.0, 0.0);
    for i in 1..n - 1 {
        for k in 0..N {
            let d2 = states[i + 1].q[k] - 2.0 * states[i].q[k] + states[i - 1].q[k];
            num += d2 * states[i].qdd[k];
            den += states[i].qdd[k].powi(2);
        }
    }
    if !(den > 0.0 && num > 0.0) {
        return 0.0;
    }
    let h2 = num / den;
    let q0 = states[0].q;
    let zero = SVector::<f64, N>::zeros();
    let inertia = (robot.inverse_dynamics(
        &q0,
        &zero,
        &SVector::from_fn(|k, _| if k == j { 1.0 } else { 0.0 }),
    ) - robot.inverse_dynamics(&q0, &zero, &zero))[j]
        .abs();
    let size = match extra {
        Rival::Backlash(_) => NOMINAL_ROTOR * inertia * NOMINAL_GAP,
        _ => (std::f64::consts::TAU * NOMINAL_MODE_HZ).powi(-2),
    };
    let c = rival_columns(extra, columns, states, x, tau);
    let b = nalgebra::DVector::from_iterator(n * N, c[0].iter().map(|v| v * size / h2));
    let left = match orthonormal(x) {
        Some(q) => &b - &q * (q.transpose() * &b),
        None => b,
    };
    (left.norm() / (n as f64).sqrt()).atan()
}

/// The mean and the mean square of `f` over a state's interval: the
/// velocity linear from `v` to the midpoints with its neighbours `prev`
/// and `next`, each half weighing alike, sampled at steps of an eighth of
/// the smooth sign's width (at most 256 a half).
fn interval_moments(f: &impl Fn(f64) -> f64, prev: f64, v: f64, next: f64) -> (f64, f64) {
    let half = |a: f64, b: f64| {
        let step = crate::effects::SIGN_SMOOTHING / 8.0;
        let m = ((b - a).abs() / step).ceil().clamp(1.0, 256.0) as usize;
        (0..m).fold((0.0, 0.0), |(s1, s2), i| {
            let y = f(a + (b - a) * (i as f64 + 0.5) / m as f64);
            (s1 + y / m as f64, s2 + y * y / m as f64)
        })
    };
    let (a, b) = (half(0.5 * (prev + v), v), half(v, 0.5 * (v + next)));
    (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1))
}

/// The share of its column a rival must keep after the other base
/// columns are projected out to count as excited: below it, what is left
/// is the rounding or the end rows of a column the others already hold,
/// and the angle between two such remnants says nothing about the effects.
pub const EXCITED_SHARE: f64 = 0.01;

/// The columns of `projected` (the columns of `m` with the others
/// projected out) that keep at least [`EXCITED_SHARE`] of the norm of
/// their column in `m`.
fn left(m: &DMatrix<f64>, projected: &DMatrix<f64>) -> DMatrix<f64> {
    let keep: Vec<usize> = (0..m.ncols())
        .filter(|&c| {
            let full = m.column(c).norm();
            full > 0.0 && projected.column(c).norm() >= EXCITED_SHARE * full
        })
        .collect();
    projected.select_columns(keep.iter())
}

/// An orthonormal basis of the columns of `m` (those of norm above 1e-9
/// of the largest after orthogonalisation); `None` when there is none.
fn orthonormal(m: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    if m.ncols() == 0 {
        return None;
    }
    let norms: Vec<f64> = (0..m.ncols()).map(|c| m.column(c).norm()).collect();
    let big = norms.iter().fold(0.0_f64, |a, &b| a.max(b));
    if big == 0.0 {
        return None;
    }
    let mut basis: Vec<nalgebra::DVector<f64>> = Vec::new();
    for c in 0..m.ncols() {
        if norms[c] <= 1e-12 * big {
            continue;
        }
        let mut v = m.column(c).into_owned() / norms[c];
        for _ in 0..2 {
            for b in &basis {
                let d = b.dot(&v);
                v.axpy(-d, b, 1.0);
            }
        }
        let n = v.norm();
        if n > 1e-9 {
            basis.push(v / n);
        }
    }
    if basis.is_empty() {
        None
    } else {
        Some(DMatrix::from_columns(&basis))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::excite::Limits;

    dynamics_macros::robot! {
        pub robot Flat;
        gravity = [0.0, 0.0, -9.81];
        link base;
        link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
        joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    }

    dynamics_macros::robot! {
        pub robot Hanging;
        gravity = [0.0, -9.81, 0.0];
        link base;
        link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
        joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
    }

    /// One harmonic `q = a sin(w t)` over a whole period, equally spaced.
    fn sine(n: usize) -> Vec<Reference<1>> {
        let (a, w) = (0.5, std::f64::consts::TAU / 4.0);
        (0..n)
            .map(|k| {
                let t = 4.0 * k as f64 / n as f64;
                Reference {
                    q: [a * (w * t).sin()].into(),
                    qd: [a * w * (w * t).cos()].into(),
                    qdd: [-a * w * w * (w * t).sin()].into(),
                }
            })
            .collect()
    }

    #[test]
    fn a_spring_on_one_harmonic_without_gravity_is_a_rotor() {
        // Hand derivation: a joint turning about the vertical feels no
        // gravity, its effort is I qdd, a sine; the second difference of a
        // sampled sine is the sine times 2 (cos(w h) - 1), so at every
        // inner state the spring's signature is that multiple of the rotor
        // column I qdd (weighted alike): one harmonic cannot tell a spring
        // from a heavier rotor.
        let flat = Flat::default();
        let limits = Limits::new([-1.0], [1.0], [3.0], [50.0]);
        let cols = BaseColumns::of(&flat, &limits, 1).unwrap();
        let n = 400;
        let states = sine(n);
        let x = cols.stack(&flat, &states).unwrap();
        let tau: Vec<_> = states
            .iter()
            .map(|s| flat.inverse_dynamics(&s.q, &s.qd, &s.qdd))
            .collect();
        let c = rival_columns(Rival::Elasticity(0), &cols, &states, &x, &tau);
        let h = 4.0 / n as f64;
        let w = std::f64::consts::TAU / 4.0;
        let inertia = tau[n / 8][0] / states[n / 8].qdd[0];
        let factor = 2.0 * ((w * h).cos() - 1.0) * inertia * cols.weights[0];
        for i in 1..n - 1 {
            let want = factor * states[i].qdd[0];
            assert!((c[0][i] - want).abs() < 1e-9 * factor.abs().max(1.0), "{i}");
        }
    }

    #[test]
    fn a_rival_the_others_hold_is_not_excited() {
        // The spring's signature on one harmonic without gravity is a
        // multiple of the rotor column at every inner state (the test
        // above): projected against the rotor, only the two end rows are
        // left (well under 1 % of the column), so the spring is not
        // excited and its angle to an offset is zero, not the 90 degrees
        // of the two end rows against a constant.
        let flat = Flat::default();
        let limits = Limits::new([-1.0], [1.0], [3.0], [50.0]);
        let cols = BaseColumns::of(&flat, &limits, 1).unwrap();
        let states = sine(400);
        let a = separation_angles(
            &flat,
            &cols,
            &[(Rival::Elasticity(0), Rival::Offset(0))],
            &states,
        )
        .unwrap();
        assert_eq!(a[0], 0.0);
        // Coulomb friction against an offset on the same swing: both keep
        // most of their column, and a sign that changes twice a period is
        // far from a constant.
        let b = separation_angles(
            &flat,
            &cols,
            &[(Rival::Coulomb(0), Rival::Offset(0))],
            &states,
        )
        .unwrap();
        assert!(b[0] > 0.5, "{}", b[0]);
    }

    /// The breakaway measure of the sine of [`sine`] at `n` states a period.
    fn breakaway(n: usize) -> f64 {
        let flat = Flat::default();
        let limits = Limits::new([-1.0], [1.0], [3.0], [50.0]);
        let cols = BaseColumns::of(&flat, &limits, 1).unwrap();
        let a = separation_angles(
            &flat,
            &cols,
            &[(Rival::Coulomb(0), Rival::Stribeck(0))],
            &sine(n),
        )
        .unwrap();
        a[0]
    }

    #[test]
    fn a_breakaway_excess_is_judged_by_its_energy_at_any_spacing() {
        // The sine 0.5 sin(pi t / 2) reverses at 1.23 rad/s^2: it crosses
        // the narrowest Stribeck bump (0.01 rad/s) in about 8 ms, under a
        // state's spacing at 100 Hz. The measure's square is the excess's
        // energy (after projection) over that of a constant: the same at
        // 100 Hz and at 2 kHz, and at most the unprojected energy share
        // computed here by quadrature (the min over the searched velocities
        // of the time mean of (exp(-(v/vs)^2) tanh(v/0.01))^2), and close
        // to it.
        let (coarse, fine) = (breakaway(400), breakaway(8000));
        assert!(coarse > 0.0 && fine > 0.0);
        assert!(
            (coarse.sin() / fine.sin() - 1.0).abs() < 0.05,
            "{coarse} at 100 Hz, {fine} at 2 kHz"
        );
        let w = std::f64::consts::TAU / 4.0;
        let m = 400_000;
        let share = crate::effects::STRIBECK_GRID
            .iter()
            .map(|&vs| {
                (0..m)
                    .map(|k| {
                        let v = 0.5 * w * (w * 4.0 * (k as f64 + 0.5) / m as f64).cos();
                        ((-(v / vs).powi(2)).exp() * (v / 0.01).tanh()).powi(2)
                    })
                    .sum::<f64>()
                    / m as f64
            })
            .fold(f64::INFINITY, f64::min);
        // The excess is a short pulse of each sign around every reversal,
        // nearly orthogonal to the smooth columns and to a sign held for
        // seconds: the projection takes little of it.
        let r2 = fine.sin().powi(2);
        assert!(
            r2 <= share * 1.01 && r2 >= 0.9 * share,
            "{r2} against {share}"
        );
        // The angle between the two columns of the pair would be large
        // for the same sine (the excess is a small part of the Coulomb
        // column): the measure is not the angle.
        assert!(fine < 0.5, "{fine}");
    }

    #[test]
    fn a_delay_is_the_efforts_time_derivative() {
        // The delay's column at an inner state is tau(i+1) - tau(i-1),
        // weighted: compared with the efforts computed here independently.
        let hanging = Hanging::default();
        let limits = Limits::new([-1.0], [1.0], [3.0], [50.0]);
        let cols = BaseColumns::of(&hanging, &limits, 1).unwrap();
        let states = sine(40);
        let x = cols.stack(&hanging, &states).unwrap();
        let tau: Vec<_> = states
            .iter()
            .map(|s| hanging.inverse_dynamics(&s.q, &s.qd, &s.qdd))
            .collect();
        let c = rival_columns(Rival::Delay, &cols, &states, &x, &tau);
        for i in 1..39 {
            let want = (tau[i + 1][0] - tau[i - 1][0]) * cols.weights[0];
            assert!((c[0][i] - want).abs() < 1e-12);
        }
        // The ends repeat their neighbour's difference.
        assert_eq!(c[0][0], c[0][1]);
        assert_eq!(c[0][39], c[0][38]);
    }
}
