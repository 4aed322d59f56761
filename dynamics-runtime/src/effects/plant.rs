//! A robot with unmodelled effects attached: its state (the robot's q, qd
//! plus a motor side for elastic and backlash joints), its equations of
//! motion, and an integrator that locates backlash contact switches.

use nalgebra::{SMatrix, SVector, Vector3};
use thiserror::Error;

use super::{Effect, Tip};
use crate::ode::{locate_event, Dopri5, OdeError, OdeState, Step, Tolerances};
use crate::{DynamicsError, Robot};

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

/// The state of a plant: the robot's (link-side) q, qd and the motor side
/// `qm`, `qmd` of joints with a motor effect (unused entries stay zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantState<const N: usize> {
    /// Link-side positions.
    pub q: SVector<f64, N>,
    /// Link-side velocities.
    pub qd: SVector<f64, N>,
    /// Motor-side positions.
    pub qm: SVector<f64, N>,
    /// Motor-side velocities.
    pub qmd: SVector<f64, N>,
}

impl<const N: usize> OdeState for PlantState<N> {
    fn axpy(&self, a: f64, x: &Self) -> Self {
        PlantState {
            q: self.q + x.q * a,
            qd: self.qd + x.qd * a,
            qm: self.qm + x.qm * a,
            qmd: self.qmd + x.qmd * a,
        }
    }
    fn error_norm(e: &Self, y0: &Self, y1: &Self, rtol: f64, atol: f64) -> f64 {
        let parts = [
            (&e.q, &y0.q, &y1.q),
            (&e.qd, &y0.qd, &y1.qd),
            (&e.qm, &y0.qm, &y1.qm),
            (&e.qmd, &y0.qmd, &y1.qmd),
        ];
        let mut s = 0.0;
        for (e, a, b) in parts {
            for i in 0..N {
                let sc = atol + rtol * a[i].abs().max(b[i].abs());
                s += (e[i] / sc).powi(2);
            }
        }
        (s / (4 * N).max(1) as f64).sqrt()
    }
    fn first_non_finite(&self) -> Option<usize> {
        [self.q, self.qd, self.qm, self.qmd]
            .iter()
            .flat_map(|v| v.iter())
            .position(|x| !x.is_finite())
    }
    fn zero() -> Self {
        PlantState {
            q: SVector::zeros(),
            qd: SVector::zeros(),
            qm: SVector::zeros(),
            qmd: SVector::zeros(),
        }
    }
}

/// A robot model with effects attached: the "real robot" of a simulation.
///
/// ```
/// use dynamics_runtime::effects::{Effect, Plant};
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

/// A running simulation of a [`Plant`]: time, state and backlash contact
/// sides (-1, 0, +1 per joint).
///
/// ```
/// use dynamics_runtime::effects::{Effect, Plant};
/// use dynamics_runtime::ode::Tolerances;
/// dynamics_macros::robot! {
///     pub robot Wheel;
///     gravity = [0.0, 0.0, -9.81];
///     link base;
///     link disc { mass = 1.0; inertia = [0.1, 0.1, 0.1]; }
///     joint j = revolute(base -> disc) { transfer = [rot_z(q)]; }
/// }
/// // A wheel driven through a gear with 0.01 rad of play: a torque step
/// // first closes the gap, then the contact takes the load.
/// let backlash = Effect::Backlash {
///     joint: 0, half_width: 0.01, motor_inertia: 0.01,
///     contact_stiffness: 1e4, contact_damping: 5.0,
/// };
/// let plant = Plant::new(Wheel::default(), vec![backlash]).unwrap();
/// let mut sim = plant.start([0.0].into(), [0.0].into());
/// assert_eq!(sim.contact, [0]); // no gravity about z: centred in the gap
/// sim.advance(&plant, 0.2, &[1.0].into(), Tolerances::default()).unwrap();
/// let first = sim.switches[0];
/// assert_eq!((first.joint, first.contact), (0, 1));
/// assert!((first.deflection - 0.01).abs() < 1e-9); // located on the edge of the gap
/// assert!(sim.state.qd[0] > 0.0); // the link moves once in contact
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PlantSim<const N: usize> {
    /// Current time.
    pub t: f64,
    /// Current state.
    pub state: PlantState<N>,
    /// Backlash contact side per joint.
    pub contact: [i8; N],
    /// Contact switches located so far.
    pub switches: Vec<Switch>,
}

