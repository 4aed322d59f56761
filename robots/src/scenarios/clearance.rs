//! Dissertation, sec. 3.2: a joint with clearance (Figs. 3.12-3.18). The pin of
//! link 2 (radius r2) rolls inside the ring of link 1 (radius r1) while the
//! ring pushes it; when the contact reaction Ru reaches zero the pin leaves
//! the ring and flies freely inside the clearance until it hits the ring
//! again. Every switch (loss of contact, re-contact, stick and slip) is
//! located as an event on the dense output (Illinois regula falsi, to
//! 1e-12 s), never by stepping over it.
//!
//! In contact (coordinates `(phi1, psi, u, phi2)` of [`crate::ClearanceArm`]) the
//! constraints (3.25) hold. The available text prints `f1 = u - (r1 - r2)` and
//! `f2 = r1 psi - r2 phi2`, the second with its sign garbled; derived again:
//! the pin's material point at the contact moves with
//! `(r1 - r2) (phi1' + psi') + r2 (phi1' + psi' + phi2')` along the ring,
//! the ring's with `r1 phi1'`; no slip makes them equal, `r1 psi' + r2 phi2' = 0`,
//! so `f2 = r1 psi + r2 phi2 - c0` with c0 fixed where contact begins.
//! The motion follows the dissertation's eq. 3.37, `D A qdd = D (Q + Qqt + U)` with
//! D^T spanning the motions the constraints allow, together with the
//! second derivatives of (3.25) (Baumgarte-stabilised); the reaction is
//! `R = A qdd - Q - Qqt - U` and Ru its u-row (sec. 3.2.2). The ring can
//! only push: contact holds while `Ru < 0` (inward along u).
//!
//! Rolling needs a tangential force Ft, which friction can give only up to
//! `mu |Ru|`: the dissertation's no-slip assumption holds while `|Ft| <= mu |Ru|`.
//! Where it fails the pin slides on the ring with Coulomb friction (only
//! f1 holds), and rolls again when the slip stops and friction suffices;
//! without this the model is inconsistent where Ru -> 0, because the
//! no-slip force would stay finite while the normal force vanishes. Not in
//! the dissertation, chosen here: mu = 0.15 (dry steel on steel, lubricated 0.1).
//! (A very large mu, near the dissertation's rolling throughout, runs into
//! Painleve's paradox while sliding: the normal force of the sliding
//! equations changes sign and the integration stops with an error.)
//!
//! In slide and flight the Cartesian model [`crate::ClearanceArmFree`]
//! integrates (see [`super::clearance_modes`]). A pin that reaches the ring
//! again hits it plastically and without friction (the dissertation gives no impact
//! law; restitution 0, chosen here): the normal velocity is removed in the
//! metric of A, which costs `1/2 vn^2 / (J A^-1 J^T)`; then it slides, or
//! stays in flight if the ring would have to pull.
//!
//! Drives: `M1 = M0 sin(w t)` on link 1, `M2 = M0 cos(w t)` between the
//! links, M0 = -1 N m, w = 2 rad/s. Not in the dissertation (it names phi10,
//! psi0, ... only), chosen here: at rest at t = 0, link 1 horizontal, link 2
//! straight up, the pin at the bottom of the ring; the contact is then lost
//! once within 4 s. (From both links horizontal the ring keeps pushing,
//! |Ru| >= 0.49 N, for 10 s: clearance alone does not open the joint.)
//! The available text's `delta = 0.005 m` does not match r1 - r2 = 5e-5 m; the radii
//! are used.

use std::f64::consts::FRAC_PI_2;

use dynamics_runtime::ode::JointState;
use nalgebra::{Vector2, Vector4};

/// Ring radius r1, m.
pub const R1: f64 = 0.0025;
/// Pin radius r2, m.
pub const R2: f64 = 0.00245;
/// Clearance r1 - r2, m.
pub const GAP: f64 = R1 - R2;
/// Drive amplitude M0, N m.
pub const M0: f64 = -1.0;
/// Drive frequency w, rad/s.
pub const OMEGA: f64 = 2.0;
/// Friction coefficient pin-ring of the default case (chosen; not in the dissertation).
pub const MU: f64 = 0.15;
/// Time tolerance of the event location, s.
pub const EVENT_TOL: f64 = 1e-12;
/// Half-width of the bracket each switch is checked on, s.
pub const EVENT_CHECK: f64 = 1e-9;
/// Baumgarte gain of the contact constraints, 1/s.
pub(crate) const BAUMGARTE: f64 = 20.0;

