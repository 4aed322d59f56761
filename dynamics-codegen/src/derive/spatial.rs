//! Spatial (6-D) algebra on graph nodes, for the analytic derivatives of
//! Newton-Euler (`rnea_derivatives.rs`).
//!
//! A spatial vector is an angular and a linear 3-vector: a motion
//! `[w; v]` (v = velocity of the point at the frame origin) or a force
//! `[n; f]` (n = moment about the frame origin). A spatial inertia about a
//! frame origin is `[Ibar, [h]x; [h]x^T, m]` with first moment `h = m c` and
//! rotational inertia `Ibar` about the origin; its time derivative has the
//! same shape with `m = 0`, so one type holds both. A transfer element maps
//! the frame before it to the frame after it: a rotation E (the new axes'
//! components are `E^T` times the old) or a translation t of the origin.

use dynamics_symbolic::{Graph, Id};

use super::body_jacobian::cross;
use super::kinematics::{dot, mat_mat, mat_vec, transpose};

pub type V3 = [Id; 3];
pub type M3 = [[Id; 3]; 3];

/// A motion or force vector: angular part, linear part.
#[derive(Clone, Copy)]
pub struct Sv {
    pub w: V3,
    pub v: V3,
}

/// A spatial inertia (or its rate, with `m = 0`) about a frame origin.
#[derive(Clone, Copy)]
pub struct Inertia {
    pub m: Id,
    pub h: V3,
    /// Symmetric: entries (r, c) and (c, r) are the same node.
    pub i: M3,
}

/// One transfer element, as the map from the frame before it.
#[derive(Clone, Copy)]
pub enum Step {
    /// Rotation matrix (rows).
    Rot(M3),
    /// Translation of the origin, in the frame before.
    Trans(V3),
}

fn add3(g: &mut Graph, a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| g.add(a[i], b[i]))
}

fn sub3(g: &mut Graph, a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| g.sub(a[i], b[i]))
}

/// A symmetric matrix from its upper triangle, mirrored node for node.
fn symmetric(g: &mut Graph, mut entry: impl FnMut(&mut Graph, usize, usize) -> Id) -> M3 {
    let zero = g.constant(0.0);
    let mut m = [[zero; 3]; 3];
    for r in 0..3 {
        for c in r..3 {
            m[r][c] = entry(g, r, c);
            m[c][r] = m[r][c];
        }
    }
    m
}

impl Sv {
    pub fn zero(g: &mut Graph) -> Sv {
        let z = g.constant(0.0);
        Sv {
            w: [z; 3],
            v: [z; 3],
        }
    }

    pub fn add(self, g: &mut Graph, o: Sv) -> Sv {
        Sv {
            w: add3(g, self.w, o.w),
            v: add3(g, self.v, o.v),
        }
    }

    pub fn sub(self, g: &mut Graph, o: Sv) -> Sv {
        Sv {
            w: sub3(g, self.w, o.w),
            v: sub3(g, self.v, o.v),
        }
    }

    pub fn scale(self, g: &mut Graph, k: Id) -> Sv {
        Sv {
            w: self.w.map(|x| g.mul(x, k)),
            v: self.v.map(|x| g.mul(x, k)),
        }
    }

    /// The pairing `w . w' + v . v'` (a motion with a force).
    pub fn dot(self, g: &mut Graph, o: Sv) -> Id {
        let t: Vec<Id> = (0..3)
            .flat_map(|i| [(self.w[i], o.w[i]), (self.v[i], o.v[i])])
            .map(|(a, b)| g.mul(a, b))
            .collect();
        g.sum(&t)
    }

    /// Motion cross product `self x m`.
    pub fn cross_motion(self, g: &mut Graph, m: Sv) -> Sv {
        let w = cross(g, self.w, m.w);
        let a = cross(g, self.w, m.v);
        let b = cross(g, self.v, m.w);
        Sv {
            w,
            v: add3(g, a, b),
        }
    }

    /// Force cross product `self x* f`.
    pub fn cross_force(self, g: &mut Graph, f: Sv) -> Sv {
        let a = cross(g, self.w, f.w);
        let b = cross(g, self.v, f.v);
        Sv {
            w: add3(g, a, b),
            v: cross(g, self.w, f.v),
        }
    }

    /// A motion carried through `step` into the frame after it.
    pub fn motion_forward(self, g: &mut Graph, step: &Step) -> Sv {
        match step {
            Step::Rot(e) => {
                let et = transpose(e);
                Sv {
                    w: mat_vec(g, &et, self.w),
                    v: mat_vec(g, &et, self.v),
                }
            }
            Step::Trans(t) => {
                let wxt = cross(g, self.w, *t);
                Sv {
                    w: self.w,
                    v: add3(g, self.v, wxt),
                }
            }
        }
    }

