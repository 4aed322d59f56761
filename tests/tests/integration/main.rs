//! Integration tests, compiled into one binary (faster on two cores).

mod diagnosis;
mod effects;
mod mar_eq10;
mod mar_vibration;
mod oracle;
mod properties;
mod simulate;
mod urdf;
