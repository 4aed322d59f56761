//! The diagnoser scored on damaged logs (issue 15): each single effect of
//! the vocabulary in turn, and controls, under one or two of the damages of
//! real logs (a jittered clock, repeated rows, holes, glitches, a 100 Hz
//! rate), drawn at random; the diagnoser gets the CSV files only. Targets:
//! the effect named first in at least 95 % of identifiable cases, the joint
//! right in at least 95 % of those, controls `none`, median held-out shrink
//! at least 0.9, and every damage present named by a warning. Then
//! effects that start and stop (an encoder that slips at a drawn time and
//! keeps the offset, a tool in a medium and a payload carried for a drawn
//! window; the held-out run has the window a quarter of its start
//! earlier), a late position stream (named `time_delay`, channel
//! `positions`, and warned) and a late effort stream (channel `effort`,
//! warned), each under one damage: the window found must lie within
//! [`WINDOW_TOLERANCE`] of the truth's, the late channel be the one named.
//! `LOGS_SEED_BASE=N` draws other cases (base 0 was the one looked at while
//! building); `LOGS_ONLY=i,j` runs single cases (printing the report and
//! the truth), `LOGS_KEEP=DIR` keeps the cases' files there.
//!
//! - `draw.rs`: what each case withholds and the damages of its record;
//! - `case.rs`: one case generated, diagnosed and scored.

mod case;
mod draw;

use case::{run_case, Outcome};
use draw::seed_base;

/// Single effects under damage, then effects in a window and late positions,
/// then late efforts.
const CASES: usize = 44;
const LATER_CASES: usize = 16;
/// Of the later cases, the first this many cycle through the windows and
/// late positions; the rest have the effort late.
const CYCLED_CASES: usize = 12;
/// How near the truth's edges a window found must lie, s (a few widths of
/// the 40 ms smoothing filter).
const WINDOW_TOLERANCE: f64 = 0.2;
/// As in the clean scoring (`diagnosis/`): the effect's effort, and the
/// part that tells it from the simpler effect it contains, both through
/// the diagnosis's smoothing (the generator's `snr`, `distinct_snr`), at
/// least this many times one sample's effort noise, on a 1 kHz record; on
/// a record of rate `r`, the ratio times `sqrt(r / 1 kHz)` (see
/// [`rate_snr`]).
const IDENTIFIABLE_SNR: f64 = 2.0;

/// The generator's signal-to-noise ratio (per sample) of a record of rate
/// `rate`, as the ratio a 1 kHz record of the same motion and the same
/// evidence would have: the evidence grows with the samples (the sum of
/// the squared ratio), so 100 Hz holds a tenth of it. On the same draw
/// (base 12000, case 37: a rotor inertia of snr 2.2 on the RRP) the
/// diagnosis gained 249 AICc at 1 kHz and 22 at 100 Hz (under the
/// `none` margin of 100; the inertia 2.05 +- 0.41 against a truth of
/// 3.12, 1 kHz 3.17 +- 0.18).
fn rate_snr(snr: f64, rate: f64) -> f64 {
    snr * (rate / 1000.0).min(1.0).sqrt()
}
/// Figures (named first / identifiable, by the evidence of a 1 kHz
/// record, `rate_snr`, of the sizes seen through the diagnosis's
/// smoothing): base 0 33/33 (windows and channels 13/14), 12000 31/31,
/// 21000 37/38 (a rotor inertia on the RRP named elastic), 22000 27/27,
/// 23000 33/33, 24000 31/31, 31000 33/33, 32000 33/33, 33000 33/33, 41000
/// 39/40 (a Stribeck named Coulomb), 42000 28/28, 43000 34/34, 44000
/// 31/31, 45000 32/32, 61000 32/32 (30/32 before the friction columns
/// were filtered as the motion shows a force and the held-out record
/// could speak against a motor side: a Stribeck named Coulomb, a rotor
/// inertia named elastic); joints, controls, warnings right on all. Some
/// 30 s of diagnosis on 2 cores.
#[test]
fn diagnoser_names_the_effect_in_damaged_logs() {
    // `LOGS_KEEP=DIR` writes the cases' files there and keeps them.
    let keep = std::env::var("LOGS_KEEP").ok();
    let dir = keep
        .clone()
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| {
            std::env::temp_dir().join(format!("dynamics-logs-{}", std::process::id()))
        });
    std::fs::create_dir_all(&dir).expect("temp dir");
    // `LOGS_ONLY=3,17` runs only those cases (to look at one closely).
    let only: Vec<usize> = std::env::var("LOGS_ONLY")
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_default();
    let outcomes: Vec<Outcome> = (0..CASES + LATER_CASES)
        .filter(|i| only.is_empty() || only.contains(i))
        .map(|i| run_case(i, &dir, &only))
        .collect();
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    let ident: Vec<&Outcome> = outcomes.iter().filter(|o| o.identifiable).collect();
    let named = ident.iter().filter(|o| o.said == o.truth.kind).count();
    let joints: Vec<&&Outcome> = ident
        .iter()
        .filter(|o| o.said == o.truth.kind && o.truth.joint.is_some())
        .collect();
    let joint_right = joints
        .iter()
        .filter(|o| o.said_joint == o.truth.joint)
        .count();
    let controls: Vec<&Outcome> = outcomes.iter().filter(|o| o.truth.kind == "none").collect();
    let quiet = controls.iter().filter(|o| o.said == "none").count();
    let mut shrinks: Vec<f64> = ident
        .iter()
        .filter(|o| o.said == o.truth.kind)
        .map(|o| o.shrink)
        .collect();
    shrinks.sort_by(f64::total_cmp);
    let median = shrinks.get(shrinks.len() / 2).copied().unwrap_or(0.0);
    let warned = outcomes.iter().filter(|o| o.warned).count();
    let later: Vec<&&Outcome> = ident
        .iter()
        .filter(|o| o.truth.window.is_some() || o.truth.late.is_some())
        .filter(|o| o.said == o.truth.kind)
        .collect();
    let detailed = later.iter().filter(|o| o.detail).count();
    eprintln!(
        "seed base {}: named {named}/{} identifiable, joint {joint_right}/{}, controls {quiet}/{} none, median shrink {median:.2}, damage warned {warned}/{}, windows and channels right {detailed}/{}",
        seed_base(),
        ident.len(),
        joints.len(),
        controls.len(),
        outcomes.len(),
        later.len()
    );
    assert!(
        named as f64 >= 0.95 * ident.len() as f64,
        "named {named}/{}",
        ident.len()
    );
    assert!(
        joint_right as f64 >= 0.95 * joints.len() as f64,
        "joints {joint_right}/{}",
        joints.len()
    );
    assert_eq!(quiet, controls.len(), "controls");
    assert!(median >= 0.9, "median shrink {median}");
    assert_eq!(warned, outcomes.len(), "warnings");
    // (A window's edge where the effect fades below the noise, a medium
    // met at low speed, is not in the data: 90 %.)
    assert!(
        detailed as f64 >= 0.9 * later.len() as f64,
        "windows and channels {detailed}/{}",
        later.len()
    );
}
