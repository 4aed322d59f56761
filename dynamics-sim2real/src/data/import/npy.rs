//! NumPy `.npy` arrays (format versions 1-3): the header dictionary
//! (`descr`, `fortran_order`, `shape`) and the data of a 0-, 1- or 2-D array
//! of floating-point or integer numbers, as a [`Table`] (a 1-D array is one
//! column).

use super::table::Table;

const MAGIC: &[u8] = b"\x93NUMPY";

/// The element types read: (size in bytes, kind).
#[derive(Clone, Copy)]
enum Kind {
    Float,
    Signed,
    Unsigned,
}

/// Reads the `.npy` bytes of array `source`; the error is a plain message
/// (the caller names the file and the array).
pub(crate) fn parse(bytes: &[u8], source: &str) -> Result<Table, String> {
    if !bytes.starts_with(MAGIC) || bytes.len() < 10 {
        return Err("no .npy magic bytes (\\x93NUMPY)".into());
    }
    let major = bytes[6];
    let (header_len, start) = match major {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        _ => {
            return Err(format!(
                ".npy format version {major} is not read (1, 2 and 3 are)"
            ))
        }
    };
    let header = bytes
        .get(start..start + header_len)
        .ok_or("the header is cut short")?;
    let header = std::str::from_utf8(header).map_err(|_| "the header is not text")?;
    let descr = value_of(header, "descr").ok_or("the header has no 'descr'")?;
    let descr = quoted(descr).ok_or("the header's 'descr' is not a quoted type")?;
    let fortran = match value_of(header, "fortran_order") {
        Some(v) if v.starts_with("True") => true,
        Some(v) if v.starts_with("False") => false,
        _ => return Err("the header has no 'fortran_order'".into()),
    };
    let shape = shape_of(header)?;
    let (little, kind, size) = dtype(descr)?;
    let (rows, cols) = match shape.as_slice() {
        [] => (1, 1),
        [n] => (*n, 1),
        [n, m] => (*n, *m),
        more => {
            return Err(format!(
                "a {}-D array (shape {more:?}); only 1-D and 2-D arrays are read",
                more.len()
            ))
        }
    };
    let count = rows * cols;
    let data = &bytes[start + header_len..];
    if data.len() < count * size {
        return Err(format!(
            "shape {shape:?} needs {} bytes of data, the array has {}",
            count * size,
            data.len()
        ));
    }
    let mut values: Vec<f64> = data[..count * size]
        .chunks_exact(size)
        .map(|c| number(c, little, kind))
        .collect();
    if fortran && rows > 1 && cols > 1 {
        let column_major = values;
        values = (0..count)
            .map(|k| column_major[(k % cols) * rows + k / cols])
            .collect();
    }
    Ok(Table {
        source: source.to_string(),
        rows,
        cols,
        values,
        lines: Vec::new(),
    })
}

/// The text after `'key':` in the header dictionary.
fn value_of<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let at = header
        .find(&format!("'{key}'"))
        .or_else(|| header.find(&format!("\"{key}\"")))?;
    let rest = &header[at + key.len() + 2..];
    Some(rest.trim_start().strip_prefix(':')?.trim_start())
}

/// The text of the quoted string `text` starts with.
fn quoted(text: &str) -> Option<&str> {
    let quote = text.chars().next().filter(|c| *c == '\'' || *c == '"')?;
    text[1..].split(quote).next()
}

/// The `shape` tuple.
fn shape_of(header: &str) -> Result<Vec<usize>, String> {
    let v = value_of(header, "shape").ok_or("the header has no 'shape'")?;
    let inner = v
        .strip_prefix('(')
        .and_then(|s| s.split(')').next())
        .ok_or("the header's 'shape' is not a tuple")?;
    inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.trim_end_matches('L')
                .parse::<usize>()
                .map_err(|_| format!("the header's 'shape' has `{s}`"))
        })
        .collect()
}

