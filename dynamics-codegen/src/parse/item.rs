//! `syn::parse::Parse` for the items and properties of the grammar.

use syn::parse::{Parse, ParseStream};
use syn::{braced, parenthesized, Attribute, Expr, Ident, Token, Visibility};

use super::ast::{Binding, Header, Item, JointDecl, LinkDecl, Prop};

const ITEMS: &str = "expected an item: `robot Name;`, `gravity = [..];`, `const NAME = ..;`, \
                     `param NAME = ..;`, `constraint NAME = ..;`, `link NAME {..}` or `joint NAME = revolute(PARENT -> CHILD) {..}`";

impl Parse for Item {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        if input.peek(Token![const]) {
            input.parse::<Token![const]>()?;
            let b = binding(attrs, input)?;
            input.parse::<Token![;]>()?;
            return finish(input, Item::Const(b));
        }
        let vis: Visibility = input.parse()?;
        let kw: Ident = input
            .parse()
            .map_err(|e| syn::Error::new(e.span(), ITEMS))?;
        let item = match kw.to_string().as_str() {
            "robot" => Item::Header(Header {
                attrs,
                vis,
                name: input.parse()?,
            }),
            "gravity" => {
                input.parse::<Token![=]>()?;
                Item::Gravity {
                    kw,
                    value: input.parse()?,
                }
            }
            "param" => Item::Param(binding(attrs, input)?),
            "urdf" => {
                input.parse::<Token![=]>()?;
                Item::Urdf {
                    kw,
                    path: input.parse()?,
                }
            }
            "constraint" => Item::Constraint(binding(attrs, input)?),
            "link" => {
                let name = input.parse()?;
                let props = body(input)?;
                return finish(input, Item::Link(LinkDecl { name, props }));
            }
            "joint" => {
                let name = input.parse()?;
                input.parse::<Token![=]>()?;
                let kind = input.parse()?;
                let content;
                parenthesized!(content in input);
                let parent = content.parse()?;
                content.parse::<Token![->]>()?;
                let child = content.parse()?;
                if !content.is_empty() {
                    return Err(content.error("expected `PARENT -> CHILD`"));
                }
                let props = body(input)?;
                return finish(
                    input,
                    Item::Joint(JointDecl {
                        name,
                        kind,
                        parent,
                        child,
                        props,
                    }),
                );
            }
            _ => return Err(syn::Error::new(kw.span(), ITEMS)),
        };
        input.parse::<Token![;]>()?;
        finish(input, item)
    }
}

fn binding(attrs: Vec<Attribute>, input: ParseStream) -> syn::Result<Binding> {
    let name = input.parse()?;
    input.parse::<Token![=]>()?;
    let value = input.parse()?;
    Ok(Binding { attrs, name, value })
}

/// `{ prop* }`, `;` or nothing.
fn body(input: ParseStream) -> syn::Result<Vec<Prop>> {
    let mut props = Vec::new();
    if input.peek(syn::token::Brace) {
        let content;
        braced!(content in input);
        while !content.is_empty() {
            props.push(content.parse()?);
        }
        if input.peek(Token![;]) {
            input.parse::<Token![;]>()?;
        }
    } else {
        input.parse::<Token![;]>()?;
    }
    Ok(props)
}

fn finish(input: ParseStream, item: Item) -> syn::Result<Item> {
    if input.is_empty() {
        Ok(item)
    } else {
        Err(input.error("unexpected tokens after this item; is a `;` missing?"))
    }
}

impl Parse for Prop {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let key: Ident = input.parse()?;
        let prop = match key.to_string().as_str() {
            "point" => {
                let name = input.parse()?;
                input.parse::<Token![=]>()?;
                Prop::Point {
                    kw: key,
                    name,
                    at: input.parse()?,
                }
            }
            "point_mass" => {
                let name = input.parse()?;
                input.parse::<Token![=]>()?;
                let mass = input.parse()?;
                let at_kw: Ident = input.parse()?;
                if at_kw != "at" {
                    return Err(syn::Error::new(
                        at_kw.span(),
                        "expected `at`: `point_mass NAME = MASS at [x, y, z];`",
                    ));
                }
                Prop::PointMass {
                    kw: key,
                    name,
                    mass,
                    at: input.parse()?,
                }
            }
            _ => {
                input.parse::<Token![=]>()?;
                let value: Expr = input.parse()?;
                Prop::Value { key, value }
            }
        };
        input.parse::<Token![;]>()?;
        Ok(prop)
    }
}
