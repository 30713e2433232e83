//! JSON files compared leaf by leaf. A leaf's key path with its array indices dropped
//! (`positions[].B[0]` for `positions[37].B[0]`) is its column: two numbers within the
//! relative tolerance of that column's scale (its largest magnitude) are the same; strings,
//! booleans and nulls must be equal; keys and array lengths must match.

use std::collections::BTreeMap;

use serde_json::Value;

use super::{DiffError, FileDiff, Pair, Spread, Verdict};

/// What the walk found.
#[derive(Default)]
struct Walk {
    /// Number leaves by column.
    columns: BTreeMap<String, Spread>,
    /// Other differences (structure, text), each with its path.
    other: Vec<String>,
}

pub(super) fn compare(pair: &Pair<'_>, old: &str, new: &str) -> Result<FileDiff, DiffError> {
    let parse = |which: &std::path::Path, text: &str| -> Result<Value, DiffError> {
        serde_json::from_str(text).map_err(|e| pair.format_error(which, "JSON", e.to_string()))
    };
    let (a, b) = (parse(pair.old, old)?, parse(pair.new, new)?);
    let mut walk = Walk::default();
    visit(&a, &b, "", &mut walk);
    let mut details = Vec::new();
    let moved: Vec<(&String, &Spread, usize)> = walk
        .columns
        .iter()
        .filter_map(|(k, s)| {
            let (n, _) = s.beyond(pair.tol_rel);
            (n > 0).then_some((k, s, n))
        })
        .collect();
    if !moved.is_empty() {
        details.push(format!("{} key paths moved beyond {:e}:", moved.len(), pair.tol_rel));
        for (k, s, n) in moved.iter().take(12) {
            details.push(format!("  {k}: {n} values; {}", s.describe()));
        }
        if moved.len() > 12 {
            details.push(format!("  … and {} more", moved.len() - 12));
        }
    }
    let others = walk.other.len();
    details.extend(walk.other.into_iter().take(8).map(|o| format!("  {o}")));
    if others > 8 {
        details.push(format!("  … and {} more differences", others - 8));
    }
    let verdict = if moved.is_empty() && others == 0 { Verdict::Within } else { Verdict::Changed };
    if verdict == Verdict::Within {
        details.push(format!("every value within {:e} (bytes differ)", pair.tol_rel));
    }
    Ok(FileDiff::new(pair.rel, verdict, details))
}

/// `positions[37].B[0]` → `positions[].B[0]`: a final index 0, 1 or 2 is kept (the x, y or z
/// of a point), every other index dropped.
fn column(path: &str) -> String {
    let last = path.rfind('[').filter(|&i| matches!(&path[i..], "[0]" | "[1]" | "[2]"));
    let mut out = String::with_capacity(path.len());
    let mut skip = false;
    for (i, ch) in path.char_indices() {
        match ch {
            '[' if Some(i) != last => {
                out.push_str("[]");
                skip = true;
            }
            ']' if skip => skip = false,
            _ if skip => {}
            _ => out.push(ch),
        }
    }
    out
}

fn visit(a: &Value, b: &Value, path: &str, walk: &mut Walk) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            walk.columns.entry(column(path)).or_default().add(x, y, || path.to_string());
        }
        (Value::Object(x), Value::Object(y)) => {
            for (k, va) in x {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                match y.get(k) {
                    Some(vb) => visit(va, vb, &p, walk),
                    None => walk.other.push(format!("{p}: removed")),
                }
            }
            for k in y.keys().filter(|k| !x.contains_key(*k)) {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                walk.other.push(format!("{p}: added"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            if x.len() != y.len() {
                walk.other.push(format!("{path}: {} items → {}", x.len(), y.len()));
            }
            for (i, (va, vb)) in x.iter().zip(y).enumerate() {
                visit(va, vb, &format!("{path}[{i}]"), walk);
            }
        }
        _ if a != b => walk.other.push(format!("{path}: {} → {}", brief(a), brief(b))),
        _ => {}
    }
}

/// A value in at most ~60 characters.
fn brief(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 60 { format!("{}…", s.chars().take(60).collect::<String>()) } else { s }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diff(old: &str, new: &str, tol: f64) -> FileDiff {
        let p = std::path::Path::new("x.json");
        compare(&Pair { rel: "x.json", old: p, new: p, tol_rel: tol }, old, new).unwrap()
    }

    #[test]
    fn a_key_path_without_its_record_index_is_a_column() {
        assert_eq!(column("positions[37].B[0]"), "positions[].B[0]");
        assert_eq!(column("gamma_min_deg"), "gamma_min_deg");
        assert_eq!(column("a[1][2]"), "a[][2]");
        assert_eq!(column("histogram[17]"), "histogram[]");
    }

    #[test]
    fn numbers_move_by_column_and_structure_is_reported() {
        let old = r#"{"positions": [{"B": [0.1, 0.2]}, {"B": [0.3, 0.4]}], "name": "x"}"#;
        let new = r#"{"positions": [{"B": [0.1, 0.2]}, {"B": [0.3001, 0.4]}], "name": "x"}"#;
        let d = diff(old, new, 1e-9);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details[1].contains("positions[].B[0]: 1 values"), "{:?}", d.details);
        assert!(d.details[1].contains("at positions[1].B[0]"), "{:?}", d.details);
        assert_eq!(diff(old, new, 1e-3).verdict, Verdict::Within);
        let d = diff(r#"{"a": 1, "b": "x"}"#, r#"{"a": 1, "b": "y", "c": []}"#, 1.0);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details.iter().any(|l| l.contains("b: \"x\" → \"y\"")), "{:?}", d.details);
        assert!(d.details.iter().any(|l| l.contains("c: added")), "{:?}", d.details);
    }
}
