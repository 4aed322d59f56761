//! The design: options, the search run over a robot, and the designed
//! motion with its figures.

use nalgebra::SVector;

use super::search::{search, Problem};
use super::separate::nested;
use super::{
    check, identifiability, BaseColumns, Check, Clearance, Clearances, Criterion, ExciteError,
    Figures, Fourier, Identifiability, Limits, Minimum, Rival,
};
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;

/// What to design.
///
/// ```
/// use dynamics_sim2real::excite::Options;
/// let o = Options::<2>::new(20.0);
/// assert_eq!((o.harmonics, o.margin, o.period()), (5, 0.1, 5.0));
/// assert_eq!(Options::<2>::new(8.0).period(), 4.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Options<const N: usize> {
    /// Duration of the motion, s (a whole number of periods).
    pub duration: f64,
    /// The period, s; `None`: the duration over the whole number of periods
    /// nearest to 5 s each (at least one).
    pub period: Option<f64>,
    /// Harmonics per joint (at least 3: the rest conditions take three).
    pub harmonics: usize,
    /// Fraction by which every limit is tightened (see [`Limits::with_margin`]).
    pub margin: f64,
    /// Start and end pose; `None`: [`Limits::middle`].
    pub q0: Option<SVector<f64, N>>,
    /// The quantity minimised.
    pub criterion: Criterion,
    /// Evaluations of the criterion the search may spend.
    pub evaluations: usize,
    /// Points per period where limits and criterion are evaluated.
    pub points: usize,
    /// Seed of the random starts and steps.
    pub seed: u64,
    /// Effort noise for the predicted identifiability, as a fraction of
    /// each joint's peak effort along the motion (`synth --noise-tau`'s
    /// convention).
    pub noise_tau: f64,
    /// The clearance of the link frames kept (see [`Clearances`]); `None`
    /// (the default): not checked.
    pub clearance: Option<Clearance>,
}

impl<const N: usize> Options<N> {
    /// Defaults for a motion of `duration` seconds.
    pub fn new(duration: f64) -> Self {
        Options {
            duration,
            period: None,
            harmonics: 5,
            margin: 0.1,
            q0: None,
            criterion: Criterion::Condition,
            evaluations: 2000,
            points: 200,
            seed: 1,
            noise_tau: 2e-3,
            clearance: None,
        }
    }

    /// The period used.
    pub fn period(&self) -> f64 {
        self.period.unwrap_or_else(|| {
            let m = (self.duration / 5.0).round().max(1.0);
            self.duration / m
        })
    }

    fn validate(&self) -> Result<(), ExciteError> {
        let bad = |option, cause: String| Err(ExciteError::Options { option, cause });
        if !(self.duration.is_finite() && self.duration > 0.0) {
            return bad(
                "duration",
                format!("{} is not a positive time", self.duration),
            );
        }
        let p = self.period();
        let m = self.duration / p;
        if !(p > 0.0 && (m - m.round()).abs() < 1e-9 && m.round() >= 1.0) {
            return bad(
                "period",
                format!("{p} s does not divide the duration {} s", self.duration),
            );
        }
        if self.harmonics < 3 {
            return bad("harmonics", format!("{} < 3", self.harmonics));
        }
        if !(0.0..1.0).contains(&self.margin) {
            return bad("margin", format!("{} is not in [0, 1)", self.margin));
        }
        if self.points < 4 * self.harmonics {
            return bad(
                "points",
                format!("{} < 4 per harmonic ({})", self.points, 4 * self.harmonics),
            );
        }
        if !(self.noise_tau.is_finite() && self.noise_tau > 0.0) {
            return bad("noise_tau", format!("{} is not positive", self.noise_tau));
        }
        if let Some(c) = self.clearance {
            if !(c.ground.is_finite() && c.distance.is_finite() && c.distance >= 0.0) {
                return bad(
                    "clearance",
                    format!(
                        "ground {} and distance {} must be finite, the distance not negative",
                        c.ground, c.distance
                    ),
                );
            }
        }
        Ok(())
    }
}

/// A designed motion and what it is predicted to identify.
#[derive(Debug, Clone, PartialEq)]
pub struct Design<const N: usize> {
    /// The motion (one period; repeated over the duration).
    pub motion: Fourier<N>,
    /// Duration, s.
    pub duration: f64,
    /// The limits with the margin applied.
    pub limits: Limits<N>,
    /// The base columns the criterion is computed on.
    pub columns: BaseColumns<N>,
    /// The criterion's figures over one period.
    pub figures: Figures,
    /// The criterion minimised.
    pub criterion: Criterion,
    /// Evaluations spent.
    pub evaluations: usize,
    /// The clearance check the motion keeps (`None`: not checked).
    pub clearances: Option<Clearances>,
}

