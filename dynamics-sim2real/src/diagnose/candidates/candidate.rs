//! The candidate effects, each with the regressor columns it adds to the
//! torque residual (linear in its parameters), or, for elasticity and
//! backlash, a motor-side simulation (`motor.rs`) driven by the measured
//! effort and link motion whose transmitted effort replaces the rigid
//! joint's.

use nalgebra::{SVector, Vector3};

use super::basis::{Basis, Frame};
use super::grids::{ALPHA_GRID, COULOMB_WIDTHS, STRIBECK_GRID};
use super::row_series::{coulomb_law, stribeck_law};
use crate::diagnose::candidates::shift::{late_effort_column, late_motion_column};
use crate::diagnose::signals::Signals;
use crate::effects::{Effect, EffectKind, SIGN_SMOOTHING};

/// Which stream of a log a delay makes late.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Channel {
    /// Positions and velocities late together against the effort.
    All,
    /// The position stream late against velocity and effort.
    Positions,
    /// The effort stream late against position and velocity.
    Effort,
}

impl Channel {
    /// The channel's name as the report writes it.
    pub fn name(self) -> &'static str {
        match self {
            Channel::All => "all",
            Channel::Positions => "positions",
            Channel::Effort => "effort",
        }
    }
}

impl std::str::FromStr for Channel {
    type Err = Unnamed;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [Channel::All, Channel::Positions, Channel::Effort]
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| Unnamed::Channel(s.to_string()))
    }
}

/// Why a report entry names no candidate ([`Candidate::named`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Unnamed {
    /// A kind with no single-effect candidate (`none`, link inertial
    /// corrections).
    #[error("`{0}` has no single-effect candidate")]
    Kind(EffectKind),
    /// A joint effect without a joint of the robot.
    #[error("no joint of the robot named")]
    Joint,
    /// A grid value the kind needs is missing or not finite.
    #[error("parameter `{0}` is missing or not a finite number")]
    Missing(&'static str),
    /// A late channel that is none of `all`, `positions`, `effort`.
    #[error("channel `{0}` is none of all, positions, effort")]
    Channel(String),
}

impl std::fmt::Display for Channel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// A candidate: kind, place, and the fixed value of a nonlinear parameter
/// searched on a grid (Stribeck velocity, resistance exponent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Candidate {
    /// Coulomb friction at a joint whose sign turns over velocity width
    /// vw (`tanh(v / vw)`).
    Coulomb(usize, f64),
    /// Viscous friction at a joint.
    Viscous(usize),
    /// Stribeck friction at a joint with Stribeck velocity vs.
    Stribeck(usize, f64),
    /// Rotor inertia at a joint.
    Armature(usize),
    /// Point mass at the tip, relative to the model: negative when the
    /// robot lacks mass the model carries there (a hand that is absent),
    /// down to the modelled mass of the tip's body.
    Payload,
    /// The same with its centre of mass away from the tip frame's origin:
    /// the mass and its first moments about that origin (mass times the
    /// offset, in the tip's frame), linear in both; the point mass's
    /// second moments are those of the mass at the centre it carries (in
    /// the tip's frame, m; the selection moves it to the centre the
    /// explanation finds, `select/recentre.rs`): the exact point mass
    /// where the two agree. Offered where the tip is a frame.
    PayloadCom([f64; 3]),
    /// Resistance at the tip with exponent alpha.
    Environment(f64),
    /// Encoder offset at a joint.
    EncoderOffset(usize),
    /// Delay of the measured motion (positions and velocities late
    /// together against the effort); its column is the secant of the
    /// measured effort over the delay it holds, s (0: the tangent, its
    /// rate; `late.rs`).
    TimeDelay(f64),
    /// The position channel late against velocity and effort: offered only
    /// when the measured positions lag the integral of the independently
    /// measured velocities (`late.rs`).
    LatePositions,
    /// The effort channel late against position and velocity (which are
    /// consistent with each other): the measured effort is the model's
    /// `delay` earlier (`late.rs`); its column is the secant of the model's
    /// effort over the delay it holds, s (0: the tangent, its rate).
    LateEffort(f64),
    /// Two-mass elastic joint.
    Elasticity(usize),
    /// Dead zone between motor and link.
    Backlash(usize),
    /// Effort sensor scale at a joint (fitted as scale - 1).
    EffortScale(usize),
    /// Effort sensor offset at a joint.
    EffortOffset(usize),
    /// A spring at a joint: stiffness and preload (the effort at q = 0). It
    /// nests the effort offset (stiffness 0) and shares its family.
    Spring(usize),
    /// Inertial corrections of a link (index into `Robot::LINK_NAMES`):
    /// columns from the inertial regressor (`links.rs`), only within the
    /// compound explanation.
    Inertial(usize),
}

