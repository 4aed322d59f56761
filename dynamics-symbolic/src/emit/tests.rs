//! Golden tests of the emission: a small DAG's `let` chain, float
//! literals, leaves alone.

use super::*;

#[test]
fn golden_small_emission() {
    let mut g = Graph::new();
    let (x, y) = (g.var(Var(0)), g.var(Var(1)));
    let (s, c) = (g.sin(x), g.cos(x));
    let k = g.constant(-0.5);
    let ks = g.mul(k, s);
    let c2 = g.powi(c, 2);
    let y3 = g.powi(y, -3);
    let p = g.product(&[ks, c2, y3]);
    let one = g.constant(1.0);
    let e = g.sum(&[p, y, one]);
    let t = g.tanh(y);
    let out = emit(&g, &[e, t, x, k], &names);
    assert_eq!(
        out.lets.to_string(),
        // Each value as late as its first use allows: tanh(y) beside
        // the last sum.
        "let (t2 , t3) : (f64 , f64) = x . sin_cos () ; \
         let t10 : f64 = t2 * t3 * t3 / (y * y * y) ; \
         let (t11 , t12) : (f64 , f64) = (1f64 + y - 0.5f64 * t10 , y . tanh ()) ;"
    );
    let roots: Vec<String> = out.roots.iter().map(|r| r.to_string()).collect();
    assert_eq!(roots, ["t11", "t12", "x", "(- 0.5f64)"]);
}

#[test]
fn floats() {
    assert_eq!(float(2.0).to_string(), "2f64");
    assert_eq!(float(-0.25).to_string(), "(- 0.25f64)");
    assert_eq!(float(f64::NAN).to_string(), "f64 :: NAN");
    assert_eq!(float(f64::NEG_INFINITY).to_string(), "(- f64 :: INFINITY)");
}

#[test]
fn leaves_only_emit_nothing() {
    let mut g = Graph::new();
    let x = g.var(Var(2));
    let out = emit(&g, &[x], &names);
    assert!(out.lets.is_empty());
    assert_eq!(out.roots[0].to_string(), "z");
}
