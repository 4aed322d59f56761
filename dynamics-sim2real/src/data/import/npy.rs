//! NumPy `.npy` arrays through the `npyz` crate: a 0-, 1- or 2-D array of
//! floating-point or integer numbers (either byte order, C or Fortran
//! order) as a [`Table`] (a 1-D array is one column). The data's size is
//! checked against the bytes there before anything is read, so that a
//! hostile shape costs no memory.

use npyz::{DType, NpyFile, Order, TypeChar};

use super::table::Table;

#[cfg(test)]
const MAGIC: &[u8] = b"\x93NUMPY";

/// Reads the `.npy` bytes of array `source`; the error is a plain message
/// (the caller names the file and the array).
pub(crate) fn parse(bytes: &[u8], source: &str) -> Result<Table, String> {
    if !bytes.starts_with(b"\x93NUMPY") || bytes.len() < 10 {
        return Err("no .npy magic bytes (\\x93NUMPY)".into());
    }
    // The header's length, to know how many data bytes follow it.
    let header_end = match bytes[6] {
        1 => 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize,
        2 | 3 if bytes.len() >= 12 => {
            12 + u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize
        }
        major => {
            return Err(format!(
                ".npy format version {major} is not read (1, 2 and 3 are)"
            ))
        }
    };
    let data_len = bytes
        .len()
        .checked_sub(header_end)
        .ok_or("the header is cut short")?;
    let npy = NpyFile::new(bytes).map_err(|e| format!("the header cannot be read: {e}"))?;
    let descr = match npy.dtype() {
        DType::Plain(ts) => ts,
        other => {
            return Err(format!(
                "element type `{}` is not read (a structured array)",
                other.descr()
            ))
        }
    };
    let unsupported =
        || format!("element type `{descr}` is not read (floats f4/f8, integers i1-i8/u1-u8 are)");
    let size = descr.size_field() as usize;
    match (descr.type_char(), size) {
        (TypeChar::Float, 4 | 8) | (TypeChar::Int | TypeChar::Uint, 1 | 2 | 4 | 8) => {}
        _ => return Err(unsupported()),
    }
    let shape: Vec<usize> = npy.shape().iter().map(|&n| n as usize).collect();
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
    let count = rows.checked_mul(cols).ok_or("the shape overflows")?;
    let need = count.checked_mul(size).ok_or("the shape overflows")?;
    if data_len < need {
        return Err(format!(
            "shape {shape:?} needs {need} bytes of data, the array has {data_len}"
        ));
    }
    let fortran = npy.order() == Order::Fortran;
    let read = |e: std::io::Error| format!("the data cannot be read: {e}");
    let mut values: Vec<f64> = match (descr.type_char(), size) {
        (TypeChar::Float, 8) => npy.into_vec::<f64>().map_err(read)?,
        (TypeChar::Float, _) => floats(npy.into_vec::<f32>().map_err(read)?),
        (TypeChar::Int, 1) => floats(npy.into_vec::<i8>().map_err(read)?),
        (TypeChar::Int, 2) => floats(npy.into_vec::<i16>().map_err(read)?),
        (TypeChar::Int, 4) => floats(npy.into_vec::<i32>().map_err(read)?),
        (TypeChar::Int, _) => npy
            .into_vec::<i64>()
            .map_err(read)?
            .into_iter()
            .map(|v| v as f64)
            .collect(),
        (TypeChar::Uint, 1) => floats(npy.into_vec::<u8>().map_err(read)?),
        (TypeChar::Uint, 2) => floats(npy.into_vec::<u16>().map_err(read)?),
        (TypeChar::Uint, 4) => floats(npy.into_vec::<u32>().map_err(read)?),
        (TypeChar::Uint, _) => npy
            .into_vec::<u64>()
            .map_err(read)?
            .into_iter()
            .map(|v| v as f64)
            .collect(),
        _ => return Err(unsupported()),
    };
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

/// Numbers of a narrower type as f64 (exact).
fn floats<T: Into<f64>>(v: Vec<T>) -> Vec<f64> {
    v.into_iter().map(Into::into).collect()
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
