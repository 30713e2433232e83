//! CSV files compared cell by cell: the columns by header name, the rows in order; two
//! numbers within the relative tolerance of their column's scale (its largest magnitude)
//! are the same, any other cell must be equal as text. What moved is reported per column:
//! the largest difference, where (the row and its first cell, e.g. `phi1_deg = 37`), and
//! how many rows moved beyond the tolerance.

use super::{DiffError, FileDiff, Pair, Spread, Verdict};

/// Columns described one per line (largest difference, where); the rest are named only.
const LISTED_COLUMNS: usize = 8;

/// A parsed CSV: its header and rows.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

fn parse(pair: &Pair<'_>, which: &std::path::Path, text: &str) -> Result<Table, DiffError> {
    let mut reader = csv::ReaderBuilder::new().flexible(true).from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| pair.format_error(which, "CSV", e.to_string()))?
        .iter()
        .map(str::to_string)
        .collect();
    let rows = reader
        .records()
        .map(|r| r.map(|r| r.iter().map(str::to_string).collect()))
        .collect::<Result<Vec<Vec<String>>, _>>()
        .map_err(|e| pair.format_error(which, "CSV", e.to_string()))?;
    Ok(Table { header, rows })
}

/// One column's comparison.
#[derive(Default)]
struct Column {
    numbers: Spread,
    /// Cells that differ as text (not both numbers): count and the first, with its row.
    texts: usize,
    first_text: Option<String>,
}

pub(super) fn compare(pair: &Pair<'_>, old: &str, new: &str) -> Result<FileDiff, DiffError> {
    let (a, b) = (parse(pair, pair.old, old)?, parse(pair, pair.new, new)?);
    let mut details = Vec::new();
    let only = |x: &Table, y: &Table| -> Vec<String> {
        x.header.iter().filter(|h| !h.is_empty() && !y.header.contains(h)).cloned().collect()
    };
    let (removed, added) = (only(&a, &b), only(&b, &a));
    if !removed.is_empty() {
        details.push(format!("columns removed: {}", removed.join(", ")));
    }
    if !added.is_empty() {
        details.push(format!("columns added: {}", added.join(", ")));
    }
    if a.rows.len() != b.rows.len() {
        details.push(format!(
            "{} rows → {} rows (compared: the first {})",
            a.rows.len(),
            b.rows.len(),
            a.rows.len().min(b.rows.len())
        ));
    }
    let structural = !details.is_empty();
    let columns = compare_columns(&a, &b);
    let mut moved: Vec<(String, Column, usize)> = columns
        .into_iter()
        .filter_map(|(name, c)| {
            let (n, _) = c.numbers.beyond(pair.tol_rel);
            (n + c.texts > 0).then_some((name, c, n))
        })
        .collect();
    // Text changes first, then the numbers that moved most for their column's scale.
    let rel = |c: &Column| if c.numbers.scale > 0.0 { c.numbers.largest / c.numbers.scale } else { f64::INFINITY };
    moved.sort_by(|x, y| y.1.texts.cmp(&x.1.texts).then(rel(&y.1).total_cmp(&rel(&x.1))).then(x.0.cmp(&y.0)));
    let rows = a.rows.len().min(b.rows.len());
    if !moved.is_empty() {
        let names: Vec<&str> = moved.iter().map(|(n, ..)| n.as_str()).collect();
        details.push(format!(
            "{} of {} columns moved beyond {:e}: {}",
            moved.len(),
            b.header.len(),
            pair.tol_rel,
            names.join(", ")
        ));
    }
    if moved.len() > LISTED_COLUMNS {
        details.push(format!("the {LISTED_COLUMNS} that moved most for their column's scale:"));
    }
    for (name, c, n) in moved.iter().take(LISTED_COLUMNS) {
        if *n > 0 {
            details.push(format!("  {name}: {} rows of {rows}; {}", n, c.numbers.describe()));
        }
        if let Some(t) = &c.first_text {
            details.push(format!("  {name}: {} cells differ as text, first {t}", c.texts));
        }
    }
    let verdict = if structural || !moved.is_empty() { Verdict::Changed } else { Verdict::Within };
    if verdict == Verdict::Within {
        details.push(format!("every cell within {:e} (bytes differ)", pair.tol_rel));
    }
    Ok(FileDiff::new(pair.rel, verdict, details))
}

