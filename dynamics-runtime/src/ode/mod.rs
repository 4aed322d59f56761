//! ODE integration on stack-allocated states: fixed-step RK4, adaptive
//! Dormand-Prince 5(4) with dense output, and event location on the dense
//! output. One file per method, the tableau as data (`tableau.rs`).

mod dopri5;
mod rk4;
mod state;
mod tableau;

pub use dopri5::{locate_event, Dopri5, OdeError, Step, Tolerances};
pub use rk4::rk4_step;
pub use state::{JointState, OdeState};
