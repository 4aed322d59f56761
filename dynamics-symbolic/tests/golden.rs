//! Golden tests: what the simplifying builders turn inputs into, pinned as
//! the text form of the DAG.

use dynamics_symbolic::{Graph, Id, Var};

fn names(v: Var) -> String {
    ["x", "y", "z"][v.0 as usize].to_string()
}

/// The text form with node numbers renamed `%a, %b, ...` in order of first
/// appearance, so the goldens pin structure, not arena positions.
fn text(g: &Graph, roots: &[Id]) -> String {
    let raw = g.to_text(roots, &names);
    let mut seen: Vec<String> = Vec::new();
    let mut out = String::new();
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        let mut num = String::new();
        while let Some(d) = chars.peek().filter(|d| d.is_ascii_digit()) {
            num.push(*d);
            chars.next();
        }
        let k = seen.iter().position(|s| *s == num).unwrap_or_else(|| {
            seen.push(num.clone());
            seen.len() - 1
        });
        out.push('%');
        out.push((b'a' + k as u8) as char);
    }
    out
}

fn xyz(g: &mut Graph) -> (Id, Id, Id) {
    (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)))
}

#[test]
fn constants_fold() {
    let mut g = Graph::new();
    let a = g.constant(2.0);
    let b = g.constant(3.0);
    let s = g.add(a, b);
    let p = g.mul(s, b);
    let z = g.constant(0.0);
    let c = g.cos(z);
    let q = g.powi(b, -2);
    let r = g.sqrt(q);
    let all = g.sum(&[p, c, r]);
    assert_eq!(text(&g, &[all]), "out[0] = 16.333333333333332\n");
    // sqrt of a negative constant stays symbolic, x / 0 too: no NaN.
    let m = g.constant(-4.0);
    let sm = g.sqrt(m);
    let (x, _, _) = xyz(&mut g);
    let d = g.div(x, z);
    assert_eq!(
        text(&g, &[sm, d]),
        "%a = sqrt(-4)\n%b = 0^-1 * x\nout[0] = %a\nout[1] = %b\n"
    );
}

#[test]
fn identities_vanish() {
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let zero = g.constant(0.0);
    let one = g.constant(1.0);
    let cases = [
        g.add(x, zero),
        g.mul(x, one),
        g.mul(y, zero),
        g.div(x, one),
        g.div(zero, y),
        g.sub(x, x),
    ];
    assert_eq!(
        text(&g, &cases),
        "out[0] = x\nout[1] = x\nout[2] = 0\nout[3] = x\nout[4] = 0\nout[5] = 0\n"
    );
    let nx = g.neg(x);
    let nnx = g.neg(nx);
    assert_eq!(
        text(&g, &[nx, nnx]),
        "%a = -1 * x\nout[0] = %a\nout[1] = x\n"
    );
    // x y - y x = 0, x / x = 1
    let xy = g.mul(x, y);
    let yx = g.mul(y, x);
    let d = g.sub(xy, yx);
    let q = g.div(x, x);
    assert_eq!(text(&g, &[d, q]), "out[0] = 0\nout[1] = 1\n");
}

#[test]
fn division_by_zero_stays_symbolic() {
    let mut g = Graph::new();
    let (x, _, _) = xyz(&mut g);
    let zero = g.constant(0.0);
    let d = g.div(x, zero);
    assert_eq!(g.as_constant(d), None);
    assert!(g.eval(&[d], &|_| 1.0)[0].is_infinite());
}

#[test]
fn canonical_order() {
    let mut g = Graph::new();
    let (x, y, z) = xyz(&mut g);
    let ab = g.add(x, y);
    let ba = g.add(y, x);
    assert_eq!(ab, ba);
    let p = g.product(&[z, y, x]);
    let q = g.product(&[x, z, y]);
    assert_eq!(p, q);
    assert_eq!(
        text(&g, &[ba, q]),
        "%a = x + y\n%b = x * y * z\nout[0] = %a\nout[1] = %b\n"
    );
}

#[test]
fn sums_are_canonical_and_collect_like_terms() {
    let mut g = Graph::new();
    let (x, y, z) = xyz(&mut g);
    let a = g.sum(&[x, y, z]);
    let b = g.sum(&[z, x, y]);
    assert_eq!(a, b);
    let two_x = g.scale(x, 2.0);
    let three_x = g.scale(x, 3.0);
    let s = g.sum(&[two_x, y, three_x]);
    assert_eq!(text(&g, &[s]), "%a = 5 * x + y\nout[0] = %a\n");
}

#[test]
fn products_collect_powers_and_coefficients() {
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let xy = g.mul(x, y);
    let k = g_const(&mut g, -2.0);
    let p = g.product(&[xy, x, k]);
    assert_eq!(text(&g, &[p]), "%a = -2 * x^2 * y\nout[0] = %a\n");
    let q = g.div(p, x);
    assert_eq!(text(&g, &[q]), "%a = -2 * x * y\nout[0] = %a\n");
}

