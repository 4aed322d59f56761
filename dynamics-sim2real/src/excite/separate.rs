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
//! A payload at the tip is refused: it is a change of the distal link's
//! inertial parameters (its column lies in their span: no motion separates
//! them); the diagnosis can prefer it only by parsimony (one parameter
//! against ten), which is not a question of the motion.

use nalgebra::{DMatrix, SVector};

use super::{BaseColumns, ExciteError};
use crate::identify::Column;
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
    fn owns(&self, c: Column) -> bool {
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
/// excited; a rival with no column left has angle zero.
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
