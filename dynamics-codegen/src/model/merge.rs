//! Welding: the mass of a link hung on a fixed joint is moved into the link
//! it is welded to (its frame stays, massless, for poses and points), as
//! Pinocchio does. One body instead of two saves the whole motion and force
//! propagation through the fixed chain. Done only where every number
//! involved is a constant (a parameter-dependent mass stays where it is).

use super::scalar::Scalar;
use super::{Elem, Inertial, JointKind, Model};
use crate::rotation::{mat_mat, mat_vec, rodrigues, rotate_tensor};

/// A constant rigid transform (rotation rows, translation).
type Pose = ([[f64; 3]; 3], [f64; 3]);

/// Merges every constant-mass link on a constant fixed chain into its parent,
/// leaves first so that chains of fixed joints collapse.
pub fn weld_fixed(model: &mut Model) {
    for k in (0..model.links.len()).rev() {
        let Some(j) = model.links[k].joint else {
            continue;
        };
        let joint = &model.joints[j];
        if joint.kind != JointKind::Fixed {
            continue;
        }
        let Some(pose) = constant_pose(&joint.chain) else {
            continue;
        };
        let Some(child) = model.links[k].inertial.as_ref().and_then(numbers) else {
            continue;
        };
        let parent = joint.parent;
        let base = match &model.links[parent].inertial {
            None => Some((0.0, [0.0; 3], [0.0; 6])),
            Some(i) => numbers(i),
        };
        let Some(base) = base else { continue };
        let moved = transform(child, &pose);
        model.links[parent].inertial = Some(to_scalars(combine(base, moved)));
        model.links[k].inertial = None;
    }
}

fn numbers(i: &Inertial) -> Option<(f64, [f64; 3], [f64; 6])> {
    let m = i.mass.as_number()?;
    let c = [
        i.com[0].as_number()?,
        i.com[1].as_number()?,
        i.com[2].as_number()?,
    ];
    let mut t = [0.0; 6];
    for (k, s) in i.inertia.iter().enumerate() {
        t[k] = s.as_number()?;
    }
    Some((m, c, t))
}

fn to_scalars((m, c, t): (f64, [f64; 3], [f64; 6])) -> Inertial {
    Inertial {
        mass: Scalar::Num(m),
        com: c.map(Scalar::Num),
        inertia: t.map(Scalar::Num),
    }
}

/// The chain's transform when it holds only constants.
fn constant_pose(chain: &[Elem]) -> Option<Pose> {
    let mut r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut p = [0.0; 3];
    for e in chain {
        let (er, et) = match e {
            Elem::Rot(u, a) => (rodrigues(*u, a.as_number()?), [0.0; 3]),
            Elem::Trans(t) => (
                [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                [t[0].as_number()?, t[1].as_number()?, t[2].as_number()?],
            ),
            Elem::Matrix(m, t) => {
                let mut er = [[0.0; 3]; 3];
                for i in 0..3 {
                    for c in 0..3 {
                        er[i][c] = m[i][c].as_number()?;
                    }
                }
                (
                    er,
                    [t[0].as_number()?, t[1].as_number()?, t[2].as_number()?],
                )
            }
        };
        // (r, p) * (er, et)
        let rt = mat_vec(&r, et);
        p = [p[0] + rt[0], p[1] + rt[1], p[2] + rt[2]];
        r = mat_mat(&r, &er);
    }
    Some((r, p))
}

/// A body (mass, com, inertia about com) seen from the parent frame.
fn transform((m, c, t): (f64, [f64; 3], [f64; 6]), (r, p): &Pose) -> (f64, [f64; 3], [f64; 6]) {
    let rc = mat_vec(r, c);
    let com = [rc[0] + p[0], rc[1] + p[1], rc[2] + p[2]];
    (m, com, rotate_tensor(t, r))
}

/// Two bodies as one: total mass, common centre, inertia about it
/// (parallel axis theorem).
fn combine(
    a: (f64, [f64; 3], [f64; 6]),
    b: (f64, [f64; 3], [f64; 6]),
) -> (f64, [f64; 3], [f64; 6]) {
    let m = a.0 + b.0;
    let c: [f64; 3] = std::array::from_fn(|i| (a.0 * a.1[i] + b.0 * b.1[i]) / m);
    let mut t = [0.0; 6];
    for (mass, com, inertia) in [a, b] {
        let d = [com[0] - c[0], com[1] - c[1], com[2] - c[2]];
        let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        t[0] += inertia[0] + mass * (dd - d[0] * d[0]);
        t[1] += inertia[1] + mass * (dd - d[1] * d[1]);
        t[2] += inertia[2] + mass * (dd - d[2] * d[2]);
        t[3] += inertia[3] - mass * d[0] * d[1];
        t[4] += inertia[4] - mass * d[0] * d[2];
        t[5] += inertia[5] - mass * d[1] * d[2];
    }
    (m, c, t)
}

#[cfg(test)]
mod tests {
    use super::{combine, transform};

    #[test]
    fn two_point_masses_make_a_dumbbell() {
        let a = (1.0, [-1.0, 0.0, 0.0], [0.0; 6]);
        let b = (1.0, [1.0, 0.0, 0.0], [0.0; 6]);
        let (m, c, t) = combine(a, b);
        assert_eq!((m, c), (2.0, [0.0; 3]));
        assert_eq!(t, [0.0, 2.0, 2.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn rotation_moves_the_tensor() {
        let quarter_z = (
            [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            [1.0, 0.0, 0.0],
        );
        let (_, c, t) = transform(
            (1.0, [1.0, 0.0, 0.0], [1.0, 2.0, 3.0, 0.0, 0.0, 0.0]),
            &quarter_z,
        );
        assert_eq!(c, [1.0, 1.0, 0.0]);
        assert_eq!(t, [2.0, 1.0, 3.0, 0.0, 0.0, 0.0]);
    }
}