    /// A force carried back through `step` into the frame before it.
    pub fn force_back(self, g: &mut Graph, step: &Step) -> Sv {
        match step {
            Step::Rot(e) => Sv {
                w: mat_vec(g, e, self.w),
                v: mat_vec(g, e, self.v),
            },
            Step::Trans(t) => {
                let txf = cross(g, *t, self.v);
                Sv {
                    w: add3(g, self.w, txf),
                    v: self.v,
                }
            }
        }
    }
}

impl Inertia {
    pub fn zero(g: &mut Graph) -> Inertia {
        let z = g.constant(0.0);
        Inertia {
            m: z,
            h: [z; 3],
            i: [[z; 3]; 3],
        }
    }

    /// A body of mass m with its centre of mass at c and inertia `ic` about
    /// the centre of mass: `Ibar = Ic + m (|c|^2 1 - c c^T)`.
    pub fn body(g: &mut Graph, m: Id, c: V3, ic: M3) -> Inertia {
        let h = c.map(|x| g.mul(m, x));
        let ch = dot(g, c, h);
        let i = symmetric(g, |g, r, k| {
            let hc = g.mul(h[r], c[k]);
            let diag = if r == k { ch } else { g.constant(0.0) };
            let s = g.sum(&[ic[r][k], diag]);
            g.sub(s, hc)
        });
        Inertia { m, h, i }
    }

    pub fn add(self, g: &mut Graph, o: Inertia) -> Inertia {
        Inertia {
            m: g.add(self.m, o.m),
            h: add3(g, self.h, o.h),
            i: symmetric(g, |g, r, c| g.add(self.i[r][c], o.i[r][c])),
        }
    }

    /// `I m = [Ibar w + h x v; m v - h x w]`.
    pub fn apply(self, g: &mut Graph, m: Sv) -> Sv {
        let iw = mat_vec(g, &self.i, m.w);
        let hxv = cross(g, self.h, m.v);
        let mv = m.v.map(|x| g.mul(self.m, x));
        let hxw = cross(g, self.h, m.w);
        Sv {
            w: add3(g, iw, hxv),
            v: sub3(g, mv, hxw),
        }
    }

    /// The rate of this inertia when its body moves with the twist v:
    /// `v x* I - I v x`, i.e. `dh = m v_lin + w x h`,
    /// `dIbar = [w]x Ibar - Ibar [w]x + 2 (v_lin . h) 1 - h v_lin^T - v_lin h^T`.
    pub fn rate(self, g: &mut Graph, v: Sv) -> Inertia {
        let mv = v.v.map(|x| g.mul(self.m, x));
        let wxh = cross(g, v.w, self.h);
        let vh = dot(g, v.v, self.h);
        let twice_vh = g.scale(vh, 2.0);
        let cols: [V3; 3] = std::array::from_fn(|c| {
            let col = [self.i[0][c], self.i[1][c], self.i[2][c]];
            cross(g, v.w, col)
        });
        // P = [w]x Ibar, P[r][c] = cols[c][r]; dIbar = P + P^T + ...
        let i = symmetric(g, |g, r, c| {
            let a = g.mul(self.h[r], v.v[c]);
            let b = g.mul(v.v[r], self.h[c]);
            let diag = if r == c { twice_vh } else { g.constant(0.0) };
            let s = g.sum(&[cols[c][r], cols[r][c], diag]);
            let ab = g.add(a, b);
            g.sub(s, ab)
        });
        Inertia {
            m: g.constant(0.0),
            h: add3(g, mv, wxh),
            i,
        }
    }

    /// This inertia, about the frame after `step`, carried into the frame
    /// before it.
    pub fn back(self, g: &mut Graph, step: &Step) -> Inertia {
        match step {
            Step::Rot(e) => {
                let ei = mat_mat(g, e, &self.i);
                let et = transpose(e);
                Inertia {
                    m: self.m,
                    h: mat_vec(g, e, self.h),
                    i: symmetric(g, |g, r, c| {
                        let t: Vec<Id> = (0..3).map(|k| g.mul(ei[r][k], et[k][c])).collect();
                        g.sum(&t)
                    }),
                }
            }
            Step::Trans(t) => {
                // Ibar_before = Ibar + m (|t|^2 1 - t t^T)
                //   + 2 (t . h) 1 - h t^T - t h^T.
                let mt = t.map(|x| g.mul(self.m, x));
                let th = dot(g, *t, self.h);
                let tmt = dot(g, *t, mt);
                let i = symmetric(g, |g, r, c| {
                    let mut terms = vec![self.i[r][c]];
                    if r == c {
                        terms.push(tmt);
                        terms.push(g.scale(th, 2.0));
                    }
                    let parts = [
                        g.mul(mt[r], t[c]),
                        g.mul(self.h[r], t[c]),
                        g.mul(t[r], self.h[c]),
                    ];
                    terms.extend(parts.map(|p| g.neg(p)));
                    g.sum(&terms)
                });
                Inertia {
                    m: self.m,
                    h: add3(g, self.h, mt),
                    i,
                }
            }
        }
    }
}
