//! Dissertation, sec. 3.2: the joint with clearance. Every switch (loss of
//! contact at Ru -> 0, re-contact, stick/slip) is located to 1e-9 s on the
//! dense output; energy balance with the work of drives and friction and
//! the impact losses; (3.25) held in contact; the rolling condition
//! re-derived against the bodies' own motion; the two coordinate sets are
//! the same bodies; sliding meets rolling at the friction limit.

use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::Robot;
use nalgebra::{Vector3, Vector4};
use robots::scenarios::clearance::{Mode, Start, GAP, MU, R1, R2};
use robots::scenarios::clearance_modes::{impact, roll, slide, slip_rate, to_free, to_seed};
use robots::scenarios::clearance_run::simulate;
use robots::{ClearanceArm, ClearanceArmFree};

fn tol(rtol: f64) -> Tolerances {
    Tolerances {
        rtol,
        atol: 1e-13,
        ..Default::default()
    }
}

#[test]
fn contact_loss_and_recontact_are_located_to_1e9_s() {
    let run = simulate(4.0, 1e-3, tol(1e-10)).expect("simulates");
    let losses: Vec<_> = run
        .switches
        .iter()
        .filter(|w| w.to == Mode::Flight && w.from != Mode::Flight)
        .collect();
    let hits: Vec<_> = run
        .switches
        .iter()
        .filter(|w| w.from == Mode::Flight)
        .collect();
    assert!(
        !losses.is_empty() && !hits.is_empty(),
        "no loss of contact or no re-contact"
    );
    assert!(run.switches.len() > 50, "stick-slip switches expected");
    for w in &run.switches {
        // The watch function changes sign within +-1e-9 s of the located time.
        assert!(w.g_before > 0.0 && w.g_after < 0.0, "{w:?}");
    }
    for w in &losses {
        // Ru at the located state is zero to within 1e-9 s of its rate.
        let (q, qd) = to_free(&w.q, &w.qd);
        let ru = if w.from == Mode::Slide {
            slide(w.t, &q, &qd, MU, slip_rate(&q, &qd).signum())
                .expect("slide")
                .1
        } else {
            roll(w.t, &w.q, &w.qd, R1 * w.q[1] + R2 * w.q[3])
                .expect("roll")
                .1[2]
        };
        let rate = (w.g_before - w.g_after).abs() / 2e-9;
        assert!(
            ru.abs() <= rate * 1e-9,
            "Ru = {ru:e} N at {}, rate {rate:e} N/s",
            w.t
        );
    }
    for w in &hits {
        // The pin is on the ring to within 1e-9 s of its normal speed.
        assert!(
            (w.q[2] - GAP).abs() <= w.qd[2].abs() * 1e-9 + 1e-18,
            "{w:?}"
        );
        assert!(w.qd[2] > 0.0 && w.impact_loss > 0.0);
    }
    // The same first loss of contact with tighter integration: the time is
    // the root's, not a step's end.
    let fine = simulate(2.5, 1e-3, tol(1e-12)).expect("simulates");
    let t_fine = fine
        .switches
        .iter()
        .find(|w| w.to == Mode::Flight)
        .expect("loses contact")
        .t;
    assert!(
        (t_fine - losses[0].t).abs() < 1e-6,
        "{t_fine} vs {}",
        losses[0].t
    );
}

#[test]
fn energy_change_equals_work_of_drives_and_friction_minus_impact_losses() {
    let run = simulate(4.0, 1e-3, tol(1e-10)).expect("simulates");
    let s = &run.samples;
    let scale = s.iter().fold(1.0f64, |m, p| m.max(p.work.abs()));
    let mut worst = 0.0f64;
    let mut last_friction = 0.0;
    for p in s {
        worst =
            worst.max((p.energy - s[0].energy - p.work - p.friction_work + p.impact_loss).abs());
        assert!(
            p.friction_work <= last_friction + 1e-15,
            "friction creates energy at {}",
            p.t
        );
        last_friction = p.friction_work;
    }
    assert!(worst < 1e-8 * scale, "balance off by {worst:e} J");
    assert!(last_friction < -1e-3);
    let lost: f64 = run.switches.iter().map(|w| w.impact_loss).sum();
    assert!(lost > 0.0 && (lost - s[s.len() - 1].impact_loss).abs() < 1e-15);
}

#[test]
fn constraints_hold_in_contact_and_the_pin_stays_inside_the_ring() {
    let run = simulate(4.0, 1e-3, tol(1e-10)).expect("simulates");
    for p in &run.samples {
        match p.mode {
            Mode::Roll => assert!(p.residual.abs().max() < 1e-10, "{p:?}"),
            Mode::Slide => assert!(p.residual[0].abs() < 1e-10, "{p:?}"),
            Mode::Flight => assert!(p.q[2] < GAP, "{p:?}"),
        }
        assert!(p.pin.norm() <= GAP * (1.0 + 1e-6));
        if p.mode != Mode::Flight {
            assert!(p.ru < 0.0, "the ring pulls at {}", p.t);
            assert!(
                p.ft.abs() <= MU * p.ru.abs() * (1.0 + 1e-6) + 1e-12,
                "{p:?}"
            );
        }
    }
}

/// World position of a point given in frame `f`'s coordinates.
fn world(arm: &ClearanceArm, f: usize, q: &Vector4<f64>, p: &Vector3<f64>) -> Vector3<f64> {
    let t = arm.frame_pose(f, q).expect("frame");
    (t * p.push(1.0)).xyz()
}