impl Candidate {
    /// The candidate a report entry names (the inverse of the report's
    /// entries: every place that reads an entry back goes through here):
    /// its `kind`, its `joint` (index; `None`: none named, or not the
    /// robot's), the late `channel` of a delay (`None`: `all`), and its
    /// parameters by name through `value` for the values searched on a
    /// grid: Coulomb friction's `vw` (sharp when absent), Stribeck's `vs`,
    /// the resistance's `alpha`, and a late effort's `delay`.
    ///
    /// ```
    /// use dynamics_sim2real::diagnose::{Candidate, Channel};
    /// use dynamics_sim2real::effects::EffectKind;
    /// let vw = |n: &str| (n == "vw").then_some(0.15);
    /// let c = Candidate::named(EffectKind::CoulombFriction, Some(1), None, &vw);
    /// assert_eq!(c, Ok(Candidate::Coulomb(1, 0.15)));
    /// let d = |n: &str| (n == "delay").then_some(0.01);
    /// let late = Candidate::named(EffectKind::TimeDelay, None, Some(Channel::Effort), &d);
    /// assert_eq!(late, Ok(Candidate::LateEffort(0.01)));
    /// ```
    pub fn named(
        kind: EffectKind,
        joint: Option<usize>,
        channel: Option<Channel>,
        value: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<Candidate, Unnamed> {
        let j = || joint.ok_or(Unnamed::Joint);
        let grid = |name: &'static str| {
            value(name)
                .filter(|v| v.is_finite())
                .ok_or(Unnamed::Missing(name))
        };
        Ok(match kind {
            EffectKind::None | EffectKind::InertialParameters => return Err(Unnamed::Kind(kind)),
            EffectKind::CoulombFriction => {
                Candidate::Coulomb(j()?, grid("vw").unwrap_or(SIGN_SMOOTHING))
            }
            EffectKind::ViscousFriction => Candidate::Viscous(j()?),
            EffectKind::StribeckFriction => Candidate::Stribeck(j()?, grid("vs")?),
            EffectKind::Armature => Candidate::Armature(j()?),
            // A centre of mass reported as a number: the payload with it.
            EffectKind::PayloadMass => match ["com_x", "com_y", "com_z"].map(value) {
                [Some(x), Some(y), Some(z)] if [x, y, z].iter().all(|v| v.is_finite()) => {
                    Candidate::PayloadCom([x, y, z])
                }
                _ => Candidate::Payload,
            },
            EffectKind::EnvironmentResistance => Candidate::Environment(grid("alpha")?),
            EffectKind::EncoderOffset => Candidate::EncoderOffset(j()?),
            EffectKind::TimeDelay => match channel {
                None | Some(Channel::All) => Candidate::TimeDelay(grid("delay").unwrap_or(0.0)),
                Some(Channel::Positions) => Candidate::LatePositions,
                Some(Channel::Effort) => Candidate::LateEffort(grid("delay")?),
            },
            EffectKind::JointElasticity => Candidate::Elasticity(j()?),
            EffectKind::Backlash => Candidate::Backlash(j()?),
            EffectKind::EffortScale => Candidate::EffortScale(j()?),
            EffectKind::EffortOffset => Candidate::EffortOffset(j()?),
            EffectKind::JointSpring => Candidate::Spring(j()?),
        })
    }

    /// The late channel a delay candidate names: `all` (positions and
    /// velocities late together against the effort), `positions` or
    /// `effort`; `None` for every other candidate.
    pub fn channel(self) -> Option<Channel> {
        match self {
            Candidate::TimeDelay(_) => Some(Channel::All),
            Candidate::LatePositions => Some(Channel::Positions),
            Candidate::LateEffort(_) => Some(Channel::Effort),
            _ => None,
        }
    }