/// Byte order, kind and size of a `descr` like `<f8`.
fn dtype(descr: &str) -> Result<(bool, Kind, usize), String> {
    let unsupported =
        || format!("element type `{descr}` is not read (floats f4/f8, integers i1-i8/u1-u8 are)");
    let mut chars = descr.chars();
    let order = chars.next().ok_or_else(unsupported)?;
    let little = match order {
        '<' | '|' | '=' => true,
        '>' => false,
        _ => return Err(unsupported()),
    };
    let kind = match chars.next() {
        Some('f') => Kind::Float,
        Some('i') => Kind::Signed,
        Some('u') => Kind::Unsigned,
        _ => return Err(unsupported()),
    };
    let size: usize = chars.as_str().parse().map_err(|_| unsupported())?;
    match (kind, size) {
        (Kind::Float, 4 | 8) | (Kind::Signed | Kind::Unsigned, 1 | 2 | 4 | 8) => {
            Ok((little, kind, size))
        }
        _ => Err(unsupported()),
    }
}

/// One element as f64.
fn number(bytes: &[u8], little: bool, kind: Kind) -> f64 {
    let mut b = [0u8; 8];
    if little {
        b[..bytes.len()].copy_from_slice(bytes);
    } else {
        for (i, x) in bytes.iter().rev().enumerate() {
            b[i] = *x;
        }
    }
    let n = bytes.len();
    match (kind, n) {
        (Kind::Float, 4) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
        (Kind::Float, _) => f64::from_le_bytes(b),
        (Kind::Unsigned, _) => u64::from_le_bytes(b) as f64,
        (Kind::Signed, _) => {
            // sign-extend from n bytes
            let shift = 64 - 8 * n as u32;
            ((u64::from_le_bytes(b) << shift) as i64 >> shift) as f64
        }
    }
}

/// The `.npy` bytes of a 2-D array of `<f8` (tests: a writer to read back).
#[cfg(test)]
pub(crate) fn write_f8(rows: usize, cols: usize, values: &[f64]) -> Vec<u8> {
    let mut header =
        format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = MAGIC.to_vec();
    out.extend([1, 0]);
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header.bytes());
    for v in values {
        out.extend(v.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
        let header = format!(
            "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}\n",
            if fortran { "True" } else { "False" }
        );
        let mut out = MAGIC.to_vec();
        out.extend([1, 0]);
        out.extend((header.len() as u16).to_le_bytes());
        out.extend(header.bytes());
        out.extend(data);
        out
    }

    #[test]
    fn element_types_orders_and_shapes() {
        let f8: Vec<u8> = [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let t = parse(&npy("<f8", false, "(2, 3)", &f8), "a").unwrap();
        assert_eq!((t.rows, t.cols, t.get(1, 0)), (2, 3, 4.0));
        // Fortran order: the same bytes are the columns.
        let t = parse(&npy("<f8", true, "(2, 3)", &f8), "a").unwrap();
        assert_eq!(t.values, vec![1.0, 3.0, 5.0, 2.0, 4.0, 6.0]);
        let be: Vec<u8> = [1.5f64, -2.0]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        assert_eq!(
            parse(&npy(">f8", false, "(2,)", &be), "a").unwrap().values,
            vec![1.5, -2.0]
        );
        let f4: Vec<u8> = [0.25f32, -8.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        assert_eq!(
            parse(&npy("<f4", false, "(2,)", &f4), "a").unwrap().values,
            vec![0.25, -8.0]
        );
        let i2: Vec<u8> = [-3i16, 7].iter().flat_map(|v| v.to_le_bytes()).collect();
        assert_eq!(
            parse(&npy("<i2", false, "(2,)", &i2), "a").unwrap().values,
            vec![-3.0, 7.0]
        );
        let back = parse(&write_f8(3, 2, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), "a").unwrap();
        assert_eq!((back.rows, back.cols, back.get(2, 1)), (3, 2, 6.0));
    }

    #[test]
    fn what_is_not_read_is_said() {
        let e = parse(&npy("<c16", false, "(1,)", &[0; 16]), "a").unwrap_err();
        assert!(e.contains("element type `<c16` is not read"), "{e}");
        let e = parse(&npy("<f8", false, "(2, 2, 2)", &[0; 64]), "a").unwrap_err();
        assert!(e.contains("a 3-D array"), "{e}");
        let e = parse(&npy("<f8", false, "(4,)", &[0; 16]), "a").unwrap_err();
        assert_eq!(e, "shape [4] needs 32 bytes of data, the array has 16");
        assert!(parse(b"PK\x03\x04", "a").unwrap_err().contains("magic"));
    }
}
