//! The design criterion: the condition number of the weighted base
//! regressor with its columns scaled to unit norm.
//!
//! Why the condition number and not D-optimality: the condition number
//! bounds how much relative noise in the efforts can grow into relative
//! error of the parameters in the worst direction, which is where an
//! identification fails (two effects traded against each other); the
//! determinant can grow by stretching well-excited directions while one
//! direction stays weak. With unit-norm columns both are free of the
//! parameters' units. The determinant (as `log det` of the unit-column Gram
//! matrix, at most 0) is reported beside it.

use nalgebra::{DMatrix, SymmetricEigen};

use super::ExciteError;

/// Which quantity the search minimises.
///
/// ```
/// use dynamics_sim2real::excite::Criterion;
/// assert_eq!("condition".parse::<Criterion>().unwrap(), Criterion::Condition);
/// assert!("x".parse::<Criterion>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Criterion {
    /// The condition number of the unit-column weighted base regressor.
    #[default]
    Condition,
    /// D-optimality: minus the log-determinant of its Gram matrix.
    DOptimal,
}

impl std::str::FromStr for Criterion {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "condition" => Ok(Criterion::Condition),
            "d-optimal" | "d_optimal" => Ok(Criterion::DOptimal),
            _ => Err(format!(
                "unknown criterion `{s}`; known: condition, d-optimal"
            )),
        }
    }
}

/// The figures of one information matrix.
///
/// ```
/// use dynamics_sim2real::excite::Figures;
/// let x = nalgebra::DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 2.0, 0.0, 0.0]);
/// let f = Figures::of_gram(&(x.transpose() * &x)).unwrap();
/// assert!((f.condition - 1.0).abs() < 1e-12); // unit columns: orthonormal
/// assert!(f.log_det.abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Figures {
    /// Condition number of the unit-column regressor (largest over
    /// smallest singular value).
    pub condition: f64,
    /// `log det` of the unit-column Gram matrix (0 for orthogonal columns;
    /// more negative: more nearly dependent columns).
    pub log_det: f64,
}

impl Figures {
    /// The figures of the Gram matrix `g = X^T X` of a regressor `X`.
    pub fn of_gram(g: &DMatrix<f64>) -> Result<Self, ExciteError> {
        let k = g.nrows();
        let d: Vec<f64> = (0..k).map(|i| g[(i, i)]).collect();
        if d.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            return Ok(Figures {
                condition: f64::INFINITY,
                log_det: f64::NEG_INFINITY,
            });
        }
        let unit = DMatrix::from_fn(k, k, |a, b| g[(a, b)] / (d[a] * d[b]).sqrt());
        let eig = SymmetricEigen::try_new(unit, 1e-13, 300).ok_or(ExciteError::Numeric {
            place: "criterion",
            cause: "the eigenvalues of the information matrix did not converge".into(),
        })?;
        let (mut lo, mut hi, mut log_det) = (f64::INFINITY, 0.0_f64, 0.0);
        for &v in eig.eigenvalues.iter() {
            lo = lo.min(v);
            hi = hi.max(v);
            log_det += v.max(f64::MIN_POSITIVE).ln();
        }
        let condition = if lo > 0.0 {
            (hi / lo).sqrt()
        } else {
            f64::INFINITY
        };
        Ok(Figures { condition, log_det })
    }

    /// The figures of a regressor `x` (rows stacked).
    ///
    /// ```
    /// use dynamics_sim2real::excite::Figures;
    /// let x = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 0.0, 1.0]);
    /// // Unit columns (1, 0) and (1, 1)/sqrt 2: singular values sqrt(1 +- 1/sqrt 2).
    /// let c = ((1.0 + 0.5f64.sqrt()) / (1.0 - 0.5f64.sqrt())).sqrt();
    /// assert!((Figures::of(&x).unwrap().condition - c).abs() < 1e-9);
    /// ```
    pub fn of(x: &DMatrix<f64>) -> Result<Self, ExciteError> {
        Self::of_gram(&(x.transpose() * x))
    }

    /// The value the search minimises under `criterion`.
    pub fn cost(&self, criterion: Criterion) -> f64 {
        match criterion {
            Criterion::Condition => self.condition.ln(),
            Criterion::DOptimal => -self.log_det,
        }
    }
}