/// A backlash contact switch located on the dense output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    /// Time of the switch.
    pub t: f64,
    /// Joint.
    pub joint: usize,
    /// Contact side entered (-1, 0, +1).
    pub contact: i8,
    /// Motor-link deflection `qm - q` at the switch (+-delta up to the
    /// location tolerance).
    pub deflection: f64,
    /// Its rate `qmd - qd`.
    pub rate: f64,
}

impl<R: Robot<N>, const N: usize> Plant<R, N> {
    /// Attaches `effects` to `robot`, checking joints and parameters.
    pub fn new(robot: R, effects: Vec<Effect>) -> Result<Self, PlantError> {
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
            e.validate()
                .map_err(|reason| PlantError::BadParameter { index, reason })?;
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

    /// The time derivative of the state under drive efforts `tau` (applied
    /// to the motor side of motor joints, to the link elsewhere).
    pub fn derivative(
        &self,
        x: &PlantState<N>,
        tau: &SVector<f64, N>,
        contact: &[i8; N],
    ) -> Result<PlantState<N>, DynamicsError> {
        let (a, f) = self.mass_and_forces(&x.q, &x.qd);
        let mut u = *tau;
        let mut qmdd = SVector::<f64, N>::zeros();
        for j in 0..N {
            let Some(k) = self.motor[j] else { continue };
            let e = &self.effects[k];
            let passed = e.transmitted(x.qm[j] - x.q[j], x.qmd[j] - x.qd[j], contact[j]);
            let jm = match *e {
                Effect::JointElasticity { motor_inertia, .. }
                | Effect::Backlash { motor_inertia, .. } => motor_inertia,
                _ => 1.0,
            };
            u[j] = passed;
            qmdd[j] = (tau[j] - passed) / jm;
        }
        let chol = a
            .cholesky()
            .ok_or_else(|| DynamicsError::SingularMassMatrix {
                q: x.q.iter().copied().collect(),
            })?;
        let qdd = chol.solve(&(f + u));
        if let Some(index) = qdd.iter().position(|v| !v.is_finite()) {
            return Err(DynamicsError::Diverged {
                quantity: "qdd",
                index,
            });
        }
        Ok(PlantState {
            q: x.qd,
            qd: qdd,
            qm: x.qmd,
            qmd: qmdd,
        })
    }

    /// The link-side inertia (robot + armature + payload) and the forces
    /// other than the drive: Q(0) + Qqt1 + Qqt2 + friction + payload
    /// gravity and velocity terms + environment resistance.
    pub fn mass_and_forces(
        &self,
        q: &SVector<f64, N>,
        qd: &SVector<f64, N>,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let terms = self.robot.motion_terms(q, qd);
        let mut a = terms.a;
        let mut f = terms.bias();
        for e in &self.effects {
            match *e {
                Effect::CoulombFriction { joint, .. }
                | Effect::ViscousFriction { joint, .. }
                | Effect::StribeckFriction { joint, .. } => f[joint] += e.joint_force(qd[joint]),
                Effect::Armature { joint, inertia } => a[(joint, joint)] += inertia,
                Effect::PayloadMass { mass } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    let bias = self.tip.bias_acceleration(&self.robot, q, qd);
                    let g = Vector3::from(R::GRAVITY);
                    a += jac.transpose() * jac * mass;
                    f += jac.transpose() * ((g - bias) * mass);
                }
                Effect::EnvironmentResistance { .. } => {
                    let (_, jac) = self.tip.position_jacobian(&self.robot, q);
                    f += jac.transpose() * e.resistance(&(jac * qd));
                }
                _ => {}
            }
        }
        (a, f)
    }

    /// Total mechanical energy: the robot's, the payload's, the rotors' and
    /// the drive springs' (for energy-balance tests).
    pub fn energy(&self, x: &PlantState<N>, contact: &[i8; N]) -> f64 {
        let mut e = self.robot.total_energy(&x.q, &x.qd);
        for eff in &self.effects {
            match *eff {
                Effect::Armature { joint, inertia } => e += 0.5 * inertia * x.qd[joint].powi(2),
                Effect::PayloadMass { mass } => {
                    let (p, jac) = self.tip.position_jacobian(&self.robot, &x.q);
                    let g = Vector3::from(R::GRAVITY);
                    e += 0.5 * mass * (jac * x.qd).norm_squared() - mass * g.dot(&p);
                }
                Effect::JointElasticity {
                    joint,
                    stiffness,
                    motor_inertia,
                    ..
                } => {
                    e += 0.5 * motor_inertia * x.qmd[joint].powi(2)
                        + 0.5 * stiffness * (x.qm[joint] - x.q[joint]).powi(2)
                }
                Effect::Backlash {
                    joint,
                    half_width,
                    motor_inertia,
                    contact_stiffness,
                    ..
                } => {
                    let d = x.qm[joint] - x.q[joint];
                    let pen = match contact[joint] {
                        1 => d - half_width,
                        -1 => d + half_width,
                        _ => 0.0,
                    };
                    e += 0.5 * motor_inertia * x.qmd[joint].powi(2)
                        + 0.5 * contact_stiffness * pen * pen
                }
                _ => {}
            }
        }
        e
    }