    /// Every candidate for a robot with N joints.
    pub fn all<const N: usize>(kinds: &[EffectKind]) -> Vec<Candidate> {
        let mut out = Vec::new();
        let want = |k: EffectKind| kinds.is_empty() || kinds.contains(&k);
        for j in 0..N {
            if want(EffectKind::CoulombFriction) {
                out.extend(COULOMB_WIDTHS.iter().map(|&w| Candidate::Coulomb(j, w)));
            }
            if want(EffectKind::ViscousFriction) {
                out.push(Candidate::Viscous(j));
            }
            if want(EffectKind::StribeckFriction) {
                out.extend(STRIBECK_GRID.iter().map(|&v| Candidate::Stribeck(j, v)));
            }
            if want(EffectKind::Armature) {
                out.push(Candidate::Armature(j));
            }
            if want(EffectKind::EncoderOffset) {
                out.push(Candidate::EncoderOffset(j));
            }
            if want(EffectKind::JointElasticity) {
                out.push(Candidate::Elasticity(j));
            }
            if want(EffectKind::Backlash) {
                out.push(Candidate::Backlash(j));
            }
            if want(EffectKind::EffortScale) {
                out.push(Candidate::EffortScale(j));
            }
            if want(EffectKind::EffortOffset) {
                out.push(Candidate::EffortOffset(j));
            }
            if want(EffectKind::JointSpring) {
                out.push(Candidate::Spring(j));
            }
        }
        if want(EffectKind::PayloadMass) {
            out.push(Candidate::Payload);
            out.push(Candidate::PayloadCom([0.0; 3]));
        }
        if want(EffectKind::EnvironmentResistance) {
            out.extend(ALPHA_GRID.iter().map(|&a| Candidate::Environment(a)));
        }
        if want(EffectKind::TimeDelay) {
            out.push(Candidate::TimeDelay(0.0));
        }
        out
    }

    /// Its kind.
    pub fn kind(&self) -> EffectKind {
        match self {
            Candidate::Coulomb(..) => EffectKind::CoulombFriction,
            Candidate::Viscous(_) => EffectKind::ViscousFriction,
            Candidate::Stribeck(..) => EffectKind::StribeckFriction,
            Candidate::Armature(_) => EffectKind::Armature,
            Candidate::Payload | Candidate::PayloadCom(_) => EffectKind::PayloadMass,
            Candidate::Environment(_) => EffectKind::EnvironmentResistance,
            Candidate::EncoderOffset(_) => EffectKind::EncoderOffset,
            Candidate::TimeDelay(_) | Candidate::LatePositions | Candidate::LateEffort(_) => {
                EffectKind::TimeDelay
            }
            Candidate::Elasticity(_) => EffectKind::JointElasticity,
            Candidate::Backlash(_) => EffectKind::Backlash,
            Candidate::EffortScale(_) => EffectKind::EffortScale,
            Candidate::EffortOffset(_) => EffectKind::EffortOffset,
            Candidate::Spring(_) => EffectKind::JointSpring,
            Candidate::Inertial(_) => EffectKind::InertialParameters,
        }
    }

    /// Whether it is a Coulomb friction wider than the sharp one: its width
    /// is one more (grid) parameter, which it must earn against the sharp
    /// one by the nesting margin (`rank.rs`, `compound/select.rs`).
    pub fn widened(&self) -> bool {
        matches!(*self, Candidate::Coulomb(_, w) if w > SIGN_SMOOTHING)
    }

    /// Its joint, for joint effects.
    pub fn joint(&self) -> Option<usize> {
        match *self {
            Candidate::Coulomb(j, _)
            | Candidate::Viscous(j)
            | Candidate::Stribeck(j, _)
            | Candidate::Armature(j)
            | Candidate::EncoderOffset(j)
            | Candidate::Elasticity(j)
            | Candidate::Backlash(j)
            | Candidate::EffortScale(j)
            | Candidate::EffortOffset(j)
            | Candidate::Spring(j) => Some(j),
            _ => None,
        }
    }

    /// The joint outside which its [`Candidate::columns`] are zero (a
    /// joint's own friction, rotor, effort scale or offset, spring), or
    /// `None` where they may reach any joint.
    pub(crate) fn local_joint(&self) -> Option<usize> {
        match *self {
            Candidate::Coulomb(j, _)
            | Candidate::Viscous(j)
            | Candidate::Stribeck(j, _)
            | Candidate::Armature(j)
            | Candidate::EffortScale(j)
            | Candidate::EffortOffset(j)
            | Candidate::Spring(j) => Some(j),
            _ => None,
        }
    }

