//! The built-in robots of the `robots` crate by name, with their joint
//! limits (URDF robots) and the home pose and amplitudes `synth` moves
//! them about (`robots::builtin::motion`, as the command line does).

use ::robots::registry::{AnyRobot, ROBOTS};
use ::robots::{Arm3rUrdf, MarUrdf, Panda, PandaArm, RrpUrdf, Ur5};
use pyo3::exceptions::PyKeyError;
use pyo3::PyResult;

use crate::kernel::{kernel, Kernel, Limits};
use crate::robot::PyRobot;

/// The names `Robot(name)` knows, with a line each.
pub fn names() -> Vec<(&'static str, &'static str)> {
    ROBOTS.to_vec()
}

fn limits(robot: &AnyRobot) -> Limits {
    macro_rules! of {
        ($t:ty) => {
            Limits::of(<$t>::LOWER, <$t>::UPPER, <$t>::VELOCITY, <$t>::EFFORT)
        };
    }
    match robot {
        AnyRobot::Ur5(_) => of!(Ur5),
        AnyRobot::Panda(_) => of!(Panda),
        AnyRobot::PandaArm(_) => of!(PandaArm),
        AnyRobot::Arm3rUrdf(_) => of!(Arm3rUrdf),
        AnyRobot::RrpUrdf(_) => of!(RrpUrdf),
        AnyRobot::MarUrdf(_) => of!(MarUrdf),
        other => Limits::none(other.joint_names().len()),
    }
}

/// The built-in robot `name`; KeyError listing the known names otherwise.
pub fn robot(name: &str) -> PyResult<PyRobot> {
    let any = AnyRobot::by_name(name).map_err(|e| PyKeyError::new_err(e.to_string()))?;
    let limits = limits(&any);
    let kernel: Box<dyn Kernel> = ::robots::each_robot!(any, r => kernel(r));
    Ok(PyRobot::new(
        name,
        kernel,
        limits,
        robots::builtin::motion(name),
    ))
}
