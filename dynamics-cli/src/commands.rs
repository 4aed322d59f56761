//! The small subcommands: `check`, `eval`, `synth`.

use std::path::PathBuf;

use dynamics_runtime::Robot;

use crate::compare::compare;
use crate::eval::evaluate;
use crate::gap::Motion;
use crate::states;
use crate::Res;

/// `dynamics check` for one robot: its values at the states of a reference
/// file (`file` names it, `text` is its content) against the file's; prints
/// the worst relative error per field and returns whether all are within
/// 1e-10.
pub fn check<R: Robot<N>, const N: usize>(
    name: &str,
    robot: &R,
    file: &str,
    text: &str,
) -> Result<bool, Box<dyn std::error::Error>> {
    let ours = evaluate(robot, &states::parse(text, file, N)?)?;
    let doc: serde_json::Value = serde_json::from_str(text)?;
    let cmp = compare(&ours, &doc);
    let worst = cmp.worst();
    let status = if worst <= 1e-10 { "ok" } else { "FAIL" };
    println!("\n{name} ({} states): {status}", ours.len());
    for (field, err) in &cmp.fields {
        println!("  {field:18} {err:9.2e}");
    }
    Ok(worst <= 1e-10)
}

/// `dynamics eval`: tau, M, g, C, nle, ddq, energies and derivatives at
/// given states (`states`; absent: the reference states `reference`, file
/// name and content, if the robot has them).
pub fn eval<R: Robot<N>, const N: usize>(
    name: &str,
    robot: R,
    reference: Option<(&str, &str)>,
    states: Option<PathBuf>,
    out: Option<PathBuf>,
) -> Res {
    let (file, text) = match &states {
        Some(path) => {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            (path.display().to_string(), text)
        }
        None => {
            let (f, t) = reference.ok_or("this robot has no reference states: give --states")?;
            (f.to_string(), t.to_string())
        }
    };
    let evaluated = evaluate(&robot, &states::parse(&text, &file, N)?)?;
    let doc = serde_json::json!({
        "robot": name,
        "joint_names": R::JOINT_NAMES.to_vec(),
        "states": evaluated,
    });
    let json = serde_json::to_string_pretty(&doc)?;
    match out {
        Some(path) => {
            std::fs::write(&path, json + "\n").map_err(|e| format!("{}: {e}", path.display()))?
        }
        None => println!("{json}"),
    }
    Ok(())
}

/// Our CSV text (`write_csv`'s: a header, then numbers written exactly) as
/// a Parquet file of the same columns.
///
/// ```
/// let text = "t,q_j,tau_j\n0,0.5,1\n0.001,0.25,2\n";
/// let bytes = dynamics_cli::commands::csv_as_parquet(text).unwrap();
/// assert!(bytes.starts_with(b"PAR1") && bytes.ends_with(b"PAR1"));
/// ```
pub fn csv_as_parquet(text: &str) -> Result<Vec<u8>, Box<dyn std::error::Error>> {
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(str::to_string)
        .collect();
    let mut columns = vec![Vec::new(); header.len()];
    for (k, line) in lines.enumerate() {
        for (c, cell) in line.split(',').enumerate() {
            let v: f64 = cell
                .parse()
                .map_err(|_| format!("line {}: `{cell}` is not a number", k + 2))?;
            if let Some(col) = columns.get_mut(c) {
                col.push(v);
            }
        }
    }
    let mut out = Vec::new();
    dynamics_sim2real::data::parquet::write_parquet_table(&mut out, &header, &columns)?;
    Ok(out)
}

/// What `synth`'s training run follows: `excitation` (a kind drawn with
/// the seed, or a design's JSON file, `*.json`) or a `motion` file (CSV),
/// and the duration when it is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Followed {
    /// `sines`, `chirp`, `pick-place` or a design's JSON (`dynamics excite --json`).
    pub excitation: String,
    /// A motion CSV (`t, q_<joint>, qd_<joint>, qdd_<joint>`).
    pub motion: Option<PathBuf>,
    /// Duration of a drawn reference, s.
    pub duration: f64,
}

