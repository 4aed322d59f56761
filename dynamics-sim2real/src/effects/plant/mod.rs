//! A robot with unmodelled effects attached: its state (the robot's q, qd
//! plus a motor side for elastic and backlash joints), its equations of
//! motion, and an integrator that locates backlash contact switches.
//!
//! - [`PlantState`] (`state.rs`): the state and its integrator norms;
//! - `forces.rs`: the equations of motion;
//! - `energy.rs`: the total mechanical energy;
//! - [`PlantSim`] (`sim.rs`): integration across backlash contact switches.

mod energy;
mod forces;
mod sim;
mod state;

pub use sim::{PlantSim, Switch};
pub use state::PlantState;

use nalgebra::SVector;
use thiserror::Error;

use super::{Effect, Tip};
use dynamics_runtime::{DynamicsError, Robot};

/// Why a plant could not be built or advanced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlantError {
    /// An effect names a joint the robot does not have.
    #[error(
        "effect {index} ({kind}): joint index {joint} is out of range (the robot has {n} joints)"
    )]
    NoSuchJoint {
        /// Position in the effect list.
        index: usize,
        /// Effect kind.
        kind: super::EffectKind,
        /// Joint index given.
        joint: usize,
        /// Number of joints.
        n: usize,
    },
    /// An effect names a link that carries no inertial parameters.
    #[error("effect {index} (inertial_parameters): link index {link} is out of range (the robot has {n} links with inertial parameters)")]
    NoSuchLink {
        /// Position in the effect list.
        index: usize,
        /// Link index given.
        link: usize,
        /// Number of links in `Robot::LINK_NAMES`.
        n: usize,
    },
    /// Two motor-side effects on one joint.
    #[error("joint {joint} has two motor-side effects (joint_elasticity/backlash); at most one")]
    TwoMotors {
        /// Joint index.
        joint: usize,
    },
    /// A parameter is not physical.
    #[error("effect {index}: {reason}")]
    BadParameter {
        /// Position in the effect list.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// The dynamics failed at time `t`.
    #[error("at t = {t:.6} s: {source}")]
    Dynamics {
        /// Time.
        t: f64,
        /// What failed.
        source: DynamicsError,
    },
    /// The integrator gave up at time `t`.
    #[error("at t = {t:.6} s: the integrator stopped ({reason})")]
    Integrator {
        /// Time.
        t: f64,
        /// Why.
        reason: String,
    },
}

/// A robot model with effects attached: the "real robot" of a simulation.
///
/// ```
/// use dynamics_sim2real::effects::{Effect, Plant};
/// use dynamics_runtime::ode::Tolerances;
/// dynamics_macros::robot! {
///     pub robot Wheel;
///     gravity = [0.0, 0.0, -9.81];
///     link base;
///     link disc { mass = 1.0; inertia = [0.1, 0.1, 0.1]; }
///     joint j = revolute(base -> disc) { transfer = [rot_z(q)]; }
/// }
/// // A spinning wheel with viscous friction slows down.
/// let plant = Plant::new(Wheel::default(), vec![Effect::ViscousFriction { joint: 0, fv: 0.1 }]).unwrap();
/// let mut sim = plant.start([0.0].into(), [1.0].into());
/// sim.advance(&plant, 1.0, &[0.0].into(), Tolerances::default()).unwrap();
/// assert!((sim.state.qd[0] - (-1.0f64).exp()).abs() < 1e-6); // qd = exp(-fv t / I)
/// ```
#[derive(Debug, Clone)]
pub struct Plant<R, const N: usize> {
    /// The rigid-body model.
    pub robot: R,
    /// The effects attached to it.
    pub effects: Vec<Effect>,
    motor: [Option<usize>; N],
    tip: Tip,
}

impl<R: Robot<N>, const N: usize> Plant<R, N> {
    /// Attaches `effects` to `robot`, checking joints and parameters.
    /// A friction correction may take away friction the robot's own model
    /// has (a URDF's `<dynamics damping friction>`), no more
    /// ([`Effect::within_nominal_friction`]); a payload may take away mass
    /// the model carries at the tip, no more than the tip body's
    /// ([`Effect::within_tip_body`]).
    pub fn new(robot: R, effects: Vec<Effect>) -> Result<Self, PlantError> {
        let (coulomb, viscous) = super::nominal_friction(&robot, &SVector::zeros());
        let tip_mass = Tip::body_mass::<R, N>(&robot);
        let mut motor = [None; N];
        for (index, e) in effects.iter().enumerate() {
            if let Some(joint) = e.joint() {
                if joint >= N {
                    return Err(PlantError::NoSuchJoint {
                        index,
                        kind: e.kind(),
                        joint,
                        n: N,
                    });
                }
                if e.has_motor() {
                    if motor[joint].is_some() {
                        return Err(PlantError::TwoMotors { joint });
                    }
                    motor[joint] = Some(index);
                }
            }
            e.validate_beside_friction(coulomb.as_slice(), viscous.as_slice())
                .or_else(|reason| e.within_tip_body(tip_mass).then_some(()).ok_or(reason))
                .map_err(|reason| PlantError::BadParameter { index, reason })?;
            if let Effect::InertialParameters { link, delta } = *e {
                super::inertial::physical(&robot, link, &delta).map_err(|err| match err {
                    None => PlantError::NoSuchLink {
                        index,
                        link,
                        n: R::LINK_NAMES.len(),
                    },
                    Some(reason) => PlantError::BadParameter { index, reason },
                })?;
            }
        }
        Ok(Plant {
            robot,
            effects,
            motor,
            tip: Tip::of::<R, N>(),
        })
    }

    /// The tip where payload and environment act.
    pub fn tip(&self) -> Tip {
        self.tip
    }

    /// A simulation starting at (q, qd) with every motor side in static
    /// equilibrium with gravity (drive springs pre-loaded, backlash in
    /// contact on the loaded side).
    pub fn start(&self, q: SVector<f64, N>, qd: SVector<f64, N>) -> PlantSim<N> {
        let g = self.robot.gravity(&q);
        let mut state = PlantState {
            q,
            qd,
            qm: SVector::zeros(),
            qmd: SVector::zeros(),
        };
        let mut contact = [0i8; N];
        for j in 0..N {
            let Some(k) = self.motor[j] else { continue };
            state.qmd[j] = qd[j];
            state.qm[j] = match self.effects[k] {
                Effect::JointElasticity { stiffness, .. } => q[j] + g[j] / stiffness,
                Effect::Backlash {
                    half_width,
                    contact_stiffness,
                    ..
                } => {
                    if g[j] > 0.0 {
                        contact[j] = 1;
                        q[j] + half_width + g[j] / contact_stiffness
                    } else if g[j] < 0.0 {
                        contact[j] = -1;
                        q[j] - half_width + g[j] / contact_stiffness
                    } else {
                        q[j]
                    }
                }
                _ => q[j],
            };
        }
        PlantSim {
            t: 0.0,
            state,
            contact,
            switches: Vec::new(),
        }
    }
}