impl<const N: usize> Design<N> {
    /// The smallest clearances of the link frames along the samples at
    /// `rate` (`None` when the design did not check them).
    pub fn clearance<R: Robot<N>>(&self, robot: &R, rate: f64) -> Option<Minimum> {
        let c = self.clearances.as_ref()?;
        let states: Vec<Reference<N>> = self.samples(rate).into_iter().map(|s| s.1).collect();
        Some(c.minimum(robot, &states))
    }

    /// The samples `(t, reference)` at `rate` Hz from 0 to the duration,
    /// both ends included.
    ///
    /// ```
    /// use dynamics_sim2real::excite::{Design, Fourier};
    /// let f = Fourier::<1>::new([0.0].into(), 2.0, 3);
    /// let s = Design::sample(&f, 4.0, 10.0);
    /// assert_eq!(s.len(), 41);
    /// assert_eq!(s[40].0, 4.0);
    /// ```
    pub fn samples(&self, rate: f64) -> Vec<(f64, Reference<N>)> {
        Self::sample(&self.motion, self.duration, rate)
    }

    /// `motion` sampled at `rate` Hz over `duration`, both ends included.
    pub fn sample(motion: &Fourier<N>, duration: f64, rate: f64) -> Vec<(f64, Reference<N>)> {
        let n = (duration * rate).round().max(1.0) as usize;
        (0..=n)
            .map(|k| {
                let t = if k == n { duration } else { k as f64 / rate };
                (t, motion.at(t))
            })
            .collect()
    }

    /// The limit check of the samples at `rate` (margin included).
    pub fn check<R: Robot<N>>(&self, robot: &R, rate: f64) -> Check<N> {
        let states: Vec<Reference<N>> = self.samples(rate).into_iter().map(|s| s.1).collect();
        check(robot, &states, &self.limits)
    }

    /// The predicted identifiability over the whole duration, from one
    /// period sampled at `rate`, at effort noise `noise_tau` times each
    /// joint's peak effort (or `noise` per joint when given).
    pub fn identifiability<R: Robot<N>>(
        &self,
        robot: &R,
        rate: f64,
        noise_tau: f64,
        noise: Option<SVector<f64, N>>,
    ) -> Result<Identifiability, ExciteError> {
        let period = Self::sample(&self.motion, self.motion.period, rate);
        let states: Vec<Reference<N>> = period[..period.len() - 1].iter().map(|s| s.1).collect();
        let noise = match noise {
            Some(n) => n,
            None => check(robot, &states, &self.limits).peak_effort * noise_tau,
        };
        identifiability(
            robot,
            &self.columns,
            &states,
            (self.duration / self.motion.period).round(),
            &noise,
        )
    }
}

/// Designs an exciting motion of `robot` within `limits` (the raw limits:
/// `options.margin` is applied here).
///
/// ```
/// use dynamics_sim2real::excite::{design, Limits, Options};
/// dynamics_macros::robot! {
///     pub robot TwoLink;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
///     joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
/// }
/// let arm = TwoLink::default();
/// let limits = Limits::<2>::new([-1.0, -1.5], [1.0, 1.5], [2.0, 2.0], [60.0, 30.0]);
/// let mut o = Options::new(8.0);
/// o.evaluations = 80;
/// let d = design(&arm, &limits, &o).unwrap();
/// assert!(d.check(&arm, 200.0).all());
/// let s = d.samples(200.0);
/// assert!(s[0].1.qd.norm() < 1e-12 && s[s.len() - 1].1.qd.norm() < 1e-9);
/// assert!(d.figures.condition.is_finite());
/// ```
pub fn design<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    limits: &Limits<N>,
    options: &Options<N>,
) -> Result<Design<N>, ExciteError> {
    Ok(run(robot, limits, options, &[])?.0)
}

