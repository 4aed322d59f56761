//! The candidates: every unmodelled effect of the vocabulary at every place
//! it can act, with what a fit needs of it.
//!
//! - `candidate.rs`: [`Candidate`] (kind, place, grid value) and its
//!   columns, the regressor it adds to the torque residual;
//! - `grids.rs`: the values searched for nonlinear parameters and the
//!   bounds of linear ones;
//! - `motor.rs`: the motor side's parameters (elasticity, backlash), their
//!   grid and physical box;
//! - `records.rs`: both records of a diagnosis prepared and checked;
//! - `prepared.rs`: one record made ready for fitting ([`Prepared`]):
//!   signals, the column cache (`basis.rs`), rows, noise levels;
//! - `columns.rs`: a candidate's whitened columns on the fit's rows;
//! - `force_filter/`: friction columns filtered as the residual shows a
//!   force the motion takes;
//! - `shift.rs`, `late.rs`: late channels (motion, positions, effort);
//! - `links.rs`: link inertial corrections, the regressor's columns per
//!   link and the combinations the data determine;
//! - `visibility.rs`: what the data can show, checked before anything is
//!   fitted; the candidates they cannot identify are dropped.

mod basis;
mod candidate;
mod columns;
mod force_filter;
mod grids;
mod late;
mod links;
mod motor;
mod prepared;
mod records;
mod row_series;
mod shift;
mod visibility;

pub use basis::Friction;
pub(in crate::diagnose) use candidate::model_part;
pub use candidate::{payload_com, Candidate, Channel, Unnamed};
pub use columns::{linear_columns, lower_bounds, whitened, whitened_rows};
pub use grids::EFFORT_SCALE_LIMIT;
pub use late::offer_delays;
pub use links::{combined, delta, link_basis, moment_basis, regressor_columns, LinkBasis, MOMENTS};
pub use motor::{motor_feasible, motor_grid, signature_limit, MotorGuess};
pub use prepared::Prepared;
pub use records::{Record, Records};
pub use visibility::{identifiable, Excitation};

use crate::diagnose::Options;

/// The candidates of `options.kinds` the training record of `records` can
/// identify, with the late channels it shows (what is left out, and why,
/// goes to the records' warnings).
pub fn offer<const N: usize>(records: &mut Records<N>, options: &Options) -> Vec<Candidate> {
    // A payload is its mass and centre of mass: at a frame tip both are
    // fitted (the centre a note where the data do not place it), as a
    // mass held at the frame's origin is biased by the ratio of the lever
    // arms; a point tip has no frame to place a centre in.
    let frame = records.p.basis.framed();
    let all = Candidate::all::<N>(&options.kinds)
        .into_iter()
        .filter(|c| match c {
            Candidate::PayloadCom(_) => frame,
            Candidate::Payload => !frame,
            _ => true,
        })
        .collect();
    let mut candidates = identifiable(
        all,
        &records.excitation,
        records.p.sig.dt,
        &mut records.warnings,
    );
    offer_delays(
        &mut candidates,
        &records.train,
        &records.p,
        &mut records.warnings,
    );
    candidates
}