/// Every column present in both, by header name, compared over the rows both have.
fn compare_columns(a: &Table, b: &Table) -> Vec<(String, Column)> {
    let key = &a.header.first().cloned().unwrap_or_default();
    let mut out = Vec::new();
    for (ia, name) in a.header.iter().enumerate() {
        let Some(ib) = b.header.iter().position(|h| h == name) else { continue };
        let mut col = Column::default();
        for (r, (ra, rb)) in a.rows.iter().zip(&b.rows).enumerate() {
            let (ca, cb) = (ra.get(ia).map_or("", String::as_str), rb.get(ib).map_or("", String::as_str));
            let at = || {
                let first = ra.first().map_or("", String::as_str);
                format!("row {} ({key} = {first})", r + 1)
            };
            match (number(ca), number(cb)) {
                (Some(x), Some(y)) => col.numbers.add(x, y, at),
                _ if ca != cb => {
                    col.texts += 1;
                    if col.first_text.is_none() {
                        col.first_text = Some(format!("{:?} → {:?} at {}", ca, cb, at()));
                    }
                }
                _ => {}
            }
        }
        out.push((name.clone(), col));
    }
    out
}

/// A cell as a number, when it is one.
fn number(cell: &str) -> Option<f64> {
    let t = cell.trim();
    if t.is_empty() {
        return None;
    }
    t.parse::<f64>().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diff(old: &str, new: &str, tol: f64) -> FileDiff {
        let p = std::path::Path::new("x.csv");
        let pair = Pair { rel: "x.csv", old: p, new: p, tol_rel: tol };
        compare(&pair, old, new).unwrap()
    }

    #[test]
    fn moved_columns_are_named_with_their_largest_difference_and_row() {
        let old = "phi1_deg,B_x,name\n0,0.1,a\n10,0.2,b\n20,0.3,c\n";
        let new = "phi1_deg,B_x,name\n0,0.1,a\n10,0.2002,b\n20,0.3001,c\n";
        let d = diff(old, new, 1e-9);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details[0].starts_with("1 of 3 columns moved beyond 1e-9: B_x"), "{:?}", d.details);
        assert!(d.details[1].contains("B_x: 2 rows of 3"), "{:?}", d.details);
        assert!(d.details[1].contains("at row 2 (phi1_deg = 10)"), "{:?}", d.details);
        // 2e-4 of a column whose scale is 0.3: within 1e-3, not within 1e-4.
        assert_eq!(diff(old, new, 1e-3).verdict, Verdict::Within);
        assert_eq!(diff(old, new, 1e-4).verdict, Verdict::Changed);
    }

    #[test]
    fn texts_columns_and_rows_are_structure() {
        let d = diff("a,b\n1,x\n", "a,b\n1,y\n", 1.0);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details.iter().any(|l| l.contains("\"x\" → \"y\" at row 1 (a = 1)")), "{:?}", d.details);
        let d = diff("a,b\n1,2\n", "a,c\n1,2\n", 1.0);
        assert_eq!(d.details[..2], ["columns removed: b".to_string(), "columns added: c".to_string()]);
        let d = diff("a\n1\n2\n", "a\n1\n", 1.0);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details[0].starts_with("2 rows → 1 rows"), "{:?}", d.details);
    }

    #[test]
    fn last_digits_are_within_the_default_tolerance() {
        let d = diff("x\n0.1\n0.30000000000000004\n", "x\n0.1\n0.3\n", super::super::DEFAULT_TOL_REL);
        assert_eq!(d.verdict, Verdict::Within);
    }
}