fn local(arm: &ClearanceArm, f: usize, q: &Vector4<f64>, p: &Vector3<f64>) -> Vector3<f64> {
    let t = arm.frame_pose(f, q).expect("frame");
    (t.try_inverse().expect("pose") * p.push(1.0)).xyz()
}

#[test]
fn rolling_condition_keeps_the_contact_points_together() {
    // r1 psi' + r2 phi2' = 0 (the sign garbled in the available text): the pin's and the
    // ring's material points at the contact move alike, checked with the
    // generated frame poses alone.
    let arm = ClearanceArm::default();
    let (f1, f2) = (
        ClearanceArm::frame_index("arm1").expect("arm1"),
        ClearanceArm::frame_index("arm2").expect("arm2"),
    );
    let line = ClearanceArm::frame_index("centre_line").expect("centre_line");
    let q = Vector4::new(0.4, 1.1, GAP, -0.3);
    let contact = world(&arm, line, &q, &Vector3::new(R1, 0.0, 0.0));
    let (p1, p2) = (local(&arm, f1, &q, &contact), local(&arm, f2, &q, &contact));
    let speed = |qd: Vector4<f64>| {
        let h = 1e-5;
        let v = |f: usize, p: &Vector3<f64>| {
            (world(&arm, f, &(q + qd * h), p) - world(&arm, f, &(q - qd * h), p)) / (2.0 * h)
        };
        (v(f1, &p1) - v(f2, &p2)).norm()
    };
    let rolling = Vector4::new(0.7, -R2 * 300.0, 0.0, R1 * 300.0);
    let wrong = Vector4::new(0.7, R2 * 300.0, 0.0, R1 * 300.0);
    assert!(speed(rolling) < 1e-8, "slip {:e}", speed(rolling));
    assert!(
        speed(wrong) > 1e-3,
        "the other sign slips: {:e}",
        speed(wrong)
    );
}

#[test]
fn both_coordinate_sets_describe_the_same_bodies() {
    let (arm, free) = (ClearanceArm::default(), ClearanceArmFree::default());
    for k in 0..20 {
        let x = |i: usize| ((k * 5 + i * 11) as f64 * 0.731).sin();
        let q = Vector4::new(
            2.0 * x(0),
            3.0 * x(1),
            GAP * (0.5 + 0.5 * x(2).abs()),
            2.0 * x(3),
        );
        let qd = Vector4::new(x(4), 50.0 * x(5), 0.01 * x(6), 3.0 * x(7));
        let (qf, qfd) = to_free(&q, &qd);
        let e = (arm.total_energy(&q, &qd), free.total_energy(&qf, &qfd));
        assert!((e.0 - e.1).abs() < 1e-12 * (1.0 + e.0.abs()), "{e:?}");
        let tip = (
            arm.point_position(0, &q).expect("tip"),
            free.point_position(0, &qf).expect("tip"),
        );
        assert!((tip.0 - tip.1).norm() < 1e-14);
        let (qb, qdb) = to_seed(&qf, &qfd, q[1]);
        assert!((qb - q).norm() < 1e-12 && (qdb - qd).norm() < 1e-9 * (1.0 + qd.norm()));
    }
}

#[test]
fn sliding_at_the_friction_limit_moves_as_rolling_and_impacts_dissipate() {
    let (q, qd) = Start {
        phi1: 0.3,
        phi: 1.0,
        rates: nalgebra::Vector2::new(0.5, -0.7),
        contact: -1.2,
        mu: MU,
    }
    .seed();
    let (qdd, r) = roll(0.3, &q, &qd, R1 * q[1] + R2 * q[3]).expect("roll");
    let ft = r[3] / R2;
    let (qf, qfd) = to_free(&q, &qd);
    let (fdd, lam) = slide(0.3, &qf, &qfd, (ft / r[2]).abs(), -ft.signum()).expect("slide");
    assert!((lam - r[2]).abs() < 1e-9 * r[2].abs(), "{lam} vs {}", r[2]);
    assert!((fdd[0] - qdd[0]).abs() < 1e-8 && (fdd[3] - (qdd[1] + qdd[3])).abs() < 1e-7);
    // A pin hitting the ring at 1 mm/s loses its normal speed, nothing else.
    let mut hit = qfd;
    hit[1] += 1e-3 * qf[1] / GAP;
    hit[2] += 1e-3 * qf[2] / GAP;
    let (after, loss) = impact(&qf, &hit).expect("impact");
    let free = ClearanceArmFree::default();
    let de = free.kinetic_energy(&qf, &hit) - free.kinetic_energy(&qf, &after);
    assert!(loss > 0.0 && (loss - de).abs() < 1e-12 * (1.0 + de));
    assert!((after[1] * qf[1] + after[2] * qf[2]).abs() < 1e-15);
}

#[test]
fn scenario_runs_and_writes_its_files() {
    let dir = std::env::temp_dir().join("dynamics-test-clearance");
    let lines = robots::scenarios::run("clearance", &dir).expect("runs");
    for f in [
        "clearance.csv",
        "clearance-switches.csv",
        "clearance-nogap.csv",
        "reaction.svg",
        "psi.svg",
        "phi2.svg",
        "phi1-nogap.svg",
        "pin.svg",
        "u.svg",
    ] {
        let text = std::fs::read_to_string(dir.join(f)).expect(f);
        assert!(text.len() > 500, "{f} is nearly empty");
    }
    assert!(lines.iter().any(|l| l.contains("losses of contact")));
}
