//! NumPy arguments in, NumPy results out: every argument `(N,)` (one
//! state) or `(B, N)` (a batch), float64, read in place when C-contiguous
//! and copied once otherwise; checked for shape and finiteness before any
//! computation, with errors that name the argument and the entry.

use std::borrow::Cow;

use numpy::{
    PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// One argument, read.
pub struct Arg<'py> {
    name: &'static str,
    array: PyReadonlyArrayDyn<'py, f64>,
}

impl<'py> Arg<'py> {
    /// `obj` as a float64 array: itself when it is one, else
    /// `numpy.asarray(obj, dtype=float64)` (lists, integer arrays, ...).
    pub fn new(name: &'static str, obj: &Bound<'py, PyAny>) -> PyResult<Self> {
        let array = match obj.cast::<PyArrayDyn<f64>>() {
            Ok(a) => a.clone(),
            Err(_) => {
                let np = obj.py().import("numpy")?;
                let converted = np.call_method1("asarray", (obj, "float64")).map_err(|e| {
                    PyValueError::new_err(format!("{name}: not an array of numbers ({e})"))
                })?;
                converted.cast_into::<PyArrayDyn<f64>>()?
            }
        };
        Ok(Arg {
            name,
            array: array.readonly(),
        })
    }

    /// The array.
    pub fn array(&self) -> &PyReadonlyArrayDyn<'py, f64> {
        &self.array
    }

    fn shape(&self) -> Vec<usize> {
        self.array.shape().to_vec()
    }

    /// The entries row-major: the array's own memory when C-contiguous,
    /// else a copy in row-major order (`as_slice` alone would also lend a
    /// Fortran-ordered array's memory, column-major).
    fn data(&self) -> Cow<'_, [f64]> {
        if self.array.is_c_contiguous() {
            if let Ok(s) = self.array.as_slice() {
                return Cow::Borrowed(s);
            }
        }
        Cow::Owned(self.array.as_array().iter().copied().collect())
    }
}

/// The arguments of one call, checked: all `(N,)` or all `(B, N)`.
pub struct Batch<'a> {
    /// `None` for one state, `Some(B)` for a batch.
    pub batch: Option<usize>,
    /// Each argument's entries, row-major.
    pub data: Vec<Cow<'a, [f64]>>,
}

impl Batch<'_> {
    /// Number of states.
    pub fn len(&self) -> usize {
        self.batch.unwrap_or(1)
    }

    /// The entries as slices.
    pub fn slices(&self) -> Vec<&[f64]> {
        self.data.iter().map(|d| d.as_ref()).collect()
    }
}