/// How the pin meets the ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Rolling without slip: (3.25) holds.
    Roll,
    /// Sliding with Coulomb friction: only f1 holds.
    Slide,
    /// Inside the clearance, no contact.
    Flight,
}

/// A located switch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    /// Time, s.
    pub t: f64,
    /// The mode left.
    pub from: Mode,
    /// The mode entered.
    pub to: Mode,
    /// The watch function that fired (roll: `-Ru`, `mu |Ru| - |Ft|`;
    /// slide: `-Ru`, slip rate along the slip; flight: `r1 - r2 - u`)
    /// [`EVENT_CHECK`] before `t`, on the same dense output: positive.
    pub g_before: f64,
    /// The same [`EVENT_CHECK`] after `t`: negative.
    pub g_after: f64,
    /// Energy the impact removed (re-contact), J.
    pub impact_loss: f64,
    /// The state at the switch in the dissertation's coordinates, before the
    /// change (velocities before an impact).
    pub q: Vector4<f64>,
    /// Its rates.
    pub qd: Vector4<f64>,
}

/// One output sample, in the dissertation's coordinates in every mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Mode.
    pub mode: Mode,
    /// (phi1, psi, u, phi2).
    pub q: Vector4<f64>,
    /// Their rates.
    pub qd: Vector4<f64>,
    /// Pin centre from A in link 1's frame, m.
    pub pin: Vector2<f64>,
    /// Contact reaction Ru along u, N (negative: the ring pushes; 0 in flight).
    pub ru: f64,
    /// Tangential contact force, N (0 in flight).
    pub ft: f64,
    /// Slip rate `r1 psi' + r2 phi2'`, m/s.
    pub slip: f64,
    /// Residuals of (3.25) in contact, m (roll: both; slide: f1).
    pub residual: Vector2<f64>,
    /// T + Pi, J.
    pub energy: f64,
    /// Work of the drives since t = 0, J.
    pub work: f64,
    /// Work of friction since t = 0 (negative), J.
    pub friction_work: f64,
    /// Energy removed by impacts since t = 0, J.
    pub impact_loss: f64,
}

/// The motion with its switches.
#[derive(Debug, Clone, Default)]
pub struct ClearanceRun {
    /// Samples every dt.
    pub samples: Vec<Sample>,
    /// Switches in time order.
    pub switches: Vec<Switch>,
}

pub(crate) type State = (JointState<4>, Vector2<f64>);

#[derive(Debug, Clone, Copy)]
pub(crate) enum Active {
    Roll { c0: f64 },
    Slide { sigma: f64 },
    Flight,
}

impl Active {
    pub(crate) fn mode(&self) -> Mode {
        match self {
            Active::Roll { .. } => Mode::Roll,
            Active::Slide { .. } => Mode::Slide,
            Active::Flight => Mode::Flight,
        }
    }
}

/// The drive torques (M1, M2) at time t.
pub fn drives(t: f64) -> (f64, f64) {
    (M0 * (OMEGA * t).sin(), M0 * (OMEGA * t).cos())
}

/// A case: where the motion starts (link angles and rates, the pin on the
/// ring at the angle `contact`, world frame, from the ring's centre) and
/// the friction between pin and ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start {
    /// Link 1's angle phi1, rad.
    pub phi1: f64,
    /// Link 2's angle to link 1 (`psi + phi2`), rad.
    pub phi: f64,
    /// Their rates, rad/s.
    pub rates: Vector2<f64>,
    /// Direction of the contact point from the ring's centre, world frame, rad.
    pub contact: f64,
    /// Friction coefficient pin-ring (large: the dissertation's rolling throughout).
    pub mu: f64,
}

impl Default for Start {
    /// Link 1 horizontal, link 2 straight up, at rest, the pin at the
    /// bottom of the ring.
    fn default() -> Self {
        Start {
            phi1: 0.0,
            phi: FRAC_PI_2,
            rates: Vector2::zeros(),
            contact: -FRAC_PI_2,
            mu: MU,
        }
    }
}

impl Start {
    /// The dissertation's coordinates (phi1, psi, u, phi2) and rates (pin rolling).
    pub fn seed(&self) -> (Vector4<f64>, Vector4<f64>) {
        let psi = self.contact - self.phi1;
        let k = R2 / GAP;
        (
            Vector4::new(self.phi1, psi, GAP, self.phi - psi),
            Vector4::new(
                self.rates[0],
                -k * self.rates[1],
                0.0,
                (1.0 + k) * self.rates[1],
            ),
        )
    }
}

/// The default start in the dissertation's coordinates.
pub fn start() -> (Vector4<f64>, Vector4<f64>) {
    Start::default().seed()
}