    /// Names of its linear parameters and whether each must be >= 0.
    pub fn linear_parameters(&self) -> &'static [(&'static str, bool)] {
        match self {
            Candidate::Coulomb(..) => &[("fc", true)],
            Candidate::Viscous(_) => &[("fv", true)],
            Candidate::Stribeck(..) => &[("fc", true), ("fs_minus_fc", true)],
            Candidate::Armature(_) => &[("inertia", true)],
            // Relative to the model: negative where the model carries mass
            // at the tip that the robot does not (`columns::lower_bounds`).
            Candidate::Payload => &[("mass", false)],
            // The report gives the centre of mass (`Fit::parameters`).
            Candidate::PayloadCom(_) => &[
                ("mass", false),
                ("mass_com_x", false),
                ("mass_com_y", false),
                ("mass_com_z", false),
            ],
            Candidate::Environment(_) => &[("mu", true)],
            Candidate::EncoderOffset(_) => &[("offset", false)],
            Candidate::TimeDelay(_) | Candidate::LatePositions | Candidate::LateEffort(_) => {
                &[("delay", true)]
            }
            Candidate::EffortScale(_) => &[("scale_minus_one", false)],
            Candidate::EffortOffset(_) => &[("offset", false)],
            Candidate::Spring(_) => &[("stiffness", true), ("preload", false)],
            Candidate::Elasticity(_) | Candidate::Backlash(_) | Candidate::Inertial(_) => &[],
        }
    }

    /// Regressor columns at sample `k`: the extra drive effort per unit of
    /// each linear parameter.
    pub fn columns<const N: usize>(
        &self,
        sig: &Signals<N>,
        basis: &Basis<N>,
        k: usize,
    ) -> [SVector<f64, N>; 4] {
        let mut c = [SVector::zeros(); 4];
        match *self {
            Candidate::Coulomb(j, w) => c[0][j] = basis.series.law(sig, coulomb_law(w), k, j),
            Candidate::Viscous(j) => c[0][j] = sig.motion.qd_at(k, j),
            Candidate::Stribeck(j, vs) => {
                c[0][j] = basis.series.law(sig, coulomb_law(SIGN_SMOOTHING), k, j);
                c[1][j] = basis.series.law(sig, stribeck_law(vs), k, j);
            }
            Candidate::Armature(j) => c[0][j] = basis.series.qdd(sig, k, j),
            Candidate::Payload => {
                let t = basis.tip_at(k);
                c[0] = t.jac.transpose() * (t.acc - basis.gravity)
            }
            // A point at r = R c off the tip's origin o moves with
            // a = a_o + alpha x r + w x (w x r), and its Jacobian is
            // J_o - [r]x J_w: the effort m J^T (a - g), to first order in
            // the first moment m c, adds J_o^T (alpha x r + w x (w x r))
            // + J_w^T (r x (a_o - g)) per unit of it; the rest,
            // J_w^T (r x (alpha x r + w x (w x r))) per unit of mass, is
            // taken at the centre c0 the candidate carries.
            Candidate::PayloadCom(c0) => {
                let t = basis.tip_at(k);
                let f = t.acc - basis.gravity;
                c[0] = t.jac.transpose() * f;
                if let Some(Frame { rot, jac_w, alpha }) = t.frame {
                    let w = jac_w * sig.qd(k);
                    let lin = |u: &Vector3<f64>| alpha.cross(u) + w.cross(&w.cross(u));
                    for i in 0..3 {
                        let u = rot.column(i).into_owned();
                        c[i + 1] = t.jac.transpose() * lin(&u) + jac_w.transpose() * u.cross(&f);
                    }
                    let r = rot * Vector3::from(c0);
                    c[0] += jac_w.transpose() * r.cross(&lin(&r));
                }
            }
            Candidate::Environment(alpha) => {
                let jac = basis.tip_at(k).jac;
                let v = jac * sig.qd(k);
                let s = v.norm();
                if s > 0.0 {
                    c[0] = jac.transpose() * (v * s.powf(alpha - 1.0));
                }
            }
            Candidate::EncoderOffset(j) => c[0] = -basis.k_column(k, j),
            // The motion d late: the model misses d times the effort's rate
            // (its secant over the delay held).
            Candidate::TimeDelay(d) => c[0] = late_motion_column(sig, k, d),
            // Positions d late: the model is evaluated at q - d qd, and
            // misses d K qd.
            Candidate::LatePositions => c[0] = basis.k(k) * sig.qd(k),
            // The effort d late: the model's effort d earlier, which misses
            // -d times its rate.
            Candidate::LateEffort(d) => c[0] = late_effort_column(sig, k, d),
            Candidate::EffortScale(j) => c[0][j] = sig.model[k][j],
            Candidate::EffortOffset(j) => c[0][j] = 1.0,
            // The drive holds the spring: stiffness q + preload.
            Candidate::Spring(j) => {
                c[0][j] = sig.motion.q_at(k, j);
                c[1][j] = 1.0;
            }
            Candidate::Elasticity(_) | Candidate::Backlash(_) | Candidate::Inertial(_) => {}
        }
        c
    }

    /// The effect with fitted linear parameters `theta`.
    pub fn effect(&self, theta: &[f64]) -> Option<Effect> {
        let p = |i: usize| theta.get(i).copied().unwrap_or(0.0);
        Some(match *self {
            Candidate::Coulomb(joint, vw) => Effect::CoulombFriction {
                joint,
                fc: p(0),
                vw,
            },
            Candidate::Viscous(joint) => Effect::ViscousFriction { joint, fv: p(0) },
            Candidate::Stribeck(joint, vs) => Effect::StribeckFriction {
                joint,
                fc: p(0),
                fs: p(0) + p(1),
                vs,
            },
            Candidate::Armature(joint) => Effect::Armature {
                joint,
                inertia: p(0),
            },
            Candidate::Payload => Effect::PayloadMass {
                mass: p(0),
                com: [0.0; 3],
            },
            Candidate::PayloadCom(_) => Effect::PayloadMass {
                mass: p(0),
                com: payload_com(theta),
            },
            Candidate::Environment(alpha) => Effect::EnvironmentResistance { mu: p(0), alpha },
            Candidate::EncoderOffset(joint) => Effect::EncoderOffset {
                joint,
                offset: p(0),
            },
            Candidate::TimeDelay(_) | Candidate::LatePositions => Effect::TimeDelay { delay: p(0) },
            // The motion early against the effort: a negative delay, which
            // only the held-out simulation reads (`horizon.rs`).
            Candidate::LateEffort(_) => Effect::TimeDelay { delay: -p(0) },
            Candidate::EffortScale(joint) => Effect::EffortScale {
                joint,
                scale: 1.0 + p(0),
            },
            Candidate::EffortOffset(joint) => Effect::EffortOffset {
                joint,
                offset: p(0),
            },
            Candidate::Spring(joint) => Effect::JointSpring {
                joint,
                stiffness: p(0),
                preload: p(1),
            },
            Candidate::Elasticity(_) | Candidate::Backlash(_) | Candidate::Inertial(_) => {
                return None
            }
        })
    }
}

