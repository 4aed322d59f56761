//! Reading a URDF file into `robot!` items: the file, its links, its joints,
//! then the tree check.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use syn::LitStr;

use super::joint::{joint, Joints, Limits};
use super::link::inertial;
use super::mimic::check_mimics;
use super::reader::Reader;
use super::tokens::ident;
use super::tree::check_tree;
use crate::ctxt::Ctxt;
use crate::parse::ast::{Binding, JointDecl, LinkDecl};

/// What a URDF file contributes.
pub struct Loaded {
    /// Absolute path of the file (for `include_str!`).
    pub path: PathBuf,
    /// Links.
    pub links: Vec<LinkDecl>,
    /// Joints.
    pub joints: Vec<JointDecl>,
    /// Run-time parameters made for damping and friction.
    pub params: Vec<Binding>,
    /// Limits by joint name.
    pub limits: HashMap<String, Limits>,
}

/// Reads `lit`'s file, relative to `base_dir` (the using crate's
/// `CARGO_MANIFEST_DIR` when called by the macro); every problem goes to
/// `cx`, naming file and element.
pub fn load(lit: &LitStr, base_dir: &Path, cx: &mut Ctxt) -> Option<Loaded> {
    let rel = lit.value();
    let path = base_dir.join(&rel);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            cx.error_spanned_by(
                lit,
                format!(
                    "cannot read URDF `{rel}` (relative to the crate's CARGO_MANIFEST_DIR): {e}"
                ),
            );
            return None;
        }
    };
    // Internal DTD entities (`<!ENTITY ...>`) are XML too; roxmltree
    // bounds their expansion.
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = match roxmltree::Document::parse_with_options(&text, options) {
        Ok(d) => d,
        Err(e) => {
            cx.error_spanned_by(lit, format!("{rel}: malformed XML: {e}"));
            return None;
        }
    };
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        cx.error_spanned_by(
            lit,
            format!(
                "{rel}: the root element is <{}>, not <robot>",
                root.tag_name().name()
            ),
        );
        return None;
    }
    let mut r = Reader {
        rel: &rel,
        lit,
        cx,
        ok: true,
    };
    let span = lit.span();
    let mut links = Vec::new();
    let mut link_names = HashSet::new();
    for node in root.children().filter(|n| n.has_tag_name("link")) {
        let Some(name) = r.attr(node, "name", "link") else {
            continue;
        };
        if !link_names.insert(name.to_string()) {
            r.error(format!("<link name=\"{name}\"> is declared twice"));
            continue;
        }
        let props = inertial(&mut r, node, name, span);
        links.push(LinkDecl {
            name: ident(name, span),
            props,
        });
    }
    let mut joints = Vec::new();
    let mut read = Joints::default();
    for node in root.children().filter(|n| n.has_tag_name("joint")) {
        if let Some(j) = joint(&mut r, node, &link_names, &mut read, span) {
            joints.push(j);
        }
    }
    let Joints {
        params,
        limits,
        children,
        parent_of,
        kinds,
        mimics,
    } = read;
    // Exactly one root, and no cycle: checked here to name the file.
    check_tree(&mut r, &link_names, &children, &parent_of);
    let joint_names: HashSet<&str> = root
        .children()
        .filter(|n| n.has_tag_name("joint"))
        .filter_map(|n| n.attribute("name"))
        .collect();
    check_mimics(&mut r, &mimics, &kinds, &joint_names);
    if !r.ok {
        return None;
    }
    Some(Loaded {
        path,
        links,
        joints,
        params,
        limits,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_JOINTS: &str = r#"<robot name="r">
      <link name="base"/>
      <link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>
      <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>
      <joint name="j1" type="continuous">
        <parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="5" velocity="2"/>
        <dynamics damping="0.5"/>
      </joint>
      <joint name="j2" type="prismatic">
        <parent link="a"/><child link="b"/>
        <limit lower="-0.2" upper="0.3" effort="50" velocity="1"/>
        <dynamics friction="0.25"/>
      </joint>
    </robot>"#;

    /// Loads `text` from a file of its own (`name`: tests run in parallel).
    fn load_text(name: &str, text: &str) -> (Option<Loaded>, Ctxt) {
        let dir = std::env::temp_dir().join(format!("dynamics-urdf-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        std::fs::write(dir.join(name), text).expect("a temporary file");
        let lit = LitStr::new(name, proc_macro2::Span::call_site());
        let mut cx = Ctxt::default();
        let loaded = load(&lit, &dir, &mut cx);
        (loaded, cx)
    }

    /// `<dynamics>` may give damping or friction alone (URDF's defaults are
    /// zero); a continuous joint has no position limits even if the file
    /// gives some.
    #[test]
    fn partial_dynamics_and_continuous_limits() {
        let (loaded, cx) = load_text("partial.urdf", TWO_JOINTS);
        assert!(cx.is_ok());
        let loaded = loaded.expect("the file reads");
        assert_eq!(loaded.joints.len(), 2);
        let params: Vec<String> = loaded.params.iter().map(|b| b.name.to_string()).collect();
        assert_eq!(params, ["damping_j1", "friction_j2"]);
        let j1 = loaded.limits["j1"];
        assert_eq!(
            (j1.lower, j1.upper, j1.effort),
            (f64::NEG_INFINITY, f64::INFINITY, 5.0)
        );
        let j2 = loaded.limits["j2"];
        assert_eq!((j2.lower, j2.upper, j2.velocity), (-0.2, 0.3, 1.0));
    }

    #[test]
    fn a_bad_number_is_an_error_naming_the_joint() {
        let (loaded, cx) = load_text("bad-number.urdf", &TWO_JOINTS.replace("0.25", "fast"));
        assert!(loaded.is_none());
        let msg = cx.check().expect_err("an error").to_string();
        assert!(
            msg.contains("`j2`") && msg.contains("friction=\"fast\""),
            "{msg}"
        );
    }
}