pub fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Checks the shapes (`n` columns) and that every entry is finite.
pub fn check<'a>(args: &'a [Arg<'_>], n: usize) -> PyResult<Batch<'a>> {
    let shapes: Vec<Vec<usize>> = args.iter().map(Arg::shape).collect();
    let describe = || {
        args.iter()
            .zip(&shapes)
            .map(|(a, s)| format!("{} {}", a.name, shape_text(s)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let batch = match shapes[0].as_slice() {
        [_] => None,
        [b, _] => Some(*b),
        _ => {
            return Err(PyValueError::new_err(format!(
                "{} has shape {}: give one state as ({n},) or a batch as (B, {n})",
                args[0].name,
                shape_text(&shapes[0])
            )))
        }
    };
    for (a, s) in args.iter().zip(&shapes) {
        let ok = match (batch, s.as_slice()) {
            (None, [m]) => *m == n,
            (Some(b), [c, m]) => *c == b && *m == n,
            _ => false,
        };
        if !ok {
            let want = match batch {
                None => format!("({n},)"),
                Some(b) => format!("({b}, {n})"),
            };
            return Err(PyValueError::new_err(format!(
                "{} has shape {}, expected {want} (this robot has {n} joints; \
                 every argument one state (N,) or all the same batch (B, N)): got {}",
                a.name,
                shape_text(s),
                describe()
            )));
        }
    }
    let data: Vec<Cow<'a, [f64]>> = args.iter().map(Arg::data).collect();
    for (a, d) in args.iter().zip(&data) {
        if let Some(k) = d.iter().position(|x| !x.is_finite()) {
            let place = match batch {
                None => format!("{}[{k}]", a.name),
                Some(_) => format!("{}[{}, {}]", a.name, k / n, k % n),
            };
            return Err(PyValueError::new_err(format!(
                "{place} is {}: inputs must be finite",
                d[k]
            )));
        }
    }
    Ok(Batch { batch, data })
}

/// A new float64 array of `shape` with its entries as a mutable slice.
pub fn output<'py>(py: Python<'py>, shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    PyArrayDyn::<f64>::zeros(py, shape, false)
}

/// The caller's `out=` buffers for outputs of full shapes `shapes` (batch
/// dimension included): one array for one output, a tuple or list of as
/// many arrays as outputs otherwise; each float64, of exactly its shape,
/// C-contiguous (whether it is writeable and has memory of its own is
/// seen when it is borrowed for writing: [`write_error`]). Returns each
/// with its name in messages.
pub fn out_buffers<'py>(
    out: &Bound<'py, PyAny>,
    shapes: &[Vec<usize>],
) -> PyResult<Vec<(String, Bound<'py, PyArrayDyn<f64>>)>> {
    let wanted = || {
        shapes
            .iter()
            .map(|s| shape_text(s))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let items: Vec<(String, Bound<'py, PyAny>)> = if shapes.len() == 1 {
        vec![("out".to_string(), out.clone())]
    } else {
        let is_sequence = out.is_instance_of::<pyo3::types::PyTuple>()
            || out.is_instance_of::<pyo3::types::PyList>();
        let n = if is_sequence { out.len()? } else { 0 };
        if !is_sequence || n != shapes.len() {
            return Err(PyValueError::new_err(format!(
                "out: give a tuple of {} float64 arrays of shapes {}",
                shapes.len(),
                wanted()
            )));
        }
        (0..n)
            .map(|i| Ok((format!("out[{i}]"), out.get_item(i)?)))
            .collect::<PyResult<_>>()?
    };
    items
        .into_iter()
        .zip(shapes)
        .map(|((name, item), shape)| {
            let array = match item.cast::<PyArrayDyn<f64>>() {
                Ok(array) => array.clone(),
                Err(_) => return Err(not_float64(&name, &item, shape)),
            };
            if array.shape() != shape.as_slice() {
                return Err(PyValueError::new_err(format!(
                    "{name} has shape {}, expected {}",
                    shape_text(array.shape()),
                    shape_text(shape)
                )));
            }
            if !array.is_c_contiguous() {
                return Err(PyValueError::new_err(format!(
                    "{name} is not C-contiguous: give a C-contiguous float64 array \
                     (numpy.empty({}))",
                    shape_text(shape)
                )));
            }
            // Whether it is writeable and has memory of its own is seen when
            // it is borrowed for writing (`write_error`).
            Ok((name, array))
        })
        .collect()
}

/// Why `item`, given as `name`, is not a float64 array.
fn not_float64(name: &str, item: &Bound<'_, PyAny>, shape: &[usize]) -> PyErr {
    match item.cast::<PyUntypedArray>() {
        Ok(untyped) => PyValueError::new_err(format!(
            "{name} has dtype {}, expected float64",
            untyped
                .dtype()
                .str()
                .map(|s| s.to_string())
                .unwrap_or_default()
        )),
        Err(_) => PyValueError::new_err(format!(
            "{name} is a {}, not a NumPy array: give a C-contiguous float64 array of shape {}",
            item.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default(),
            shape_text(shape)
        )),
    }
}

/// The error for an output `name` that cannot be borrowed for writing.
pub fn write_error(name: &str, e: numpy::BorrowError) -> PyErr {
    match e {
        numpy::BorrowError::NotWriteable => PyValueError::new_err(format!("{name} is read-only")),
        _ => PyValueError::new_err(format!(
            "{name} shares memory with an input or another output: give a buffer of its own"
        )),
    }
}
