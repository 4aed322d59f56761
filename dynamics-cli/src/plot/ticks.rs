//! Axis ticks at round values (1, 2 or 5 times a power of ten) and their
//! labels, written from integers so that no rounding residue (0.30000000000000004)
//! reaches the page.

/// Ticks inside `[a, b]`: multiples of a round step, about five of them.
/// Each is `(value, label)`.
pub(crate) fn ticks(a: f64, b: f64) -> Vec<(f64, String)> {
    if !(a.is_finite() && b.is_finite()) || b <= a {
        return Vec::new();
    }
    let rough = (b - a) / 5.0;
    let k = rough.log10().floor() as i32;
    let unit = 10f64.powi(k);
    let m = [1i64, 2, 5, 10]
        .into_iter()
        .find(|&m| m as f64 * unit >= rough)
        .unwrap_or(10);
    let (m, k) = if m == 10 { (1, k + 1) } else { (m, k) };
    let step = m as f64 * 10f64.powi(k);
    let (first, last) = ((a / step).ceil() as i64, (b / step).floor() as i64);
    // One style per axis: decimals with the step's places, or scientific
    // when the values are large or small.
    let size = a.abs().max(b.abs());
    let scientific = !(1e-2..1e5).contains(&size);
    (first..=last)
        .map(|n| {
            let v = n as f64 * step;
            let text = if n == 0 {
                "0".to_string()
            } else if scientific {
                scientific_label(n * m, k)
            } else {
                format!("{v:.*}", (-k).max(0) as usize)
            };
            (v, text)
        })
        .collect()
}

/// `i * 10^k` in scientific notation with the shortest mantissa.
fn scientific_label(mut i: i64, mut k: i32) -> String {
    while i % 10 == 0 {
        i /= 10;
        k += 1;
    }
    let digits = i.unsigned_abs().to_string();
    let exponent = k + digits.len() as i32 - 1;
    let sign = if i < 0 { "-" } else { "" };
    let (head, tail) = digits.split_at(1);
    if tail.is_empty() {
        format!("{sign}{head}e{exponent}")
    } else {
        format!("{sign}{head}.{tail}e{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(a: f64, b: f64) -> Vec<String> {
        ticks(a, b).into_iter().map(|t| t.1).collect()
    }

    #[test]
    fn round_steps_and_clean_labels() {
        assert_eq!(labels(0.0, 360.0), ["0", "100", "200", "300"]);
        assert_eq!(labels(-0.1, 0.32), ["-0.1", "0", "0.1", "0.2", "0.3"]);
        assert_eq!(labels(-5.85e-4, 2.18e-4), ["-4e-4", "-2e-4", "0", "2e-4"]);
        assert_eq!(labels(0.0, 2.237), ["0", "0.5", "1.0", "1.5", "2.0"]);
        assert_eq!(labels(0.0, 2e4), ["0", "5000", "10000", "15000", "20000"]);
        assert_eq!(labels(1.0e5, 1.6e6), ["5e5", "1e6", "1.5e6"]);
        assert_eq!(labels(0.0012, 0.0031), ["1.5e-3", "2e-3", "2.5e-3", "3e-3"]);
        assert_eq!(labels(-1e-3, 1e-3), ["-1e-3", "-5e-4", "0", "5e-4", "1e-3"]);
    }

    #[test]
    fn every_tick_lies_in_the_range() {
        for (a, b) in [(-3.3, 7.9), (1e-9, 3e-9), (-1e7, -2e6), (0.45, 0.4501)] {
            let t = ticks(a, b);
            assert!(t.len() >= 2 && t.len() <= 11, "{a} {b}: {t:?}");
            // Within the rounding of `n * step`.
            let tol = 1e-9 * (b - a);
            assert!(
                t.iter().all(|(v, _)| *v >= a - tol && *v <= b + tol),
                "{a} {b}: {t:?}"
            );
        }
        assert!(ticks(1.0, 1.0).is_empty() && ticks(f64::NAN, 1.0).is_empty());
    }
}
