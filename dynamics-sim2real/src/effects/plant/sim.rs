//! A running simulation of a plant: integration with the drive efforts
//! held, stopping at each backlash contact switch (located on the dense
//! output) to change the contact mode.

use nalgebra::SVector;

use super::{Plant, PlantError, PlantState};
use crate::effects::Effect;
use dynamics_runtime::ode::{locate_event, Dopri5, OdeError, Step, Tolerances};
use dynamics_runtime::Robot;

/// A running simulation of a [`Plant`]: time, state and backlash contact
/// sides (-1, 0, +1 per joint).
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
