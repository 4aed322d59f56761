//! The design as JSON: the coefficients (enough to rebuild the motion),
//! the criterion's figures, the limit check and the predicted
//! identifiability.

use nalgebra::SVector;
use serde::{Serialize, Serializer};

use super::{Check, Clearance, Criterion, Design, ExciteError, Figures, Identifiability, Minimum};
use dynamics_runtime::Robot;

/// Serialises a fixed-size vector as a JSON array.
pub(crate) fn vector<S: Serializer, const N: usize>(
    v: &SVector<f64, N>,
    s: S,
) -> Result<S::Ok, S::Error> {
    s.collect_seq(v.iter())
}

/// The report of a design (what `dynamics excite --json` writes).
///
/// `q_j(t) = q0[j] + sum_k sin[k][j] sin((k+1) w t) + cos[k][j] cos((k+1) w t)`,
/// `w = 2 pi / period`.
///
/// ```
/// use dynamics_sim2real::excite::{design, DesignReport, Limits, Options};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let mut o = Options::new(4.0);
/// o.evaluations = 40;
/// let d = design(&p, &Limits::new([-1.0], [1.0], [3.0], [50.0]), &o).unwrap();
/// let r = DesignReport::of(&p, &d, 100.0, None).unwrap();
/// assert_eq!(r.joints, ["j"]);
/// assert!(r.check.position && r.identifiability.parameters.len() > 1);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignReport<const N: usize> {
    /// The robot's name.
    pub robot: String,
    /// Joint names in coordinate order.
    pub joints: Vec<String>,
    /// Duration, s.
    pub duration: f64,
    /// Period, s.
    pub period: f64,
    /// Fundamental frequency, Hz.
    pub fundamental_hz: f64,
    /// Start and end pose.
    #[serde(serialize_with = "vector")]
    pub q0: SVector<f64, N>,
    /// Sine coefficients, `sin[k][j]` for harmonic `k + 1` of joint `j`.
    pub sin: Vec<Vec<f64>>,
    /// Cosine coefficients, same layout.
    pub cos: Vec<Vec<f64>>,
    /// The criterion minimised.
    pub criterion: Criterion,
    /// Its figures on the base regressor with friction, rotor inertia and
    /// offset columns.
    pub figures: Figures,
    /// Number of base parameters.
    pub base_parameters: usize,
    /// The limits used (margin applied): lower, upper, velocity, effort.
    pub limits: [Vec<f64>; 4],
    /// The acceleration limit used, if any.
    pub acceleration_limit: Option<Vec<f64>>,
    /// The check of the samples at the output rate.
    pub check: Check<N>,
    /// The clearance asked of the link frames (`null`: not checked).
    pub clearance: Option<Clearance>,
    /// The smallest clearances along the samples at the output rate, and
    /// where (`null`: not checked).
    pub min_clearance: Option<Minimum>,
    /// Evaluations the search spent.
    pub evaluations: usize,
    /// Predicted identifiability over the whole duration.
    pub identifiability: Identifiability,
}

impl<const N: usize> DesignReport<N> {
    /// The report of `design` of `robot` sampled at `rate` Hz; the
    /// identifiability at `noise` per joint when given, else at 0.002 of
    /// each joint's peak effort.
    pub fn of<R: Robot<N>>(
        robot: &R,
        design: &Design<N>,
        rate: f64,
        noise: Option<SVector<f64, N>>,
    ) -> Result<Self, ExciteError> {
        let m = &design.motion;
        let v = |x: &SVector<f64, N>| x.iter().copied().collect::<Vec<f64>>();
        let l = &design.limits;
        Ok(DesignReport {
            robot: R::NAME.to_string(),
            joints: R::JOINT_NAMES.iter().map(|s| s.to_string()).collect(),
            duration: design.duration,
            period: m.period,
            fundamental_hz: 1.0 / m.period,
            q0: m.q0,
            sin: m.sin.iter().map(v).collect(),
            cos: m.cos.iter().map(v).collect(),
            criterion: design.criterion,
            figures: design.figures,
            base_parameters: design.columns.kept.len(),
            limits: [v(&l.lower), v(&l.upper), v(&l.velocity), v(&l.effort)],
            acceleration_limit: l.acceleration.as_ref().map(v),
            check: design.check(robot, rate),
            clearance: design.clearances.as_ref().map(|c| c.asked),
            min_clearance: design.clearance(robot, rate),
            evaluations: design.evaluations,
            identifiability: design.identifiability(robot, rate, 2e-3, noise)?,
        })
    }
}
