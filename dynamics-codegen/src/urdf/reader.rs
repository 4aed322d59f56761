//! Attribute access on the URDF's XML with errors that name the file, the
//! element and the attribute at fault (all at the `urdf = "..."` literal).

use syn::LitStr;

use crate::ctxt::Ctxt;

/// The file being read and where its errors go.
pub struct Reader<'a> {
    /// The file name as written in the macro input.
    pub rel: &'a str,
    /// The path literal: every error points at it.
    pub lit: &'a LitStr,
    /// Where errors go.
    pub cx: &'a mut Ctxt,
    /// False once any error was recorded.
    pub ok: bool,
}

impl Reader<'_> {
    /// Records `msg`, prefixed by the file name.
    pub fn error(&mut self, msg: String) {
        self.ok = false;
        self.cx
            .error_spanned_by(self.lit, format!("{}: {msg}", self.rel));
    }

    /// The line of `node` in the file.
    pub fn line(node: roxmltree::Node) -> u32 {
        node.document().text_pos_at(node.range().start).row
    }

    /// A required attribute; its absence is an error naming the line.
    pub fn attr<'n>(
        &mut self,
        node: roxmltree::Node<'n, '_>,
        attr: &str,
        what: &str,
    ) -> Option<&'n str> {
        let v = node.attribute(attr);
        if v.is_none() {
            let pos = node.document().text_pos_at(node.range().start);
            self.error(format!(
                "{what} at line {}: missing attribute `{attr}`",
                pos.row
            ));
        }
        v
    }

    /// An optional attribute that must be a finite number when present.
    pub fn number(&mut self, node: roxmltree::Node, attr: &str, owner: &str) -> Option<f64> {
        let text = node.attribute(attr)?;
        match text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Some(v),
            _ => {
                self.error(format!(
                    "`{owner}` (line {}): <{} {attr}=\"{text}\"> is not a finite number{}",
                    Self::line(node),
                    node.tag_name().name(),
                    xacro_hint(text)
                ));
                None
            }
        }
    }

    /// An optional `"x y z"` attribute (zeros when absent).
    pub fn triple(&mut self, node: roxmltree::Node, attr: &str, owner: &str) -> Option<[f64; 3]> {
        let Some(text) = node.attribute(attr) else {
            return Some([0.0; 3]);
        };
        let parts: Vec<Option<f64>> = text
            .split_whitespace()
            .map(|p| p.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect();
        match parts.as_slice() {
            [Some(a), Some(b), Some(c)] => Some([*a, *b, *c]),
            _ => {
                self.error(format!(
                    "`{owner}` (line {}): <{} {attr}=\"{text}\"> must be three finite numbers{}",
                    Self::line(node),
                    node.tag_name().name(),
                    xacro_hint(text)
                ));
                None
            }
        }
    }
}

/// A hint when a value is an unexpanded xacro expression (`${..}`, `$(..)`).
fn xacro_hint(text: &str) -> &'static str {
    if text.contains("${") || text.contains("$(") {
        " (an unexpanded xacro expression: run `xacro` on the file first)"
    } else {
        ""
    }
}
