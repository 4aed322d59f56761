//! `dynamics new`: a crate scaffolded from a URDF the workspace does not
//! build, built and run through the whole program (issue 16), and the
//! inputs refused before anything is written.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::{dynamics, fails, fresh_dir, read_json, succeeds, workspace};

/// The efforts of state `state` in an `eval` output.
fn tau(doc: &serde_json::Value, state: usize) -> Vec<f64> {
    doc["states"][state]["tau"]
        .as_array()
        .expect("tau")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect()
}

/// SLOW (one cargo build of a new crate, a few minutes; runs in CI like
/// every test): `dynamics new` on a copy of the UR5's URDF with the robot
/// renamed and damping at the elbow (a robot the workspace does not
/// build), built sharing the workspace's target directory; its `check`
/// against Pinocchio's UR5 values to 1e-10 (with `--set` removing the
/// damping Pinocchio does not model, and failing without), its `eval`
/// changed by `--set`, a wrong name refused, and its `synth` + `diagnose`
/// naming the withheld effect.
#[test]
fn a_scaffolded_crate_builds_and_runs_the_whole_program() {
    let dir = fresh_dir("new");
    let urdf = std::fs::read_to_string(workspace().join("robots/data/urdf/ur5.urdf"))
        .expect("ur5 urdf")
        .replace("<robot name=\"ur5\">", "<robot name=\"my_arm\">");
    let elbow = "<joint name=\"elbow_joint\" type=\"revolute\">";
    let at = urdf.find(elbow).expect("elbow");
    let end = at + urdf[at..].find("</joint>").expect("joint end");
    let joint = urdf[at..end].replace("damping=\"0.0\"", "damping=\"0.5\"");
    let urdf = format!("{}{joint}{}", &urdf[..at], &urdf[end..]);
    std::fs::write(dir.join("my_arm.urdf"), urdf).expect("writes");
    let krate = dir.join("my-arm");
    let said = succeeds(
        dynamics()
            .args(["new"])
            .arg(&krate)
            .arg("--urdf")
            .arg(dir.join("my_arm.urdf")),
    );
    assert!(
        said.contains("robot MyArm") && said.contains("cargo build --release"),
        "{said}"
    );
    let main = std::fs::read_to_string(krate.join("src/main.rs")).expect("main.rs");
    assert!(
        main.contains("pub robot MyArm;")
            && main.contains("dynamics_cli::run_with(MyArm::default(), info)")
    );
    // The workspace's target directory and flags: its compiled crates are reused.
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace().join("target"));
    succeeds(
        Command::new(env!("CARGO"))
            .args(["build", "--release", "--offline"])
            .current_dir(&krate)
            .env("CARGO_TARGET_DIR", &target)
            .env("RUSTFLAGS", "-C target-cpu=native"),
    );
    let program = || Command::new(target.join("release").join("my-arm"));
    let reference = workspace().join("robots/data/pinocchio/ur5.json");
    let checked = succeeds(
        program()
            .args(["check", "--set", "damping_elbow_joint=0", "--reference"])
            .arg(&reference),
    );
    assert!(checked.contains(": ok"));
    // With the damping Pinocchio's model lacks, the values differ.
    fails(program().args(["check", "--reference"]).arg(&reference));
    let (damped, rigid) = (dir.join("damped.json"), dir.join("rigid.json"));
    for (out, set) in [
        (&damped, "damping_elbow_joint=0.5"),
        (&rigid, "damping_elbow_joint=0"),
    ] {
        succeeds(
            program()
                .args(["eval", "--set", set, "--states"])
                .arg(&reference)
                .arg("--out")
                .arg(out),
        );
    }
    let (d, r) = (read_json(&damped), read_json(&rigid));
    let v = d["states"][1]["v"][2].as_f64().expect("v");
    assert!(v.abs() > 1e-3);
    // tau = ... + 0.5 qd at the elbow (joint index 2), the rest the same.
    assert!((tau(&d, 1)[2] - tau(&r, 1)[2] - 0.5 * v).abs() < 1e-9);
    assert!((tau(&d, 1)[0] - tau(&r, 1)[0]).abs() < 1e-12);
    let err = fails(
        program()
            .args(["eval", "--set", "damping_elbow=1", "--states"])
            .arg(&reference),
    );
    assert!(
        err.contains("no parameter `damping_elbow`; known: damping_elbow_joint"),
        "{err}"
    );
    // Generated data and their diagnosis.
    let data = dir.join("data.csv");
    succeeds(
        program()
            .args([
                "synth",
                "--effect",
                "viscous_friction",
                "--joint",
                "wrist_1_joint",
            ])
            .args([
                "--magnitude",
                "1.0",
                "--duration",
                "4",
                "--seed",
                "2",
                "--out",
            ])
            .arg(&data),
    );
    let report = dir.join("report.json");
    succeeds(
        program()
            .args(["diagnose", "--train"])
            .arg(&data)
            .arg("--holdout")
            .arg(dir.join("data-holdout.csv"))
            .arg("--json")
            .arg(&report),
    );
    let v = &read_json(&report)["which"]["verdict"];
    assert_eq!(v["kind"], "viscous_friction", "{v}");
    assert_eq!(v["joint"], "wrist_1_joint", "{v}");
    // An exciting motion within the URDF's limits (margin 0.1), checked
    // here against the URDF's numbers read independently of the program.
    let (motion, design) = (dir.join("excite.csv"), dir.join("excite.json"));
    succeeds(
        program()
            .args([
                "excite",
                "--duration",
                "10",
                "--rate",
                "200",
                "--evaluations",
                "100",
            ])
            .arg("--out")
            .arg(&motion)
            .arg("--json")
            .arg(&design),
    );
    crate::excite::assert_within_urdf_limits(
        &motion,
        &workspace().join("robots/data/urdf/ur5.urdf"),
        0.1,
    );
    let d = read_json(&design);
    assert_eq!(d["check"]["effort"], true, "{d}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `new` checks what it is given before writing anything.
#[test]
fn new_refuses_bad_input_with_the_cause() {
    let dir = fresh_dir("newbad");
    let urdf = workspace().join("robots/data/urdf/ur5.urdf");
    let new = |target: &Path, urdf: &Path, extra: &[&str]| {
        fails(
            dynamics()
                .arg("new")
                .arg(target)
                .arg("--urdf")
                .arg(urdf)
                .args(extra),
        )
    };
    let err = new(&dir.join("a"), &dir.join("none.urdf"), &[]);
    assert!(
        err.contains("none.urdf") && err.contains("No such file"),
        "{err}"
    );
    let err = new(&dir.join("a"), &urdf, &["--name", "my_arm"]);
    assert!(
        err.contains("--name `my_arm`: not a Rust type name"),
        "{err}"
    );
    let err = new(&dir.join("a"), &urdf, &["--gravity", "0,-9.81"]);
    assert!(
        err.contains("--gravity `0,-9.81`: expected three finite numbers"),
        "{err}"
    );
    std::fs::write(dir.join("full.txt"), "x").expect("writes");
    let err = new(&dir, &urdf, &[]);
    assert!(err.contains("exists and is not an empty folder"), "{err}");
    let broken = dir.join("broken.urdf");
    std::fs::write(&broken, r#"<robot name="b"><link name="a"/><joint name="j" type="revolute"><parent link="a"/><child link="zz"/></joint></robot>"#).expect("writes");
    let err = new(&dir.join("b"), &broken, &[]);
    assert!(
        err.contains("joint `j`") && err.contains("unknown link"),
        "{err}"
    );
    // A Python package builds against the checkout's bindings only.
    let err = new(&dir.join("c"), &urdf, &["--python", "--registry"]);
    assert!(
        err.contains("--python") && err.contains("--registry"),
        "{err}"
    );
    assert!(!dir.join("a").exists() && !dir.join("b").exists() && !dir.join("c").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `new --python` writes a maturin package whose module is the folder's
/// name: the `robot!` call and one line of bindings (python/tests builds
/// and installs one into a fresh virtual environment).
#[test]
fn new_python_writes_a_package_for_the_bindings() {
    let dir = fresh_dir("newpy");
    let krate = dir.join("my-arm");
    let said = succeeds(
        dynamics()
            .arg("new")
            .arg(&krate)
            .arg("--urdf")
            .arg(workspace().join("robots/data/urdf/ur5.urdf"))
            .arg("--python"),
    );
    assert!(
        said.contains("Python module my_arm") && said.contains("pip install"),
        "{said}"
    );
    let read = |f: &str| std::fs::read_to_string(krate.join(f)).expect("written");
    let cargo = read("Cargo.toml");
    assert!(
        cargo.contains("name = \"my_arm\"\ncrate-type = [\"cdylib\"]"),
        "{cargo}"
    );
    assert!(
        cargo.contains("dynamics-python = { path = ") && cargo.contains("default-features = false")
    );
    assert!(read("pyproject.toml").contains("module-name = \"my_arm\""));
    let lib = read("src/lib.rs");
    assert!(
        lib.contains("pub robot Ur5;") && lib.contains("fn my_arm("),
        "{lib}"
    );
    assert!(lib.contains("_dynamics::kernel(Ur5::default())"), "{lib}");
    assert!(krate.join("ur5.urdf").is_file() && krate.join("Cargo.lock").is_file());
    assert!(!krate.join("src/main.rs").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
