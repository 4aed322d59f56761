//! The values searched for a candidate's nonlinear parameters (grids) and
//! the limit of an effort scale.

use crate::effects::SIGN_SMOOTHING;

/// Coulomb friction's velocity widths searched, rad/s: sharp (the smooth
/// sign of every friction law, [`SIGN_SMOOTHING`]) to the tenths of a
/// rad/s over which real joints' friction turns (the Panda's published
/// sigmoids `1 / (1 + exp(-phi2 v))`, Gaz et al. 2019, are `tanh(v / vw)`
/// with `vw = 2 / phi2` = 0.12-0.39 rad/s). Not wider: a width of 0.4
/// rad/s is nearly linear over a joint's usual speeds and takes the place
/// of viscous friction.
pub const COULOMB_WIDTHS: [f64; 3] = [SIGN_SMOOTHING, 0.05, 0.15];
/// Stribeck velocities searched, rad/s.
pub(crate) use crate::effects::STRIBECK_GRID;
/// Resistance exponents searched.
pub const ALPHA_GRID: [f64; 5] = [1.0, 1.5, 2.0, 2.5, 3.0];

/// The largest `|s - 1|` an effort scale may take. A torque constant or a
/// gear ratio in a robot's configuration is off by some per cent, a
/// motor's torque constant by up to 10-20 % with temperature and
/// saturation; one off by more than half (or of the wrong sign) is not an
/// effort scale but a wrong unit, a wrong channel or a wrong sign, which
/// the data should not be bent to explain.
pub const EFFORT_SCALE_LIMIT: f64 = 0.5;
