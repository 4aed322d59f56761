//! What `new` reads from its inputs: gravity, and the names of the robot
//! type and the package (checked, or derived from the URDF and the
//! folder).

use std::path::Path;

use super::NewError;

/// Parses `x,y,z`.
///
/// ```
/// use dynamics_cli::scaffold::gravity;
/// assert_eq!(gravity("0, 0, -9.81").unwrap(), [0.0, 0.0, -9.81]);
/// assert!(gravity("0,-9.81").is_err());
/// assert!(gravity("0,0,nan").is_err());
/// ```
pub fn gravity(text: &str) -> Result<[f64; 3], NewError> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| NewError::Gravity(text.into()))?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
        _ => Err(NewError::Gravity(text.into())),
    }
}

/// Whether `name` is an UpperCamelCase Rust type name.
///
/// ```
/// use dynamics_cli::scaffold::type_name_ok;
/// assert!(type_name_ok("MyUr5"));
/// assert!(!type_name_ok("my_ur5") && !type_name_ok("5Axis") && !type_name_ok("Self"));
/// ```
pub fn type_name_ok(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_uppercase())
        && chars.all(|c| c.is_ascii_alphanumeric())
        && name != "Self"
}

/// UpperCamelCase of a URDF robot name (`ur5_arm` -> `Ur5Arm`).
pub(super) fn camel(name: &str) -> String {
    let out: String = name
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
                .unwrap_or_default()
        })
        .collect();
    if out.starts_with(|c: char| c.is_ascii_uppercase()) {
        out
    } else {
        format!("Robot{out}")
    }
}

/// The `name` attribute of the URDF's `<robot>` element.
pub(super) fn urdf_robot_name(text: &str) -> Option<String> {
    let start = text.find("<robot")?;
    let tag = &text[start..start + text[start..].find('>')?];
    let at = tag.find("name")?;
    let rest = tag[at + 4..].trim_start().strip_prefix('=')?.trim_start();
    let quote = rest.chars().next().filter(|c| *c == '"' || *c == '\'')?;
    let rest = &rest[1..];
    Some(rest[..rest.find(quote)?].to_string())
}

/// A package name from the folder's name.
pub(super) fn package_name(dir: &Path) -> String {
    let raw = dir
        .file_name()
        .map(|f| f.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let name: String = raw
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    let name = name.trim_matches('-').to_string();
    if name.starts_with(|c: char| c.is_ascii_lowercase()) {
        name
    } else {
        format!("robot-{name}").trim_end_matches('-').to_string()
    }
}
