//! The `Constrained<N, M>` implementation of a robot with program
//! constraints: residual, Jacobian and bias of each constraint.

use proc_macro2::TokenStream;
use quote::quote;

use super::body::{self, Spelling};
use crate::derive::Derived;
use crate::model::Model;

/// `impl Constrained<N, M>` when the robot has program constraints.
pub(super) fn emit(model: &Model, d: &Derived, sp: &Spelling) -> TokenStream {
    if d.constraints.is_empty() {
        return TokenStream::new();
    }
    let g = &d.graph;
    let (n, m) = (d.vars.n, d.constraints.len());
    let name = &model.name;
    let names = model.constraints.iter().map(|c| c.name.to_string());
    let f: Vec<_> = d.constraints.iter().map(|c| c.f).collect();
    let jac: Vec<_> = d
        .constraints
        .iter()
        .flat_map(|c| c.jacobian.iter().copied())
        .collect();
    let bias: Vec<_> = d.constraints.iter().map(|c| c.bias).collect();
    let f_body = body::vector(g, &f, sp);
    let jac_body = body::matrix(g, &jac, m, n, sp);
    let bias_body = body::vector(g, &bias, sp);
    quote! {
        #[allow(unused_variables, clippy::all, clippy::pedantic)]
        impl ::dynamics_runtime::Constrained<#n, #m> for #name {
            const CONSTRAINT_NAMES: [&'static str; #m] = [#(#names),*];
            fn constraint_residual(&self, t: f64, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #m> { #f_body }
            fn constraint_jacobian(&self, t: f64, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SMatrix<f64, #m, #n> { #jac_body }
            fn constraint_bias(&self, t: f64, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #m> { #bias_body }
        }
    }
}
