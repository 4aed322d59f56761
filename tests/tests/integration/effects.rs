//! Effects attached to a generated robot: energy balance (friction, damping
//! and resistance dissipate, conservative add-ons conserve), backlash
//! contact switches located by events, the two-mass joint's resonance.

use dynamics_runtime::ode::Tolerances;
use dynamics_sim2real::effects::{Effect, Plant, PlantSim};
use nalgebra::Vector3;
use robots::Arm3r;

fn tight() -> Tolerances {
    Tolerances {
        rtol: 1e-11,
        atol: 1e-12,
        ..Default::default()
    }
}

/// Energies at 1 ms samples of 1.5 s of free motion from a bent pose.
fn free_energies(effects: Vec<Effect>) -> Vec<f64> {
    let plant = Plant::new(Arm3r::default(), effects).expect("valid effects");
    let mut sim: PlantSim<3> =
        plant.start(Vector3::new(0.4, -0.6, 0.9), Vector3::new(1.0, -2.0, 1.5));
    let mut out = vec![plant.energy(&sim.state, &sim.contact)];
    for k in 1..=1500 {
        sim.advance(&plant, k as f64 * 1e-3, &Vector3::zeros(), tight())
            .expect("simulates");
        out.push(plant.energy(&sim.state, &sim.contact));
    }
    out
}

#[test]
fn conservative_add_ons_conserve_energy() {
    for e in [
        Effect::Armature {
            joint: 1,
            inertia: 0.01,
        },
        Effect::PayloadMass {
            mass: 0.7,
            com: [0.0; 3],
        },
        Effect::JointElasticity {
            joint: 2,
            stiffness: 200.0,
            damping: 0.0,
            motor_inertia: 0.002,
        },
    ] {
        let en = free_energies(vec![e]);
        let drift = en.iter().map(|x| (x - en[0]).abs()).fold(0.0, f64::max);
        assert!(drift < 1e-6 * en[0].abs().max(1.0), "{e:?}: drift {drift}");
    }
}

#[test]
fn friction_damping_and_resistance_never_create_energy() {
    for e in [
        Effect::coulomb(0, 0.5),
        Effect::ViscousFriction { joint: 1, fv: 0.2 },
        Effect::StribeckFriction {
            joint: 2,
            fc: 0.1,
            fs: 0.2,
            vs: 0.05,
        },
        Effect::EnvironmentResistance {
            mu: 0.5,
            alpha: 2.0,
        },
        Effect::JointElasticity {
            joint: 1,
            stiffness: 300.0,
            damping: 0.5,
            motor_inertia: 0.003,
        },
        Effect::Backlash {
            joint: 1,
            half_width: 0.002,
            motor_inertia: 0.003,
            contact_stiffness: 2e3,
            contact_damping: 0.5,
        },
    ] {
        let en = free_energies(vec![e]);
        // Never increases beyond integration error; and it does dissipate.
        for w in en.windows(2) {
            assert!(
                w[1] <= w[0] + 1e-7,
                "{e:?}: energy rose {} -> {}",
                w[0],
                w[1]
            );
        }
        assert!(en[en.len() - 1] < en[0] - 1e-4, "{e:?}: nothing dissipated");
    }
}

#[test]
fn backlash_switches_are_located_to_1e9_s() {
    let half_width = 0.003;
    let plant = Plant::new(
        Arm3r::default(),
        vec![Effect::Backlash {
            joint: 2,
            half_width,
            motor_inertia: 0.002,
            contact_stiffness: 5e3,
            contact_damping: 0.2,
        }],
    )
    .expect("valid");
    let mut sim = plant.start(Vector3::new(0.3, 0.2, -0.4), Vector3::new(0.0, 0.0, 2.0));
    for k in 1..=800 {
        // A torque that reverses at the motor drives the motor across the gap.
        let tau = Vector3::new(0.0, 0.0, 0.4 * (k as f64 * 0.02).sin());
        sim.advance(&plant, k as f64 * 1e-3, &tau, tight())
            .expect("simulates");
    }
    assert!(
        sim.switches.len() >= 4,
        "the motor never crossed the gap: {:?}",
        sim.switches
    );
    for s in &sim.switches {
        // At a located switch the deflection sits on +-delta: an error of
        // 1e-9 s in time would leave it |rate| * 1e-9 away.
        let off = (s.deflection.abs() - half_width).abs();
        assert!(
            off <= s.rate.abs() * 1e-9 + 1e-13,
            "{s:?}: {off:e} off the boundary"
        );
    }
}

#[test]
fn two_mass_joint_rings_at_its_resonance() {
    // Link 3 locked by large inertia elsewhere is not needed: compare the
    // motor-link relative oscillation with sqrt(k (1/Jm + 1/I3)).
    let k = 400.0;
    let jm = 0.002;
    let plant = Plant::new(
        Arm3r::default(),
        vec![Effect::JointElasticity {
            joint: 2,
            stiffness: k,
            damping: 0.0,
            motor_inertia: jm,
        }],
    )
    .expect("valid");
    let q0 = Vector3::new(0.0, 0.0, 0.0);
    let mut sim = plant.start(q0, Vector3::zeros());
    sim.state.qm[2] += 1e-3; // pluck the spring
    let mut last = sim.state.qm[2] - sim.state.q[2];
    let mut crossings = vec![];
    for i in 1..=400 {
        let t = i as f64 * 2.5e-4;
        // Hold the robot against gravity at the motor so only the ringing moves.
        let g = dynamics_runtime::Robot::gravity(&plant.robot, &sim.state.q);
        sim.advance(&plant, t, &g, tight()).expect("simulates");
        let e = sim.state.qm[2] - sim.state.q[2] - g[2] / k;
        if e.signum() != last.signum() {
            crossings.push(t);
        }
        last = e;
    }
    assert!(crossings.len() >= 4, "{crossings:?}");
    let period =
        2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let f_measured = 1.0 / period;
    // The link's effective inertia about joint 3 with the other joints free
    // is below A[2][2]; bracket with A[2][2] (locked) and the motor alone.
    let a = dynamics_runtime::Robot::mass_matrix(&plant.robot, &q0);
    let f_locked = (k * (1.0 / jm + 1.0 / a[(2, 2)])).sqrt() / (2.0 * std::f64::consts::PI);
    let f_motor = (k / jm).sqrt() / (2.0 * std::f64::consts::PI);
    assert!(
        f_measured > f_motor * 0.98 && f_measured < f_locked * 1.25,
        "{f_measured} vs [{f_motor}, {f_locked}]"
    );
}

#[test]
fn bad_effects_are_refused_with_the_reason() {
    let e = Plant::new(
        Arm3r::default(),
        vec![Effect::Armature {
            joint: 5,
            inertia: 1.0,
        }],
    )
    .unwrap_err();
    assert!(e.to_string().contains("joint index 5"), "{e}");
    let e = Plant::new(
        Arm3r::default(),
        vec![Effect::ViscousFriction { joint: 0, fv: -1.0 }],
    )
    .unwrap_err();
    assert!(e.to_string().contains("fv"), "{e}");
}