/// Designs a motion of `robot` within `limits` that tells each pair of
/// rival effects apart: it maximises the smallest over the pairs of the
/// separation angle (see [`crate::excite::separation_angles`]); returns
/// the design and the angles (rad) over one period. For a nested pair
/// (Stribeck over Coulomb friction, elasticity or backlash over a rotor)
/// without a period given, the period is searched too: the whole
/// divisions of the duration into periods of at least 1.5 s.
///
/// ```
/// use dynamics_sim2real::excite::{design_separating, Limits, Options, Rival};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let mut o = Options::new(4.0);
/// o.evaluations = 60;
/// let limits = Limits::new([-1.0], [1.0], [3.0], [50.0]);
/// let pairs = [(Rival::Coulomb(0), Rival::Stribeck(0))];
/// let (d, angles) = design_separating(&p, &limits, &o, &pairs).unwrap();
/// assert!(d.check(&p, 200.0).all() && angles[0] > 0.0);
/// ```
pub fn design_separating<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    limits: &Limits<N>,
    options: &Options<N>,
    pairs: &[(Rival, Rival)],
) -> Result<(Design<N>, Vec<f64>), ExciteError> {
    if pairs.is_empty() {
        return Err(ExciteError::Options {
            option: "pairs",
            cause: "no pair of rival effects to separate".into(),
        });
    }
    if options.period.is_some() || !pairs.iter().any(|&(a, b)| nested(a, b)) {
        return run(robot, limits, options, pairs);
    }
    // A nested pair's extra is measured at the motion's slow reversals
    // (a breakaway) or its effort's turns (a motor side), whose number
    // grows as the period shrinks: the period is searched too, over the
    // whole divisions of the duration into periods of at least
    // `NESTED_PERIOD`, each with the whole budget; the best kept.
    let most = (options.duration / NESTED_PERIOD).floor().max(1.0) as usize;
    let mut best: Option<(Design<N>, Vec<f64>)> = None;
    for m in 1..=most {
        let o = Options {
            period: Some(options.duration / m as f64),
            ..options.clone()
        };
        let found = run(robot, limits, &o, pairs)?;
        let worst = |a: &[f64]| a.iter().fold(f64::INFINITY, |m, &v| m.min(v));
        if best.as_ref().is_none_or(|b| worst(&found.1) > worst(&b.1)) {
            best = Some(found);
        }
    }
    best.ok_or(ExciteError::Numeric {
        place: "separating design",
        cause: "no period searched".into(),
    })
}

/// The shortest period searched for a nested pair, s.
const NESTED_PERIOD: f64 = 1.5;

fn run<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    limits: &Limits<N>,
    options: &Options<N>,
    pairs: &[(Rival, Rival)],
) -> Result<(Design<N>, Vec<f64>), ExciteError> {
    options.validate()?;
    limits.require_finite(&R::JOINT_NAMES)?;
    let tight = limits.with_margin(options.margin);
    let q0 = options.q0.unwrap_or_else(|| tight.middle());
    for j in 0..N {
        if !(q0[j] >= tight.lower[j] && q0[j] <= tight.upper[j]) {
            return Err(ExciteError::StartOutside {
                joint: R::JOINT_NAMES[j].to_string(),
                value: q0[j],
                lower: tight.lower[j],
                upper: tight.upper[j],
            });
        }
    }
    let rest = robot.inverse_dynamics(&q0, &SVector::zeros(), &SVector::zeros());
    for j in 0..N {
        // NaN efforts fail too.
        if rest[j].abs().partial_cmp(&tight.effort[j]) != Some(std::cmp::Ordering::Less) {
            return Err(ExciteError::StartEffort {
                joint: R::JOINT_NAMES[j].to_string(),
                need: rest[j].abs(),
                limit: tight.effort[j],
            });
        }
    }
    let columns = BaseColumns::of(robot, &tight, options.seed)?;
    let clearances = options
        .clearance
        .map(|c| Clearances::of(robot, &tight, &q0, &c));
    let period = options.period();
    let grid: Vec<f64> = (0..options.points)
        .map(|k| k as f64 * period / options.points as f64)
        .collect();
    let problem = Problem {
        robot,
        columns: &columns,
        limits: tight,
        q0,
        period,
        harmonics: options.harmonics,
        grid,
        criterion: options.criterion,
        pairs,
        clearances: clearances.as_ref(),
    };
    let found = search(&problem, options.evaluations, options.seed);
    let mut motion = problem.realise(&found.x).ok_or(ExciteError::Numeric {
        place: "search",
        cause: "no candidate motion moves within the limits".into(),
    })?;
    // Peaks between the grid's points: shrink until a fine sampling keeps
    // every limit (20 points per period of the highest harmonic or more).
    let fine = (40 * options.harmonics).max(4 * options.points) as f64 / period;
    let mut design = Design {
        figures: problem.figures(&motion)?,
        motion: motion.clone(),
        duration: options.duration,
        limits: tight,
        columns: columns.clone(),
        criterion: options.criterion,
        evaluations: found.evaluations,
        clearances: clearances.clone(),
    };
    for _ in 0..50 {
        let one = Design::sample(&motion, period, fine);
        let states: Vec<Reference<N>> = one.into_iter().map(|s| s.1).collect();
        let clear = clearances.as_ref().is_none_or(|c| c.keeps(robot, &states));
        if check(robot, &states, &tight).all() && clear {
            break;
        }
        motion.scale(&SVector::repeat(0.99));
        design.motion = motion.clone();
    }
    design.figures = problem.figures(&design.motion)?;
    let angles = if pairs.is_empty() {
        Vec::new()
    } else {
        problem.angles(&design.motion)?
    };
    Ok((design, angles))
}
