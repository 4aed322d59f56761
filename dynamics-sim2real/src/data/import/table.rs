//! A table of numbers as read from one source (a text file or an array of
//! a NumPy archive): `rows` x `cols`, row-major, with the place each row came
//! from so that errors can name it.

/// Numbers read from one source, row-major.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Table {
    /// Where the numbers came from (`file` or `file:array`).
    pub(crate) source: String,
    /// Number of rows.
    pub(crate) rows: usize,
    /// Number of columns.
    pub(crate) cols: usize,
    /// `rows * cols` values, row after row.
    pub(crate) values: Vec<f64>,
    /// The 1-based line of each row in a text file (empty for binary data).
    pub(crate) lines: Vec<usize>,
}

impl Table {
    /// The value at `row`, `col`.
    pub(crate) fn get(&self, row: usize, col: usize) -> f64 {
        self.values[row * self.cols + col]
    }

    /// Where row `row` is, for a message: `file:line` or `file row k`.
    pub(crate) fn place(&self, row: usize) -> String {
        match self.lines.get(row) {
            Some(line) => format!("{}:{line}", self.source),
            None => format!("{} row {}", self.source, row + 1),
        }
    }
}
