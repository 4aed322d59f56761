//! Text matrices: one sample a line, numbers separated by commas,
//! semicolons, tabs or spaces (as `dlmwrite`, `savetxt`, `writematrix` and
//! loggers write them). Blank lines and lines starting with `#` or `%` are
//! skipped; a first line that is not all numbers is taken as a header and
//! skipped with a warning.

use super::error::ImportError;
use super::table::Table;

/// Splits a line into its cells.
fn cells(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|c| !c.is_empty())
}

/// Reads `text` (from `file`) as a matrix; `warnings` gets what was skipped.
pub(crate) fn parse(
    text: &str,
    file: &str,
    warnings: &mut Vec<String>,
) -> Result<Table, ImportError> {
    let mut table = Table {
        source: file.to_string(),
        rows: 0,
        cols: 0,
        values: Vec::new(),
        lines: Vec::new(),
    };
    let mut header_checked = false;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let trimmed = raw.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') || trimmed.starts_with('%') {
            continue;
        }
        if !header_checked {
            header_checked = true;
            if cells(trimmed).all(|c| c.parse::<f64>().is_err()) {
                warnings.push(format!("{file}:{line}: header line skipped"));
                continue;
            }
        }
        let start = table.values.len();
        for (c, cell) in cells(trimmed).enumerate() {
            let value = cell
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| ImportError::BadNumber {
                    file: file.to_string(),
                    line,
                    column: c + 1,
                    value: cell.to_string(),
                })?;
            table.values.push(value);
        }
        let found = table.values.len() - start;
        if table.rows == 0 {
            table.cols = found;
        } else if found != table.cols {
            return Err(ImportError::Ragged {
                file: file.to_string(),
                line,
                found,
                expected: table.cols,
            });
        }
        table.rows += 1;
        table.lines.push(line);
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separators_comments_and_header() {
        let mut w = Vec::new();
        let t = parse(
            "time q1 q2\n% matlab comment\n0, 1.5 ,2\n\n1;2\t3e-1\n",
            "m.txt",
            &mut w,
        )
        .unwrap();
        assert_eq!((t.rows, t.cols), (2, 3));
        assert_eq!(t.values, vec![0.0, 1.5, 2.0, 1.0, 2.0, 0.3]);
        assert_eq!(t.lines, vec![3, 5]);
        assert_eq!(w, vec!["m.txt:1: header line skipped".to_string()]);
    }

    #[test]
    fn bad_cells_and_ragged_rows_are_named() {
        let mut w = Vec::new();
        let e = parse("1 2\n3 x\n", "m.txt", &mut w).unwrap_err();
        assert_eq!(
            e.to_string(),
            "m.txt:2: column 2: `x` is not a finite number"
        );
        let e = parse("1 2\n3 4 5\n", "m.txt", &mut w).unwrap_err();
        assert_eq!(e.to_string(), "m.txt:2: 3 columns, the first row has 2");
        let e = parse("1 2\n3 inf\n", "m.txt", &mut w).unwrap_err();
        assert!(
            e.to_string().contains("`inf` is not a finite number"),
            "{e}"
        );
    }
}