    /// Backlash watch functions of joint `j` in contact mode `mode`: each
    /// `(g, next_mode)` with g >= 0 while the mode holds.
    fn watches(&self, j: usize, mode: i8, x: &PlantState<N>) -> [(f64, i8); 2] {
        let Some(Effect::Backlash { half_width, .. }) = self.motor[j].map(|k| self.effects[k])
        else {
            return [(1.0, mode), (1.0, mode)];
        };
        let e = x.qm[j] - x.q[j];
        match mode {
            1 => [(e - half_width, 0), (1.0, 1)],
            -1 => [(-(e + half_width), 0), (1.0, -1)],
            _ => [(half_width - e, 1), (e + half_width, -1)],
        }
    }
}

impl<const N: usize> PlantSim<N> {
    /// Integrates to `t1` with the drive efforts `tau` held constant,
    /// stopping at every backlash contact switch (located to 1e-12 s on the
    /// dense output) to change the contact mode and restart.
    pub fn advance<R: Robot<N>>(
        &mut self,
        plant: &Plant<R, N>,
        t1: f64,
        tau: &SVector<f64, N>,
        tol: Tolerances,
    ) -> Result<(), PlantError> {
        let mut guard = 0;
        while self.t < t1 {
            guard += 1;
            if guard > 100_000 {
                return Err(PlantError::Integrator {
                    t: self.t,
                    reason: "more than 100000 contact switches in one interval (chattering)".into(),
                });
            }
            let contact = self.contact;
            let t0 = self.t;
            let mut rhs = |_t: f64, x: &PlantState<N>| plant.derivative(x, tau, &contact);
            let mut ode = Dopri5::new(t0, self.state, tol);
            let mut event: Option<(f64, usize, i8, Step<PlantState<N>>)> = None;
            let run = ode.run(&mut rhs, t1, |step| {
                for j in 0..N {
                    let w0 = plant.watches(j, contact[j], &step.y0);
                    let w1 = plant.watches(j, contact[j], &step.y1);
                    for k in 0..2 {
                        if w1[k].0 < 0.0 {
                            let te = if w0[k].0 > 0.0 {
                                let mut g = |_t: f64, x: &PlantState<N>| {
                                    plant.watches(j, contact[j], x)[k].0
                                };
                                locate_event(step, &mut g, w0[k].0, w1[k].0, 1e-12)
                            } else {
                                step.t0
                            };
                            if event.is_none_or(|e| te < e.0) {
                                event = Some((te, j, w1[k].1, *step));
                            }
                        }
                    }
                }
                event.is_none()
            });
            match run {
                Ok(()) => {}
                Err(OdeError::Rhs(source)) => {
                    return Err(PlantError::Dynamics { t: ode.t(), source })
                }
                Err(OdeError::StepSizeCollapsed { t, h }) => {
                    return Err(PlantError::Integrator {
                        t,
                        reason: format!("step size collapsed to {h:e} s"),
                    })
                }
                Err(OdeError::TooManySteps { t }) => {
                    return Err(PlantError::Integrator {
                        t,
                        reason: "too many steps".into(),
                    })
                }
            }
            match event {
                Some((te, j, mode, step)) => {
                    self.state = step.at(te);
                    self.t = te;
                    self.contact[j] = mode;
                    self.switches.push(Switch {
                        t: te,
                        joint: j,
                        contact: mode,
                        deflection: self.state.qm[j] - self.state.q[j],
                        rate: self.state.qmd[j] - self.state.qd[j],
                    });
                }
                None => {
                    self.state = *ode.y();
                    self.t = t1;
                }
            }
        }
        Ok(())
    }
}
