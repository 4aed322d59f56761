//! Rival pairs that no motion separates: two effects whose columns
//! coincide once the robot's base parameters are regrouped. The classical
//! case is the rotor inertia of a joint whose axis is fixed in the world
//! (the first joint) against the inertia of the link it turns about that
//! axis: both multiply that joint's acceleration only, so every motion
//! shows their sum (one base parameter) and only a measurement of one of
//! them (a datasheet's rotor inertia) splits it.
//!
//! The test works in the base parameters' coordinates
//! ([`BaseColumns`]: every column of the regressor is a base column or a
//! fixed combination of them, found over random states, so the relation
//! holds at every state and on every motion). Each effect's columns (a
//! link's ten, the dropped ones included, written in base columns) are
//! kept on the base columns the two effects own, the others' coordinates
//! set aside (any motion fits those as well); the pair is inseparable when
//! the two sets of columns share a direction there: some change of one
//! effect acts on the efforts as some change of the other. Only effects
//! with regressor columns are judged (Coulomb and viscous friction, an
//! offset, rotor and link inertia); a delay, elasticity and backlash have
//! signatures along a motion, Stribeck friction nests Coulomb friction, a
//! spring's column is the position (which no base column holds).

use nalgebra::DMatrix;

use super::{BaseColumns, ExciteError, Limits, Rival};
use crate::identify::Column;
use dynamics_runtime::Robot;

/// Relative size under which a singular value counts as zero in the rank
/// tests (the combinations' coefficients come from a factorisation with
/// tolerance 1e-5 on unit columns).
const RANK_TOLERANCE: f64 = 1e-6;

/// Whether no motion separates `a` and `b` on `robot` (base columns found
/// within `limits`): some change of one acts on the efforts as some change
/// of the other, at every state. False for a pair with a kind the base
/// columns do not hold (Stribeck friction, a spring, a delay, elasticity,
/// backlash).
///
/// ```
/// use dynamics_sim2real::excite::{inseparable, Limits, Rival};
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, 0.0, -9.81];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_y(q)]; }
/// }
/// let arm = TwoLink::default();
/// let limits = Limits::<2>::new([-1.0; 2], [1.0; 2], [2.0; 2], [50.0; 2]);
/// // j1 turns about a fixed vertical axis: its rotor and l1's inertia
/// // about that axis are one base parameter.
/// assert!(inseparable(&arm, &limits, Rival::Armature(0), Rival::Link(0)).unwrap());
/// // j2's axis turns with j1: l2's inertia acts on j1's effort, j2's rotor
/// // does not.
/// assert!(!inseparable(&arm, &limits, Rival::Armature(1), Rival::Link(1)).unwrap());
/// ```
pub fn inseparable<R: Robot<N>, const N: usize>(
    robot: &R,
    limits: &Limits<N>,
    a: Rival,
    b: Rival,
) -> Result<bool, ExciteError> {
    let held = |r: Rival| {
        matches!(
            r,
            Rival::Coulomb(_)
                | Rival::Viscous(_)
                | Rival::Offset(_)
                | Rival::Armature(_)
                | Rival::Link(_)
        )
    };
    if !held(a) || !held(b) || a == b {
        return Ok(false);
    }
    let columns = BaseColumns::of(robot, limits, 1)?;
    Ok(share_a_direction(&columns, a, b))
}

/// Whether some combination of `a`'s columns equals some combination of
/// `b`'s, in the base coordinates the two own.
fn share_a_direction<const N: usize>(columns: &BaseColumns<N>, a: Rival, b: Rival) -> bool {
    let owned = |c: Column| a.owns(c) || b.owns(c);
    // The base coordinates the pair owns.
    let mine: Vec<usize> = columns
        .kept
        .iter()
        .filter(|&&k| owned(columns.all[k]))
        .copied()
        .collect();
    // A column of the regressor in those coordinates.
    let coordinates = |c: usize| -> Vec<f64> {
        let mut v = vec![0.0; mine.len()];
        let add = |v: &mut Vec<f64>, k: usize, x: f64| {
            if let Some(p) = mine.iter().position(|&m| m == k) {
                v[p] += x;
            }
        };
        if columns.kept.contains(&c) {
            add(&mut v, c, 1.0);
        } else if let Some((_, combo)) = columns.dropped.iter().find(|(d, _)| *d == c) {
            for &(k, x) in combo {
                add(&mut v, k, x);
            }
        }
        v
    };
    let of = |r: Rival| -> Vec<Vec<f64>> {
        (0..columns.all.len())
            .filter(|&c| r.owns(columns.all[c]))
            .map(&coordinates)
            .collect()
    };
    let (ca, cb) = (of(a), of(b));
    let rank = |cols: &[Vec<f64>]| -> usize {
        if cols.is_empty() || mine.is_empty() {
            return 0;
        }
        let m = DMatrix::from_fn(mine.len(), cols.len(), |r, c| cols[c][r]);
        let s = m.singular_values();
        let big = s.max();
        if big == 0.0 {
            return 0;
        }
        s.iter().filter(|&&x| x > RANK_TOLERANCE * big).count()
    };
    let both: Vec<Vec<f64>> = ca.iter().chain(&cb).cloned().collect();
    rank(&ca) + rank(&cb) > rank(&both)
}

#[cfg(test)]
mod tests {
    use super::*;

    dynamics_macros::robot! {
        pub robot Planar;
        gravity = [0.0, -9.81, 0.0];
        link base;
        link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
        link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
        joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
        joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
    }

    #[test]
    fn the_first_rotor_and_link_inertia_about_its_axis_are_one_parameter() {
        // A planar 2R arm (gravity in the plane): j1's rotor inertia and
        // l1's I_zz both multiply qdd_1 alone (the classical ZZ1R); l1's
        // first moments feel gravity and stay apart. Its l1 columns that
        // remain are the first moments, which gravity separates from the
        // rotor: the pair is separable. j2's rotor against l2: l2's I_zz
        // acts on j1's effort too, the rotor does not.
        let arm = Planar::default();
        let limits = Limits::<2>::new([-1.0; 2], [1.0; 2], [2.0; 2], [50.0; 2]);
        let one = |a, b| inseparable(&arm, &limits, a, b).unwrap();
        assert!(one(Rival::Armature(0), Rival::Link(0)));
        assert!(one(Rival::Link(0), Rival::Armature(0)));
        assert!(!one(Rival::Armature(1), Rival::Link(1)));
        assert!(!one(Rival::Coulomb(0), Rival::Offset(0)));
        // Signatures along a motion and nested pairs are not judged here.
        assert!(!one(Rival::Delay, Rival::Armature(0)));
        assert!(!one(Rival::Coulomb(1), Rival::Stribeck(1)));
    }
}
