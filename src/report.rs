//! JSON summary and CSV: the public data interfaces (documented in docs/scene-files.md and
//! each kind's page). Shared helpers; each kind's pipeline builds its own records.

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

/// `v` written exactly as `format!("{v}")` writes it — the shortest decimal that reads back
/// as `v`, never in exponent form (`0.0000001`, `1e21` as `1000000000000000000000`), `-0`
/// for negative zero, `NaN`, `inf`, `-inf` — with the digits found by `ryu` (the same
/// shortest round-trip digits, about ten times faster than the standard library's search).
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let mut buffer = ryu::Buffer::new();
    let text = buffer.format_finite(v);
    if may_tie(v, text) {
        // Halfway between two shortest candidates: ryu takes the even one, `{}` the upper.
        return format!("{v}");
    }
    if !text.contains('e') {
        // ryu's `int.frac` is `{}`'s form but for a whole number's `.0`.
        return text.strip_suffix(".0").unwrap_or(text).to_string();
    }
    // `[-]d[.ddd]e[-]x`: the digits, and where the decimal point goes.
    let (mantissa, exponent) = text.split_once('e').unwrap_or((text, "0"));
    let exponent = exponent.parse::<i32>().unwrap_or(0);
    let (negative, mantissa) = match mantissa.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, mantissa),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits: String = int.chars().chain(frac.chars()).collect();
    let digits = digits.trim_end_matches('0');
    // ryu's mantissa has one digit before the point: the point goes after 1 + exponent digits.
    let point = 1 + exponent;
    let mut out = String::with_capacity(digits.len() + point.unsigned_abs() as usize + 3);
    if negative {
        out.push('-');
    }
    if point <= 0 {
        out.push_str("0.");
        out.extend(std::iter::repeat_n('0', point.unsigned_abs() as usize));
        out.push_str(digits);
    } else if point as usize >= digits.len() {
        out.push_str(digits);
        out.extend(std::iter::repeat_n('0', point as usize - digits.len()));
    } else {
        let (whole, part) = digits.split_at(point as usize);
        out.push_str(whole);
        out.push('.');
        out.push_str(part);
    }
    out
}

/// Whether `v`'s shortest digits (`text`, as ryu wrote them) may be one of two candidates
/// equally near `v`, where ryu and `{}` break the tie differently. A tie at n digits needs
/// `v`'s exact decimal expansion to have n + 1 ≤ 18 significant digits (ending in 5) and
/// more than ryu wrote: a dyadic fraction m / 2^j (m odd) has the expansion's significant
/// digits of m·5^j; an integer below 2^53 is written exactly.
fn may_tie(v: f64, text: &str) -> bool {
    let bits = v.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1 << 52) - 1);
    let (m, e) = if biased == 0 { (fraction, -1074) } else { (fraction | (1 << 52), biased - 1075) };
    if m == 0 {
        return false;
    }
    let zeros = m.trailing_zeros();
    let (m, e) = (m >> zeros, e + zeros as i32);
    if e >= 0 {
        return v.abs() >= 9_007_199_254_740_992.0;
    }
    let j = e.unsigned_abs();
    if j > 25 {
        // m·5^j ≥ 5^26 has 19 digits or more.
        return false;
    }
    let exact = u128::from(m) * 5u128.pow(j);
    let exact_digits = exact.ilog10() + 1;
    let mantissa = text.split_once('e').map_or(text, |(m, _)| m);
    let digits = mantissa.bytes().filter(u8::is_ascii_digit);
    let significant = digits.skip_while(|&d| d == b'0').collect::<Vec<_>>();
    let significant = significant.len() - significant.iter().rev().take_while(|&&d| d == b'0').count();
    exact_digits <= 18 && exact_digits as usize > significant
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
        self.rows.push(values.into_iter().map(number).collect());
    }

    /// Appends rows of numbers (as [`Csv::row`] each), formatted in parallel.
    pub fn rows(&mut self, rows: &[Vec<f64>]) {
        use crate::par::prelude::*;
        let formatted: Vec<Vec<String>> = rows.par_iter().map(|r| r.iter().copied().map(number).collect()).collect();
        self.rows.extend(formatted);
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
            r.push(values.get(i).map_or(String::new(), |v| number(*v)));
        }
    }

    /// Puts a column `name` of already formatted fields first, one per row (rows beyond
    /// `fields` get an empty field).
    pub fn prepend_column(&mut self, name: impl Into<String>, fields: &[String]) {
        self.header.insert(0, name.into());
        for (i, r) in self.rows.iter_mut().enumerate() {
            r.insert(0, fields.get(i).cloned().unwrap_or_default());
        }
    }

    /// Appends a column `name` with one value per row: a number, or an empty field where
    /// the value is `None` (a quantity the row does not have); rows beyond `values` get an
    /// empty field too.
    pub fn column_opt(&mut self, name: impl Into<String>, values: &[Option<f64>]) {
        self.header.push(name.into());
        for (i, r) in self.rows.iter_mut().enumerate() {
            r.push(values.get(i).copied().flatten().map_or(String::new(), number));
        }
    }

    /// The first field that writes a number that is not finite (`NaN`, `inf`:
    /// [`crate::text::non_finite_word`]), described for a message (row, column, field).
    pub fn first_non_finite(&self) -> Option<String> {
        self.rows.iter().enumerate().find_map(|(i, r)| {
            r.iter().enumerate().find(|(_, f)| crate::text::non_finite_word(f).is_some()).map(|(j, f)| {
                let column = self.header.get(j).map_or("?", String::as_str);
                format!("row {} column {column} is \"{}\"", i + 1, crate::text::excerpt(f))
            })
        })
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

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::number;

    /// A small deterministic generator (xorshift64*) for the comparison below.
    fn next(state: &mut u64) -> u64 {
        *state ^= *state >> 12;
        *state ^= *state << 25;
        *state ^= *state >> 27;
        state.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    #[test]
    fn numbers_are_what_format_writes() {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.5,
            1e-7,
            1.5e-7,
            123456789.0,
            1e15,
            1e16,
            1e21,
            1e22,
            1.2345e-300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            f64::EPSILON,
            std::f64::consts::PI,
            -273.15,
            f64::from_bits(0xc2b9_8624_db7b_6050), // -28063934675808.3125, a tie at 17 digits
            0.3125,
            2.5,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for v in special {
            assert_eq!(number(v), format!("{v}"), "{v:e}");
        }
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        for k in 0..200_000 {
            let r = next(&mut state);
            let v = match k % 5 {
                // Any bit pattern (finite or not).
                0 => f64::from_bits(r),
                // The CSV's kind of numbers: a few units to thousands, and small ones.
                1 => (r >> 11) as f64 / (1u64 << 53) as f64 * 2000.0 - 1000.0,
                2 => ((r >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 10f64.powi((r % 40) as i32 - 20),
                // Dyadic fractions with few fraction bits: ties between two shortest candidates.
                3 => (r >> 11) as f64 / f64::from(1u32 << (r % 13)),
                // Short decimals and integers, where exact values sit.
                _ => ((r % 2_000_001) as f64 - 1_000_000.0) / 10f64.powi((r >> 40) as i32 % 8),
            };
            assert_eq!(number(v), format!("{v}"), "{v:e} (bits {:#x})", v.to_bits());
        }
    }
}
