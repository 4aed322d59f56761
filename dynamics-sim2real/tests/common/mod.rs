//! The robot the sim-to-real tests of this crate share.

dynamics_macros::robot! {
    /// A planar two-link arm in a vertical plane.
    pub robot Arm2;
    gravity = [0.0, -9.8, 0.0];
    link base;
    link upper { mass = 3.0; com = [0.1, 0.0, 0.0]; inertia = [1e-5, 0.02, 0.02]; }
    link lower { mass = 1.5; com = [0.08, 0.0, 0.0]; inertia = [1e-5, 0.008, 0.008]; }
    joint j1 = revolute(base -> upper) { transfer = [rot(q)]; }
    joint j2 = revolute(upper -> lower) { transfer = [tu(0.25), rot(q)]; }
}

/// The generator's defaults for Arm2 over `duration` s with seed `seed`.
#[allow(dead_code)] // (not every test binary uses it)
pub fn synth_options(duration: f64, seed: u64) -> dynamics_sim2real::synth::SynthOptions<2> {
    dynamics_sim2real::synth::SynthOptions {
        duration,
        seed,
        ..Default::default()
    }
}
