//! The reported standard deviation of a searched parameter against the
//! scatter of its fits over re-noised replicates of one recording.

use dynamics_cli::gap::SynthRequest;
use dynamics_sim2real::diagnose::Options;
use dynamics_sim2real::effects::EffectKind;
use dynamics_sim2real::synth::{ExcitationKind, Noise, Rng};
use robots::builtin::{diagnose_files, synth};

/// The reported standard deviation of a searched parameter (the stiffness
/// of an elastic joint, from the curvature of the fit's objective) against
/// a spread that can be checked: one recording, re-noised eight times with
/// fresh sensor noise of the generator's levels added to what was
/// measured (so each replicate carries the noise of the original and one
/// fresh draw, the same in every replicate but the fresh draw). The
/// scatter of the fitted stiffness over the replicates is then the part of
/// its uncertainty the fresh noise causes, about 1/sqrt(2) of the whole
/// noise-driven spread of a replicate (whose noise variance is twice the
/// original's); the reported std, of a replicate, is the whole.
#[test]
fn diagnosed_stiffness_spread_matches_a_noise_bootstrap() {
    use dynamics_sim2real::data::{read_csv_str, write_csv};
    let dir = std::env::temp_dir().join(format!("dynamics-spread-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let level = Noise {
        q: 2e-5,
        qd: 2e-3,
        tau_relative: 2e-3,
    };
    let out = synth(&SynthRequest {
        robot: "arm3r".into(),
        kind: Some(EffectKind::JointElasticity),
        joint: Some("j1".into()),
        magnitude: Some(12.0),
        seed: 500,
        excitation: ExcitationKind::Sines,
        duration: 6.0,
        noise: level,
    })
    .expect("synthesizes");
    let joints = ["j1", "j2", "j3"];
    let train = read_csv_str::<3>(&out.train, &joints, "train").expect("reads");
    let holdout = dir.join("b.csv");
    std::fs::write(&holdout, &out.holdout).expect("writes");
    // The generator's effort noise is relative to each joint's peak effort.
    let peak: Vec<f64> = (0..3)
        .map(|j| train.tau.iter().map(|t| t[j].abs()).fold(0.0, f64::max))
        .collect();
    let repeats = 8;
    let fits: Vec<(f64, f64)> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..2)
            .map(|t| {
                let (dir, train, peak, holdout) = (&dir, &train, &peak, &holdout);
                s.spawn(move || {
                    (0..repeats)
                        .filter(|i| i % 2 == t)
                        .map(|i| {
                            let mut rng = Rng::new(900 + i as u64);
                            let mut m = train.clone();
                            for k in 0..m.len() {
                                for j in 0..3 {
                                    m.q[k][j] += level.q * rng.normal();
                                    m.qd[k][j] += level.qd * rng.normal();
                                    m.tau[k][j] += level.tau_relative * peak[j] * rng.normal();
                                }
                            }
                            let path = dir.join(format!("{i}-a.csv"));
                            let mut text = Vec::new();
                            write_csv(&mut text, &m, &joints).expect("csv");
                            std::fs::write(&path, text).expect("writes");
                            let (report, _) = diagnose_files(
                                "arm3r",
                                &path,
                                holdout,
                                &Options::default(),
                                &|_, _| {},
                            )
                            .expect("diagnoses");
                            let entry = report
                                .which
                                .ranked
                                .iter()
                                .find(|r| {
                                    r.kind.name() == "joint_elasticity"
                                        && r.joint.as_deref() == Some("j1")
                                })
                                .expect("elasticity at j1 ranked");
                            let p = entry
                                .parameters
                                .iter()
                                .find(|p| p.name == "stiffness")
                                .expect("stiffness");
                            (p.value, p.std)
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        hs.into_iter()
            .flat_map(|h| h.join().expect("thread"))
            .collect()
    });
    let _ = std::fs::remove_dir_all(&dir);
    let n = fits.len() as f64;
    let mean = fits.iter().map(|f| f.0).sum::<f64>() / n;
    let scatter = (fits.iter().map(|f| (f.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let mut stds: Vec<f64> = fits.iter().map(|f| f.1).collect();
    stds.sort_by(f64::total_cmp);
    let reported = stds[stds.len() / 2];
    // The whole noise-driven spread of a replicate.
    let whole = scatter * 2f64.sqrt();
    eprintln!(
        "stiffness (truth file: {}): fitted (value, std) {:?}; mean {mean:.1}, bootstrap spread x sqrt 2 = {whole:.1}, median reported std {reported:.1}",
        out.truth.effect,
        fits.iter().map(|f| (f.0.round(), f.1.round())).collect::<Vec<_>>()
    );
    assert!(
        reported > whole / 2.0 && reported < 2.0 * whole,
        "reported std {reported} against the bootstrap's {whole}"
    );
}
