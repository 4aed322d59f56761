//! The state of a plant: link side and motor side, and the norms the
//! integrator measures it with.

use nalgebra::SVector;

use dynamics_runtime::ode::OdeState;

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
