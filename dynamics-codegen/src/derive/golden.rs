//! Golden tests of the derivation: the whole pipeline from tokens to the
//! expression DAG of a pendulum and a planar two-link arm, pinned as text.

use dynamics_symbolic::Var;
use quote::quote;

use crate::ctxt::Ctxt;
use crate::{derive, model, parse};

fn derived(tokens: proc_macro2::TokenStream) -> derive::Derived {
    let mut cx = Ctxt::default();
    let ast = parse::parse(tokens, &mut cx);
    let m = model::build(ast, true, std::path::Path::new("."), &mut cx).expect("valid model");
    assert!(cx.check().is_ok());
    derive::derive(&m)
}

fn text(d: &derive::Derived, roots: &[dynamics_symbolic::Id]) -> String {
    let names = |v: Var| {
        let (kind, i) = d.vars.classify(v);
        format!("{}{i}", ["q", "qd", "qdd", "p", "t"][kind])
    };
    // Rename arena ids in order of appearance so the golden pins structure.
    let raw = d.graph.to_text(roots, &names);
    let mut seen: Vec<String> = Vec::new();
    let mut out = String::new();
    let mut rest = raw.as_str();
    while let Some(i) = rest.find('%') {
        out.push_str(&rest[..i]);
        let digits: String = rest[i + 1..]
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        let k = seen.iter().position(|s| *s == digits).unwrap_or_else(|| {
            seen.push(digits.clone());
            seen.len() - 1
        });
        out.push_str(&format!("%{k}"));
        rest = &rest[i + 1 + digits.len()..];
    }
    out.push_str(rest);
    out
}

#[test]
fn pendulum() {
    let d = derived(quote! {
        pub robot Pendulum;
        gravity = [0.0, -10.0, 0.0];
        link base;
        link rod { mass = 2.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
        joint j = revolute(base -> rod) { transfer = [rot_z(q)]; damping = 0.3; }
    });
    // A = m l^2 + Izz, constant.
    assert_eq!(text(&d, &[d.a[0][0]]), "out[0] = 0.6\n");
    // g = dPi/dq = m g l cos q.
    assert_eq!(
        text(&d, &d.gravity),
        "%0 = cos(q0)\n%1 = 10 * %0\nout[0] = %1\n"
    );
    // Q(0) = -g - b qd.
    assert_eq!(
        text(&d, &d.q0),
        "%0 = cos(q0)\n%1 = -10 * %0 + -0.3 * qd0\nout[0] = %1\n"
    );
    // No Coriolis terms for a single joint.
    assert_eq!(text(&d, &d.qqt1), "out[0] = 0\n");
}

#[test]
fn planar_two_link_mass_matrix_depends_on_the_elbow_only() {
    let d = derived(quote! {
        pub robot Two;
        gravity = [0.0, 0.0, 0.0];
        link base;
        link a { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
        link b { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
        joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
        joint j2 = revolute(a -> b) { transfer = [tu(1.0), rot(q)]; }
    });
    // A11 = I1 + I2 + m1 c1^2 + m2 (l1^2 + c2^2 + 2 l1 c2 cos q2)
    //     = 0.1 + 0.1 + 0.25 + 1 + 0.25 + cos q2
    assert_eq!(
        text(&d, &[d.a[0][0], d.a[0][1], d.a[1][1]]),
        "%0 = cos(q1)\n%1 = 1.7 + %0\n%2 = 0.35 + 0.5 * %0\nout[0] = %1\nout[1] = %2\nout[2] = 0.35\n"
    );
    // Qqt1_2 = 1/2 qd^T dA/dq2 qd = -1/2 sin q2 (qd1^2 + qd1 qd2)
    let t = text(&d, &[d.qqt1[1]]);
    assert!(t.contains("sin(q1)") && !t.contains("q0"), "{t}");
}
