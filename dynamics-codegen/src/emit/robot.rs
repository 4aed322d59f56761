//! The robot struct and its `Robot<N>` implementation (the regressor
//! bodies from `regressor.rs`, a constrained robot's impl from
//! `constraints.rs`).

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::body::{self, Spelling};
use super::{constraints, lanes, regressor};
use crate::derive::Derived;
use crate::model::{JointKind, Model};

/// The robot struct, its inherent items and the trait impl.
pub fn emit(model: &Model, d: &Derived) -> TokenStream {
    let g = &d.graph;
    let n = d.vars.n;
    let sp = Spelling::new(d.vars, model);
    let vis = &model.vis;
    let name = &model.name;
    let attrs = &model.attrs;
    let params = format_ident!("{}Params", name);
    let name_str = name.to_string();

    let coords = model.coords();
    let joint_names = coords.iter().map(|&j| model.joints[j].name.to_string());
    let joint_kinds = coords.iter().map(|&j| match model.joints[j].kind {
        JointKind::Prismatic => quote!(::dynamics_runtime::JointKind::Prismatic),
        _ => quote!(::dynamics_runtime::JointKind::Revolute),
    });
    let frame_names = model.links.iter().map(|l| l.name.to_string());
    let point_names = model
        .links
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.name.to_string()));
    let gravity = model.gravity.map(Literal::f64_suffixed);

    let upper: Vec<_> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
    let a_roots: Vec<_> = upper.iter().map(|&(i, j)| d.a[i][j]).collect();
    let mass_matrix = body::matrix(g, &a_roots, n, n, &sp);
    let qqt1 = body::vector(g, &d.qqt1, &sp);
    let qqt2 = body::vector(g, &d.qqt2, &sp);
    let qqt = body::vector(g, &d.qqt, &sp);
    let c_roots: Vec<_> = upper.iter().map(|&(i, j)| d.coriolis[i][j]).collect();
    let coriolis = body::matrix(g, &c_roots, n, n, &sp);
    let gravity_body = body::vector(g, &d.gravity, &sp);
    let q0 = body::vector(g, &d.q0, &sp);
    let tau = body::vector(g, &d.tau, &sp);
    let kinetic = body::scalar(g, d.kinetic, &sp);
    let potential = body::scalar(g, d.potential, &sp);

    let terms = {
        let mut roots = a_roots.clone();
        roots.extend(&d.qqt);
        roots.extend(&d.q0);
        let (lets, vals) = body::chain(g, &roots, &sp);
        let nn = n * n;
        let a_set = body::assign_matrix(g, &a_roots, &vals[..nn], n, quote!(a));
        let qqt_set = body::assign_vector(g, &d.qqt, &vals[nn..nn + n], quote!(qqt));
        let q0_set = body::assign_vector(g, &d.q0, &vals[nn + n..], quote!(q0));
        quote! {
            #lets
            let mut a = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            let mut qqt = ::dynamics_runtime::nalgebra::SVector::<f64, #n>::zeros();
            let mut q0 = ::dynamics_runtime::nalgebra::SVector::<f64, #n>::zeros();
            #a_set #qqt_set #q0_set
            ::dynamics_runtime::MotionTerms { a, qqt, q0 }
        }
    };

    let fused = {
        let p = &d.perturbation;
        let a_roots: Vec<_> = upper.iter().map(|&(i, j)| d.a_fused[i][j]).collect();
        let mut first = a_roots.clone();
        first.extend(&d.qqt_fused);
        first.extend(&d.q0);
        let mut second: Vec<_> = p.k.iter().flatten().copied().collect();
        second.extend(p.d.iter().flatten());
        let stages = body::stages(g, &[&first, &second], &sp);
        let (lets1, vals1) = &stages[0];
        let (lets2, vals2) = &stages[1];
        let nn = n * n;
        let a_set = body::assign_matrix(g, &a_roots, &vals1[..nn], n, quote!(a));
        let qqt_set = body::assign_vector(g, &d.qqt_fused, &vals1[nn..nn + n], quote!(qqt));
        let q0_set = body::assign_vector(g, &d.q0, &vals1[nn + n..], quote!(q0));
        let k_set = body::assign_matrix(g, &second[..nn], &vals2[..nn], n, quote!(k));
        let d_set = body::assign_matrix(g, &second[nn..], &vals2[nn..], n, quote!(d));
        quote! {
            #lets1
            let mut a = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            let mut qqt = ::dynamics_runtime::nalgebra::SVector::<f64, #n>::zeros();
            let mut q0 = ::dynamics_runtime::nalgebra::SVector::<f64, #n>::zeros();
            #a_set #qqt_set #q0_set
            let qdd = accelerations(&::dynamics_runtime::MotionTerms { a, qqt, q0 })?;
            #lets2
            let mut k = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            let mut d = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            #k_set #d_set
            ::core::option::Option::Some((qdd, ::dynamics_runtime::PerturbationJacobians { k, d }))
        }
    };

    let perturbation = {
        let p = &d.perturbation;
        let mut roots: Vec<_> = p.k.iter().flatten().copied().collect();
        roots.extend(p.d.iter().flatten());
        let (lets, vals) = body::chain(g, &roots, &sp);
        let nn = n * n;
        let k_set = body::assign_matrix(g, &roots[..nn], &vals[..nn], n, quote!(k));
        let d_set = body::assign_matrix(g, &roots[nn..], &vals[nn..], n, quote!(d));
        quote! {
            #lets
            let mut k = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            let mut d = ::dynamics_runtime::nalgebra::SMatrix::<f64, #n, #n>::zeros();
            #k_set #d_set
            ::dynamics_runtime::PerturbationJacobians { k, d }
        }
    };
    let sensitivity_arms = d.perturbation.dp.iter().enumerate().map(|(k, col)| {
        let b = body::vector(g, col, &sp);
        quote! { #k => ::core::option::Option::Some({ #b }), }
    });

    let frame_arms = d.frames.iter().enumerate().map(|(k, pose)| {
        let r = &pose.r;
        let roots = vec![
            r[0][0], r[0][1], r[0][2], pose.p[0], r[1][0], r[1][1], r[1][2], pose.p[1], r[2][0],
            r[2][1], r[2][2], pose.p[2],
        ];
        let (lets, vals) = body::chain(g, &roots, &sp);
        let z = Literal::f64_suffixed(0.0);
        let o = Literal::f64_suffixed(1.0);
        quote! {
            #k => {
                #lets
                ::core::option::Option::Some(::dynamics_runtime::nalgebra::Matrix4::new(
                    #(#vals,)* #z, #z, #z, #o
                ))
            }
        }
    });
    let point_arms = d.points.iter().enumerate().map(|(k, p)| {
        let (lets, vals) = body::chain(g, p, &sp);
        quote! {
            #k => {
                #lets
                ::core::option::Option::Some(::dynamics_runtime::nalgebra::Vector3::new(#(#vals),*))
            }
        }
    });
    let jac_arms = d.point_jacobians.iter().enumerate().map(|(k, jac)| {
        let roots: Vec<_> = jac.iter().flat_map(|row| row.iter().copied()).collect();
        let b = body::matrix(g, &roots, 3, n, &sp);
        quote! { #k => { ::core::option::Option::Some({ #b }) } }
    });

    let lane_methods = lane_methods(model, d, &a_roots);

    let link_names = d
        .regressor
        .links
        .iter()
        .map(|&l| model.links[l].name.to_string());
    let (regressor, parameters) = regressor::bodies(d, &sp);
    let constrained = constraints::emit(model, d, &sp);
    let doc_n = format!(" Number of joint coordinates of [`{name}`].");
    quote! {
        #(#attrs)*
        #[derive(Debug, Clone, Copy, Default, PartialEq)]
        #vis struct #name {
            /// Run-time parameters.
            pub params: #params,
        }

        impl #name {
            #[doc = #doc_n]
            pub const DOF: usize = #n;
            /// A robot with the given run-time parameters.
            pub fn new(params: #params) -> Self {
                Self { params }
            }
        }

        #[allow(unused_variables, clippy::all, clippy::pedantic)]
        impl ::dynamics_runtime::Robot<#n> for #name {
            type Params = #params;
            const NAME: &'static str = #name_str;
            const JOINT_NAMES: [&'static str; #n] = [#(#joint_names),*];
            const JOINT_KINDS: [::dynamics_runtime::JointKind; #n] = [#(#joint_kinds),*];
            const FRAME_NAMES: &'static [&'static str] = &[#(#frame_names),*];
            const POINT_NAMES: &'static [&'static str] = &[#(#point_names),*];
            const GRAVITY: [f64; 3] = [#(#gravity),*];
            const LINK_NAMES: &'static [&'static str] = &[#(#link_names),*];

            fn params(&self) -> &#params { &self.params }
            fn params_mut(&mut self) -> &mut #params { &mut self.params }

            #[inline]
            fn mass_matrix(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SMatrix<f64, #n, #n> { #mass_matrix }
            #[inline]
            fn qqt1(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #qqt1 }
            #[inline]
            fn qqt2(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #qqt2 }
            #[inline]
            fn qqt(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #qqt }
            #[inline]
            fn coriolis_matrix(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SMatrix<f64, #n, #n> { #coriolis }
            #[inline]
            fn gravity(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #gravity_body }
            #[inline]
            fn generalized_forces(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #q0 }
            #[inline]
            fn inverse_dynamics(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qdd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::nalgebra::SVector<f64, #n> { #tau }
            #[inline]
            fn perturbation_jacobians(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qdd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::PerturbationJacobians<#n> { #perturbation }
            fn parameter_sensitivity(&self, index: usize, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qdd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::core::option::Option<::dynamics_runtime::nalgebra::SVector<f64, #n>> {
                match index { #(#sensitivity_arms)* _ => ::core::option::Option::None }
            }
            fn inertial_regressor(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qdd: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                out: &mut [::dynamics_runtime::nalgebra::SMatrix<f64, #n, 10>])
                -> ::core::result::Result<(), ::dynamics_runtime::DynamicsError> { #regressor }
            fn inertial_parameters(&self, out: &mut [::dynamics_runtime::nalgebra::SVector<f64, 10>])
                -> ::core::result::Result<(), ::dynamics_runtime::DynamicsError> { #parameters }
            #[inline]
            fn motion_terms(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::dynamics_runtime::MotionTerms<#n> { #terms }
            fn motion_and_jacobians<F>(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>, mut accelerations: F)
                -> ::core::option::Option<(::dynamics_runtime::nalgebra::SVector<f64, #n>,
                    ::dynamics_runtime::PerturbationJacobians<#n>)>
            where
                F: ::core::ops::FnMut(&::dynamics_runtime::MotionTerms<#n>)
                    -> ::core::option::Option<::dynamics_runtime::nalgebra::SVector<f64, #n>>,
            { #fused }
            #[inline]
            fn kinetic_energy(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>,
                qd: &::dynamics_runtime::nalgebra::SVector<f64, #n>) -> f64 { #kinetic }
            #[inline]
            fn potential_energy(&self, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>) -> f64 { #potential }
            fn frame_pose(&self, index: usize, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::core::option::Option<::dynamics_runtime::nalgebra::Matrix4<f64>> {
                match index { #(#frame_arms)* _ => ::core::option::Option::None }
            }
            fn point_position(&self, index: usize, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::core::option::Option<::dynamics_runtime::nalgebra::Vector3<f64>> {
                match index { #(#point_arms)* _ => ::core::option::Option::None }
            }
            fn point_jacobian(&self, index: usize, q: &::dynamics_runtime::nalgebra::SVector<f64, #n>)
                -> ::core::option::Option<::dynamics_runtime::nalgebra::SMatrix<f64, 3, #n>> {
                match index { #(#jac_arms)* _ => ::core::option::Option::None }
            }
            #lane_methods
        }

        #constrained
    }
}

/// The `*_lanes` methods: the scalar methods' chains over a lane type `L`
/// (see `lanes.rs`), always inlined so that the batch functions compile
/// them for the CPU features they run with.
fn lane_methods(model: &Model, d: &Derived, a_roots: &[dynamics_symbolic::Id]) -> TokenStream {
    let g = &d.graph;
    let n = d.vars.n;
    let sp = Spelling::lanes(d.vars, model);
    let nn = n * n;
    let tau = lanes::vector(g, &d.tau, &sp);

    let mass_matrix = {
        let (lets, vals) = body::chain(g, a_roots, &sp);
        let zero = lanes::zero_matrix("a", n);
        let set = lanes::assign_matrix(g, a_roots, &vals, n, quote!(a));
        quote! { #lets #zero #set a }
    };

    let terms = {
        let mut roots = a_roots.to_vec();
        roots.extend(&d.qqt);
        roots.extend(&d.q0);
        let (lets, vals) = body::chain(g, &roots, &sp);
        let zeros = [
            lanes::zero_matrix("a", n),
            lanes::zero_vector("qqt", n),
            lanes::zero_vector("q0", n),
        ];
        let a_set = lanes::assign_matrix(g, a_roots, &vals[..nn], n, quote!(a));
        let qqt_set = body::assign_vector(g, &d.qqt, &vals[nn..nn + n], quote!(qqt));
        let q0_set = body::assign_vector(g, &d.q0, &vals[nn + n..], quote!(q0));
        quote! { #lets #(#zeros)* #a_set #qqt_set #q0_set (a, qqt, q0) }
    };

    let perturbation = {
        let p = &d.perturbation;
        let mut roots: Vec<_> = p.k.iter().flatten().copied().collect();
        roots.extend(p.d.iter().flatten());
        let (lets, vals) = body::chain(g, &roots, &sp);
        let zeros = [lanes::zero_matrix("k", n), lanes::zero_matrix("d", n)];
        let k_set = lanes::assign_matrix(g, &roots[..nn], &vals[..nn], n, quote!(k));
        let d_set = lanes::assign_matrix(g, &roots[nn..], &vals[nn..], n, quote!(d));
        quote! { #lets #(#zeros)* #k_set #d_set (k, d) }
    };

    let fused = {
        let p = &d.perturbation;
        let upper: Vec<_> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
        let a_roots: Vec<_> = upper.iter().map(|&(i, j)| d.a_fused[i][j]).collect();
        let mut first = a_roots.clone();
        first.extend(&d.qqt_fused);
        first.extend(&d.q0);
        let mut second: Vec<_> = p.k.iter().flatten().copied().collect();
        second.extend(p.d.iter().flatten());
        let stages = body::stages(g, &[&first, &second], &sp);
        let (lets1, vals1) = &stages[0];
        let (lets2, vals2) = &stages[1];
        let zeros1 = [
            lanes::zero_matrix("a", n),
            lanes::zero_vector("qqt", n),
            lanes::zero_vector("q0", n),
        ];
        let zeros2 = [lanes::zero_matrix("k", n), lanes::zero_matrix("d", n)];
        let a_set = lanes::assign_matrix(g, &a_roots, &vals1[..nn], n, quote!(a));
        let qqt_set = body::assign_vector(g, &d.qqt_fused, &vals1[nn..nn + n], quote!(qqt));
        let q0_set = body::assign_vector(g, &d.q0, &vals1[nn + n..], quote!(q0));
        let k_set = lanes::assign_matrix(g, &second[..nn], &vals2[..nn], n, quote!(k));
        let d_set = lanes::assign_matrix(g, &second[nn..], &vals2[nn..], n, quote!(d));
        quote! {
            #lets1
            #(#zeros1)*
            #a_set #qqt_set #q0_set
            let qdd = accelerations(&a, &qqt, &q0);
            #lets2
            #(#zeros2)*
            #k_set #d_set
            (qdd, k, d)
        }
    };

    quote! {
        #[inline(always)]
        fn inverse_dynamics_lanes<L: ::dynamics_runtime::lanes::Lanes>(&self,
            q: &[L; #n], qd: &[L; #n], qdd: &[L; #n]) -> [L; #n] { #tau }
        #[inline(always)]
        fn mass_matrix_lanes<L: ::dynamics_runtime::lanes::Lanes>(&self, q: &[L; #n])
            -> [[L; #n]; #n] { #mass_matrix }
        #[inline(always)]
        fn motion_terms_lanes<L: ::dynamics_runtime::lanes::Lanes>(&self, q: &[L; #n], qd: &[L; #n])
            -> ([[L; #n]; #n], [L; #n], [L; #n]) { #terms }
        #[inline(always)]
        fn perturbation_jacobians_lanes<L: ::dynamics_runtime::lanes::Lanes>(&self,
            q: &[L; #n], qd: &[L; #n], qdd: &[L; #n]) -> ([[L; #n]; #n], [[L; #n]; #n]) { #perturbation }
        #[inline(always)]
        fn motion_and_jacobians_lanes<L: ::dynamics_runtime::lanes::Lanes, F>(&self,
            q: &[L; #n], qd: &[L; #n], accelerations: F) -> ([L; #n], [[L; #n]; #n], [[L; #n]; #n])
        where
            F: ::core::ops::FnOnce(&[[L; #n]; #n], &[L; #n], &[L; #n]) -> [L; #n],
        { #fused }
    }
}
