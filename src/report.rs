//! JSON summary and CSV: the public data interfaces (documented in README). Shared
//! helpers; each kind's pipeline builds its own records.

use crate::geom::{Point, Vector};

/// A point or vector as the JSON pair `[x, y]`.
pub fn pair(x: f64, y: f64) -> serde_json::Value {
    serde_json::json!([x, y])
}

/// A point as `[x, y]`.
pub fn point(p: Point) -> serde_json::Value {
    pair(p.x, p.y)
}

/// A vector as `[x, y]`.
pub fn vector(v: Vector) -> serde_json::Value {
    pair(v.x, v.y)
}

/// A CSV table built in memory: a header and rows of numbers or text.
#[derive(Debug, Clone, Default)]
pub struct Csv {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Csv {
    /// A table with these column names.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Csv {
        Csv { header: header.into_iter().map(Into::into).collect(), rows: Vec::new() }
    }

    /// Appends a row of numbers, written with full precision (shortest round-trip form).
    pub fn row(&mut self, values: impl IntoIterator<Item = f64>) {
        self.rows.push(values.into_iter().map(|v| format!("{v}")).collect());
    }

    /// Appends a row of already formatted fields.
    pub fn row_text<S: Into<String>>(&mut self, fields: impl IntoIterator<Item = S>) {
        self.rows.push(fields.into_iter().map(Into::into).collect());
    }

    /// Appends a column `name` with one number per row (full precision, as [`Csv::row`]);
    /// rows beyond `values` get an empty field.
    pub fn column(&mut self, name: impl Into<String>, values: &[f64]) {
        self.header.push(name.into());
        for (i, r) in self.rows.iter_mut().enumerate() {
            r.push(values.get(i).map_or(String::new(), |v| format!("{v}")));
        }
    }

    /// The table as CSV text (RFC 4180 quoting, `\n` line ends).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
        // Writing into a Vec cannot fail; a failure here would be a bug in csv.
        w.write_record(&self.header).expect("in-memory CSV write");
        for r in &self.rows {
            w.write_record(r).expect("in-memory CSV write");
        }
        w.into_inner().expect("in-memory CSV flush")
    }
}