/// The centre of mass of a payload fitted as mass and first moments
/// (`theta = [m, m c_x, m c_y, m c_z]`): the first moments over the mass,
/// zero where the mass is zero.
///
/// ```
/// use dynamics_sim2real::diagnose::payload_com;
/// assert_eq!(payload_com(&[-0.5, 0.01, 0.0, 0.035]), [-0.02, -0.0, -0.07]);
/// assert_eq!(payload_com(&[0.0, 0.01, 0.0, 0.0]), [0.0; 3]);
/// ```
pub fn payload_com(theta: &[f64]) -> [f64; 3] {
    let p = |i: usize| theta.get(i).copied().unwrap_or(0.0);
    let m = p(0);
    if m == 0.0 || !m.is_finite() {
        return [0.0; 3];
    }
    [p(1) / m, p(2) / m, p(3) / m]
}

/// The part of a delay's column at sample `k` that the model's own effort
/// carries, for the channels whose column is a rate of the effort: the
/// model effort's rate for the motion late (`time_delay`, channel `all`),
/// minus it for the effort late (its column is minus the effort's
/// secant); `None` for every other candidate (the `positions` column,
/// `K qd`, is the model's own through and through). Zero where the
/// model's rate is not finite.
///
/// A late stream shifts the whole effort: the part the model predicts
/// (inertia, gravity, Coriolis) as much as what it misses; a lag of what
/// it misses alone (a friction whose force lags its velocity reversals)
/// does not show in this part (`evaluate/confirm.rs`).
pub fn model_part<const N: usize>(
    sig: &Signals<N>,
    k: usize,
    c: Candidate,
) -> Option<SVector<f64, N>> {
    let sign = match c {
        Candidate::TimeDelay(_) => 1.0,
        Candidate::LateEffort(_) => -1.0,
        _ => return None,
    };
    let rate = sig.model_rate(k);
    Some(if rate.iter().all(|x| x.is_finite()) {
        rate * sign
    } else {
        SVector::zeros()
    })
}