fn g_const(g: &mut Graph, v: f64) -> Id {
    g.constant(v)
}

#[test]
fn negation_normal_form_distributes_into_sums() {
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let s = g.sub(x, y);
    let n = g.neg(s);
    // -(x - y) is the sum -x + y, not a negation node.
    assert_eq!(text(&g, &[n]), "%a = -1 * x + y\nout[0] = %a\n");
    let back = g.neg(n);
    assert_eq!(back, s);
    // -(2 x y) is a coefficient, not a node over the product.
    let two = g_const(&mut g, 2.0);
    let p = g.product(&[two, x, y]);
    let np = g.neg(p);
    assert_eq!(text(&g, &[np]), "%a = -2 * x * y\nout[0] = %a\n");
}

#[test]
fn pythagoras() {
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let (s, c) = (g.sin(x), g.cos(x));
    let s2 = g.powi(s, 2);
    let c2 = g.powi(c, 2);
    // 3 y sin^2 x + 3 y cos^2 x + y = 4 y
    let three = g_const(&mut g, 3.0);
    let a = g.product(&[three, y, s2]);
    let b = g.product(&[three, y, c2]);
    let e = g.sum(&[a, b, y]);
    assert_eq!(text(&g, &[e]), "%a = 4 * y\nout[0] = %a\n");
    // Different coefficients do not combine.
    let two = g_const(&mut g, 2.0);
    let b2 = g.product(&[two, y, c2]);
    let e2 = g.sum(&[a, b2]);
    assert_eq!(
        text(&g, &[e2]),
        "%a = sin(x)\n%b = cos(x)\n%c = y * %a^2\n%d = y * %b^2\n%e = 3 * %c + 2 * %d\nout[0] = %e\n"
    );
    // sin^2 + cos^2 alone is 1; with a constant, 1 + k.
    let one = g.add(s2, c2);
    let five = g_const(&mut g, 5.0);
    let six = g.sum(&[c2, five, s2]);
    assert_eq!(text(&g, &[one, six]), "out[0] = 1\nout[1] = 6\n");
}

#[test]
fn trig_parity() {
    let mut g = Graph::new();
    let (x, _, _) = xyz(&mut g);
    let nx = g.neg(x);
    let s = g.sin(nx);
    let sx = g.sin(x);
    let ns = g.neg(s);
    assert_eq!(ns, sx);
    let c = g.cos(nx);
    let cx = g.cos(x);
    assert_eq!(c, cx);
    assert_eq!(
        text(&g, &[s, c]),
        "%a = sin(x)\n%b = -1 * %a\n%c = cos(x)\nout[0] = %b\nout[1] = %c\n"
    );
}

#[test]
fn derivative_of_rotation_product() {
    // d/dx (cos x cos y - sin x sin y) = -sin x cos y - cos x sin y
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let (cx, sx, cy, sy) = (g.cos(x), g.sin(x), g.cos(y), g.sin(y));
    let a = g.mul(cx, cy);
    let b = g.mul(sx, sy);
    let e = g.sub(a, b);
    let d = g.diff(e, Var(0));
    let expect = {
        let p = g.mul(sx, cy);
        let q = g.mul(cx, sy);
        let s = g.add(p, q);
        g.neg(s)
    };
    assert_eq!(d, expect);
    let dz = g.diff(e, Var(2));
    assert!(g.is_zero(dz));
}

#[test]
fn emission_is_valid_rust_and_shares_sin_cos() {
    let mut g = Graph::new();
    let (x, y, _) = xyz(&mut g);
    let (s, c) = (g.sin(x), g.cos(x));
    let a = g.mul(s, y);
    let b = g.sub(c, a);
    let inv = g.div(b, y);
    let out = dynamics_symbolic::emit(&g, &[b, inv], &|v| {
        let n = proc_macro2::Ident::new(&names(v), proc_macro2::Span::call_site());
        quote::quote!(#n)
    });
    let lets = out.lets.to_string();
    assert_eq!(lets.matches("sin_cos").count(), 1, "{lets}");
    let roots = &out.roots;
    let block: syn::File = syn::parse_str(&format!(
        "fn f(x: f64, y: f64) -> (f64, f64) {{ {} ({}, {}) }}",
        lets, roots[0], roots[1]
    ))
    .expect("valid Rust");
    assert_eq!(block.items.len(), 1);
    assert_eq!(
        lets,
        "let (t3 , t4) : (f64 , f64) = x . sin_cos () ; \
         let t5 : f64 = y * t3 ; \
         let t8 : f64 = t4 - t5 ; \
         let t10 : f64 = t8 / y ;"
    );
    assert_eq!(roots[0].to_string(), "t8");
    assert_eq!(roots[1].to_string(), "t10");
}
