//! `dynamics new DIR --urdf FILE`: a ready crate for a user's own robot —
//! Cargo.toml, the URDF copied beside it, `src/main.rs` with the `robot!`
//! call and one line that hands `main` to the generic program
//! ([`crate::run`]). With `--python`, a maturin package instead: `src/lib.rs`
//! with the `robot!` call and one line that hands the robot to the Python
//! bindings of the workspace (`python/`, docs/python.md). The inputs are
//! checked first, the URDF by the macro's own pipeline
//! (`dynamics_codegen::expand`), so that a crate that is written also builds.
//!
//! Here: the command's arguments, errors and steps; the names in
//! `names.rs`, the files written in `template.rs`.

mod names;
mod template;

pub use names::{gravity, type_name_ok};

use std::path::{Path, PathBuf};

use clap::Args;
use thiserror::Error;

use names::{camel, package_name, urdf_robot_name};
use template::{check_model, files, python_files, robot_body};

/// `new`.
#[derive(Args, Debug, Clone)]
pub struct NewArgs {
    /// Folder to create (must not exist, or be empty).
    pub dir: PathBuf,
    /// The robot's URDF file.
    #[arg(long, value_name = "FILE")]
    pub urdf: PathBuf,
    /// The robot's Rust type name (default: the URDF's robot name in UpperCamelCase).
    #[arg(long, value_name = "TypeName")]
    pub name: Option<String>,
    /// Gravity in the world frame, m/s^2.
    #[arg(
        long,
        value_name = "X,Y,Z",
        default_value = "0,0,-9.81",
        allow_hyphen_values = true
    )]
    pub gravity: String,
    /// The dynamics workspace the crate depends on by path (default: the checkout this program
    /// was built from).
    #[arg(long, value_name = "WORKSPACE", conflicts_with = "registry")]
    pub path: Option<PathBuf>,
    /// Depend on the crates' registry versions instead of a checkout.
    #[arg(long)]
    pub registry: bool,
    /// Write a Python package instead of a program: `pip install DIR` builds it (maturin)
    /// and `import NAME` (the folder's name, `-` as `_`) gives `NAME.Robot()`, this robot with
    /// the API of the package `dynamics` (needs a checkout: not with --registry).
    #[arg(long, conflicts_with = "registry")]
    pub python: bool,
}

