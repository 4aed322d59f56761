//! Rival pairs that no motion separates: two effects whose columns
//! coincide once the robot's base parameters are regrouped. The classical
//! case is the rotor inertia of a joint whose axis is fixed in the world
//! (the first joint) against the inertia of the link it turns about that
//! axis: both multiply that joint's acceleration only, so every motion
//! shows their sum (one base parameter) and only a measurement of one of
//! them (a datasheet's rotor inertia) splits it.
//!
//! The same holds for a joint whose axis stays perpendicular to every
//! joint axis before it (the shoulder of a 6R arm, after a vertical first
//! joint): the link's inertia about that axis enters that joint's effort
//! only, through its own acceleration, as the rotor's does. And a change
//! of a farther link can act as the first rotor (inertia added about two
//! axes of a link whose third is a joint axis perpendicular to the first:
//! the classical regrouping of `YY` into `ZZ1`).
//!
//! The test works in the base parameters' coordinates ([`BaseColumns`]:
//! every column of the regressor is a base column or a fixed combination
//! of them, found over random states, so the relation holds at every state
//! and on every motion): each effect's columns (a link's ten, the dropped
//! ones included) written in base columns; the pair is inseparable when
//! the two sets share a direction, some change of one acting on the
//! efforts exactly as some change of the other (each fitted alone, as the
//! diagnosis fits its candidates). Only effects with regressor columns are
//! judged (Coulomb and viscous friction, an offset, rotor and link
//! inertia); a delay, elasticity and backlash have signatures along a
//! motion, Stribeck friction nests Coulomb friction, a spring's column is
//! the position (which no base column holds).

use nalgebra::DMatrix;

use super::{BaseColumns, ExciteError, Limits, Rival};
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
/// // j2's axis is horizontal, perpendicular to j1's at every pose: l2's
/// // inertia about it enters j2's effort only, as j2's rotor does.
/// assert!(inseparable(&arm, &limits, Rival::Armature(1), Rival::Link(1)).unwrap());
/// // Friction and an offset: a reversal tells them apart.
/// assert!(!inseparable(&arm, &limits, Rival::Coulomb(1), Rival::Offset(1)).unwrap());
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
/// `b`'s, in base coordinates.
fn share_a_direction<const N: usize>(columns: &BaseColumns<N>, a: Rival, b: Rival) -> bool {
    let k = columns.kept.len();
    // A column of the regressor in base coordinates.
    let coordinates = |c: usize| -> Vec<f64> {
        let mut v = vec![0.0; k];
        if let Some(p) = columns.kept.iter().position(|&m| m == c) {
            v[p] = 1.0;
        } else if let Some((_, combo)) = columns.dropped.iter().find(|(d, _)| *d == c) {
            for &(m, x) in combo {
                if let Some(p) = columns.kept.iter().position(|&q| q == m) {
                    v[p] += x;
                }
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
        if cols.is_empty() {
            return 0;
        }
        let m = DMatrix::from_fn(k, cols.len(), |r, c| cols[c][r]);
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
        // l1's I_zz both multiply qdd_1 alone (the classical ZZ1R). j2's
        // rotor against l2: l2's I_zz acts on j1's effort too (its
        // angular velocity is qd_1 + qd_2), the rotor does not.
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
