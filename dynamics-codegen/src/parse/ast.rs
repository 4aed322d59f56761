//! The syntax tree of a `robot!` input, as written.

use syn::{Attribute, Expr, Ident, Visibility};

/// The whole input: items in the order written.
#[derive(Default)]
pub struct Input {
    /// Every item that parsed.
    pub items: Vec<Item>,
}

/// One top-level item.
pub enum Item {
    /// `#[attr] pub robot Name;`
    Header(Header),
    /// `gravity = [gx, gy, gz];`
    Gravity {
        /// The `gravity` keyword.
        kw: Ident,
        /// The vector expression.
        value: Expr,
    },
    /// `urdf = "path.urdf";`: links and joints from a URDF file.
    Urdf {
        /// The `urdf` keyword.
        kw: Ident,
        /// The path, relative to the using crate's manifest directory.
        path: syn::LitStr,
    },
    /// `const NAME = expr;`: a compile-time constant, folded into the code.
    Const(Binding),
    /// `param NAME = expr;`: a run-time parameter with its default.
    Param(Binding),
    /// `constraint NAME = expr;`: a program constraint f(t, q) = 0 on the
    /// motion (dissertation, eq. 2.39), with joint names standing for their
    /// coordinates and `t` for time.
    Constraint(Binding),
    /// `link NAME;` or `link NAME { ... }`
    Link(LinkDecl),
    /// `joint NAME = KIND(PARENT -> CHILD) { ... }`
    Joint(JointDecl),
}

/// `#[attr] pub robot Name;`
pub struct Header {
    /// Outer attributes and doc comments, passed on to the generated struct.
    pub attrs: Vec<Attribute>,
    /// Visibility of the generated items.
    pub vis: Visibility,
    /// The robot's type name.
    pub name: Ident,
}

/// `NAME = expr`
pub struct Binding {
    /// Doc comments written above it.
    pub attrs: Vec<Attribute>,
    /// The name.
    pub name: Ident,
    /// The value.
    pub value: Expr,
}

/// A link and its inertial data.
pub struct LinkDecl {
    /// The link's name.
    pub name: Ident,
    /// Its properties, in the order written.
    pub props: Vec<Prop>,
}

/// A joint between two links.
pub struct JointDecl {
    /// The joint's name.
    pub name: Ident,
    /// `revolute`, `prismatic` or `fixed` (checked in the model stage).
    pub kind: Ident,
    /// The parent link's name.
    pub parent: Ident,
    /// The child link's name.
    pub child: Ident,
    /// Its properties, in the order written.
    pub props: Vec<Prop>,
}

/// One `key = value;` line inside a link or joint body.
// The variants' sizes depend on proc-macro2's `span-locations` feature
// (larger `Ident`s), which a dependency elsewhere in the workspace turns on
// (binrw_derive, under the bag reader's mcap): the lint's verdict would
// change with the build's feature set, not with this code.
#[allow(clippy::large_enum_variant)]
pub enum Prop {
    /// `key = expr;`
    Value {
        /// The property name.
        key: Ident,
        /// Its value.
        value: Expr,
    },
    /// `point NAME = [x, y, z];`
    Point {
        /// The `point` keyword.
        kw: Ident,
        /// The point's name.
        name: Ident,
        /// Its position in the link frame.
        at: Expr,
    },
    /// `point_mass NAME = mass at [x, y, z];`
    PointMass {
        /// The `point_mass` keyword.
        kw: Ident,
        /// The point mass's name (also a named point).
        name: Ident,
        /// Its mass.
        mass: Expr,
        /// Its position in the link frame.
        at: Expr,
    },
}