/// Why a crate could not be written.
#[derive(Debug, Error)]
pub enum NewError {
    /// The target folder exists and is not empty (or is a file).
    #[error("{dir}: exists and is not an empty folder; choose a new one")]
    Occupied {
        /// The folder.
        dir: String,
    },
    /// The URDF file cannot be read.
    #[error("--urdf {file}: {source}")]
    Urdf {
        /// The file.
        file: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The URDF does not make a robot.
    #[error("--urdf {file}: {message}")]
    Model {
        /// The file.
        file: String,
        /// The macro's error(s).
        message: String,
    },
    /// Not a Rust type name.
    #[error("--name `{0}`: not a Rust type name in UpperCamelCase (a capital letter, then letters and digits)")]
    Name(String),
    /// Not three finite numbers.
    #[error("--gravity `{0}`: expected three finite numbers x,y,z (m/s^2)")]
    Gravity(String),
    /// No dynamics workspace there.
    #[error("{path}: not a checkout of the dynamics workspace (no dynamics-cli/Cargo.toml there); give --path WORKSPACE or --registry")]
    Workspace {
        /// The path.
        path: String,
    },
    /// Writing failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
}

/// The PyO3 version of `python/` (the bindings): a package for a user's
/// robot must use the same.
const PYO3: &str = "0.30";

/// The checkout this program was built from.
fn built_from() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Runs `dynamics new`.
pub fn new(args: &NewArgs) -> crate::Res {
    let dir = &args.dir;
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| NewError::Io { path, source }
    };
    if dir.exists() {
        let empty = dir.is_dir() && std::fs::read_dir(dir).map_err(io(dir))?.next().is_none();
        if !empty {
            return Err(NewError::Occupied {
                dir: dir.display().to_string(),
            }
            .into());
        }
    }
    let urdf_name = args.urdf.display().to_string();
    let text = std::fs::read_to_string(&args.urdf).map_err(|source| NewError::Urdf {
        file: urdf_name.clone(),
        source,
    })?;
    let name = match &args.name {
        Some(n) => n.clone(),
        None => camel(&urdf_robot_name(&text).unwrap_or_else(|| package_name(dir))),
    };
    if !type_name_ok(&name) {
        return Err(NewError::Name(name).into());
    }
    let g = gravity(&args.gravity)?;
    let file_name = args
        .urdf
        .file_name()
        .map(|f| f.to_string_lossy().to_string())
        .unwrap_or_else(|| "robot.urdf".into());
    let body = robot_body(&name, g, &file_name);
    let source_dir = args.urdf.parent().unwrap_or(Path::new("."));
    let source_dir = if source_dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        source_dir
    };
    check_model(&body, source_dir).map_err(|message| NewError::Model {
        file: urdf_name.clone(),
        message,
    })?;
    let version = env!("CARGO_PKG_VERSION");
    let (deps, workspace) = if args.registry {
        (
            format!("dynamics-macros = \"{version}\"\ndynamics-runtime = \"{version}\"\ndynamics-cli = \"{version}\"\n"),
            None,
        )
    } else {
        let ws = args.path.clone().unwrap_or_else(built_from);
        let ws = std::fs::canonicalize(&ws).unwrap_or(ws);
        if !ws.join("dynamics-cli").join("Cargo.toml").is_file() {
            return Err(NewError::Workspace {
                path: ws.display().to_string(),
            }
            .into());
        }
        let dep = |c: &str| {
            format!(
                "{c} = {{ path = {:?} }}\n",
                ws.join(c).display().to_string()
            )
        };
        let deps = if args.python {
            // The bindings without the built-in robots, and the PyO3 they use.
            dep("dynamics-macros")
                + &dep("dynamics-runtime")
                + &format!(
                    "dynamics-python = {{ path = {:?}, default-features = false }}\npyo3 = \"{}\"\n",
                    ws.join("python").display().to_string(),
                    PYO3
                )
        } else {
            dep("dynamics-macros") + &dep("dynamics-runtime") + &dep("dynamics-cli")
        };
        (deps, Some(ws))
    };
    let package = package_name(dir);
    let module = package.replace('-', "_");
    std::fs::create_dir_all(dir.join("src")).map_err(io(dir))?;
    let written = if args.python {
        python_files(&package, &module, &name, &body, &file_name, &deps)
    } else {
        files(&package, &name, &body, &file_name, &deps)
    };
    for (path, content) in written {
        let path = dir.join(path);
        std::fs::write(&path, content).map_err(io(&path))?;
    }
    let copy = dir.join(&file_name);
    std::fs::write(&copy, &text).map_err(io(&copy))?;
    if let Some(ws) = &workspace {
        // The same dependency versions as the workspace (and an offline build).
        let lock = if args.python {
            ws.join("python").join("Cargo.lock")
        } else {
            ws.join("Cargo.lock")
        };
        if lock.is_file() {
            std::fs::copy(&lock, dir.join("Cargo.lock")).map_err(io(&lock))?;
        }
    }
    let shown = dir.display();
    if args.python {
        println!(
            "wrote {shown}: pyproject.toml, Cargo.toml, src/lib.rs, {file_name} (robot {name}, Python module {module})"
        );
        println!("install and use it:");
        println!("  pip install {shown}");
        println!("  python -c \"import {module}; arm = {module}.Robot(); print(arm.joint_names)\"");
        if let Some(ws) = &workspace {
            println!(
                "to share the compiled dependencies with the workspace and build for this CPU as it does:\n  \
                 CARGO_TARGET_DIR={} RUSTFLAGS=\"-C target-cpu=native\" pip install {shown}",
                ws.join("target").display()
            );
        }
        return Ok(());
    }
    println!("wrote {shown}: Cargo.toml, src/main.rs, {file_name} (robot {name})");
    println!("build and run it:");
    println!("  cd {shown} && cargo build --release");
    println!("  ./target/release/{package} eval --states STATES.json     # or: cargo run --release -- --help");
    if let Some(ws) = &workspace {
        println!(
            "to share the compiled dependencies with the workspace and build for this CPU as it does\n\
             (its .cargo/config.toml sets -C target-cpu=native, which does not apply outside it):\n  \
             CARGO_TARGET_DIR={} RUSTFLAGS=\"-C target-cpu=native\" cargo build --release   (the program is then in that target/release/)",
            ws.join("target").display()
        );
    }
    Ok(())
}
