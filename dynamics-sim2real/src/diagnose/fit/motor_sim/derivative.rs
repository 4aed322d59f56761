//! One step's arithmetic of the motor-side lanes: the force the coupling
//! passes (a spring, or a dead zone between two contacts) and the state
//! derivative of every lane, the link following the measured motion plus
//! what the transmitted effort adds over the model's.

/// The force the coupling of lane parameters `(k, c, w)` (stiffness,
/// damping, half-width) passes for deflection `e` and its rate `ed`, of
/// one of `L` lanes, `B` backlash.
#[inline(always)]
pub(super) fn force<const L: usize, const B: bool>(k: f64, c: f64, w: f64, e: f64, ed: f64) -> f64 {
    if !B {
        return k * e + c * ed;
    }
    if L == 1 {
        return if e > w {
            (k * (e - w) + c * ed).max(0.0)
        } else if e < -w {
            (k * (e + w) + c * ed).min(0.0)
        } else {
            0.0
        };
    }
    // Lanes side by side: both sides computed and one selected, no
    // branch for the lanes to mispredict (a half-width is positive, so at
    // most one side is in contact); the same values.
    let pushing = (k * (e - w) + c * ed).max(0.0);
    let pulling = (k * (e + w) + c * ed).min(0.0);
    let f = if e < -w { pulling } else { 0.0 };
    if e > w {
        pushing
    } else {
        f
    }
}

/// What the lanes' state derivative needs besides the state: each lane's
/// coupling and motor inertia, and the interval's measured effort.
pub(super) struct Lanes<'a, const L: usize> {
    pub(super) k: &'a [f64; L],
    pub(super) c: &'a [f64; L],
    pub(super) w: &'a [f64; L],
    pub(super) inv_jm: &'a [f64; L],
    pub(super) inv_i: f64,
    pub(super) wo2: f64,
    pub(super) two_wo: f64,
    pub(super) tau: f64,
}

impl<const L: usize> Lanes<'_, L> {
    /// State derivative of every lane (motor angle, motor rate, link
    /// angle, link rate) where the measured motion and the model's effort
    /// are `m` (q, qd, qdd, effort): the link follows the measured motion
    /// plus what the transmitted effort adds over the model's, pulled back
    /// to the measurement at OBSERVER_HZ.
    #[inline(always)]
    pub(super) fn derivative<const B: bool>(
        &self,
        x: &[[f64; L]; 4],
        m: &[f64; 4],
    ) -> [[f64; L]; 4] {
        let [qs, vs, as_, ms] = *m;
        let mut dx = [[0.0; L]; 4];
        for l in 0..L {
            let f = force::<L, B>(
                self.k[l],
                self.c[l],
                self.w[l],
                x[0][l] - x[2][l],
                x[1][l] - x[3][l],
            );
            dx[0][l] = x[1][l];
            dx[1][l] = (self.tau - f) * self.inv_jm[l];
            dx[2][l] = x[3][l];
            dx[3][l] = as_
                + (f - ms) * self.inv_i
                + self.wo2 * (qs - x[2][l])
                + self.two_wo * (vs - x[3][l]);
        }
        dx
    }
}

/// `x + c k`, lane by lane.
#[inline(always)]
pub(super) fn add<const L: usize>(x: &[[f64; L]; 4], k: &[[f64; L]; 4], c: f64) -> [[f64; L]; 4] {
    let mut y = *x;
    for i in 0..4 {
        for l in 0..L {
            y[i][l] = x[i][l] + c * k[i][l];
        }
    }
    y
}