impl Followed {
    /// The kind drawn for the held-out run (and the training run when no
    /// motion is given), the motion given with its duration, if any.
    ///
    /// ```
    /// use dynamics_cli::commands::Followed;
    /// let f = Followed { excitation: "chirp".into(), motion: None, duration: 3.0 };
    /// let (kind, given) = f.resolve::<2>(&["a", "b"]).unwrap();
    /// assert_eq!(format!("{kind:?}"), "Chirp");
    /// assert!(given.is_none());
    /// ```
    #[allow(clippy::type_complexity)]
    pub fn resolve<const N: usize>(
        &self,
        joints: &[&str; N],
    ) -> Result<
        (
            dynamics_sim2real::synth::ExcitationKind,
            Option<(dynamics_sim2real::synth::Excitation<N>, f64)>,
        ),
        String,
    > {
        use dynamics_sim2real::synth::{Excitation, ExcitationKind};
        let read = |path: &std::path::Path| {
            std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
        };
        if let Some(path) = &self.motion {
            let file = path.display().to_string();
            let samples = crate::excite::read_samples::<N>(&read(path)?, joints, &file)?;
            let end = samples.last().map(|s| s.0).unwrap_or(0.0);
            let ex = Excitation::samples(samples).map_err(|e| format!("{file}: {e}"))?;
            return Ok((ExcitationKind::Sines, Some((ex, end))));
        }
        if self.excitation.ends_with(".json") {
            let path = std::path::Path::new(&self.excitation);
            let (f, duration) =
                crate::excite::read_design::<N>(&read(path)?, joints, &self.excitation)?;
            return Ok((
                ExcitationKind::Sines,
                Some((Excitation::designed(f), duration)),
            ));
        }
        Ok((self.excitation.parse()?, None))
    }
}

/// `dynamics synth`: training and held-out CSVs (or Parquet files) of a robot with a withheld effect.
#[allow(clippy::too_many_arguments)]
pub fn synth_cmd<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    motion: &Motion,
    name: &str,
    effect: Option<String>,
    joint: Option<String>,
    magnitude: Option<f64>,
    seed: u64,
    followed: &Followed,
    noise: [f64; 3],
    out: &std::path::Path,
    truth: Option<PathBuf>,
    recording: &crate::gap::Recording,
) -> Res {
    use dynamics_sim2real::synth::Noise;
    let kind = effect.map(|e| e.parse()).transpose()?;
    let (excitation, given) = followed.resolve::<N>(&R::JOINT_NAMES)?;
    let duration = given.as_ref().map_or(followed.duration, |g| g.1);
    let req = crate::gap::SynthRequest {
        robot: name.into(),
        kind,
        joint,
        magnitude,
        seed,
        excitation,
        duration,
        noise: Noise {
            q: noise[0],
            qd: noise[1],
            tau_relative: noise[2],
        },
    };
    let data =
        crate::gap::synth_following(robot, motion, &req, recording, given.as_ref().map(|g| &g.0))?;
    let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("data");
    let parquet = out.extension().and_then(|e| e.to_str()) == Some("parquet");
    let hold = out.with_file_name(format!(
        "{stem}-holdout.{}",
        if parquet { "parquet" } else { "csv" }
    ));
    for (path, text) in [(out, &data.train), (hold.as_path(), &data.holdout)] {
        let bytes = if parquet {
            csv_as_parquet(text)?
        } else {
            text.clone().into_bytes()
        };
        std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    eprintln!("wrote {} and {}", out.display(), hold.display());
    if let Some(t) = truth {
        std::fs::write(&t, serde_json::to_string_pretty(&data.truth)?)
            .map_err(|e| format!("{}: {e}", t.display()))?;
        eprintln!("wrote the truth to {}", t.display());
    }
    Ok(())
}
