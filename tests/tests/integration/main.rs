//! Integration tests, compiled into one binary (faster on two cores).

mod batch;
mod chunks;
mod clearance;
mod compound;
mod determinism;
mod diagnosis;
mod effects;
mod elastic_grip;
mod environment;
mod excite;
mod excite_clearance;
mod excite_follow;
mod excite_plot;
mod identify;
mod linearize;
mod logs;
mod mar_eq10;
mod mar_vibration;
mod mimic;
mod module_graph;
mod mujoco;
mod oracle;
mod properties;
mod regressor;
mod simulate;
mod urdf;
