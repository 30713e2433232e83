//! The runs of a text: which parts of a [`Shape::Text`](super::Shape::Text)'s value are
//! drawn at the base size, which as subscripts (`R` + `A` of `RA`, `k` + `v` of `k_v`), and
//! which are written only where a writer draws the text flat.
//!
//! The value stays the text as one flat string: what the DXF writes (DXF text has no
//! subscripts: `RA`, `k_v`), what [`Shape::text`](super::Shape::text) returns and what a
//! search finds. The SVG, PNG and PDF writers draw a subscript run
//! [`SUB_SIZE`](super::font::SUB_SIZE) times the base size, its baseline lowered by
//! [`SUB_SHIFT_EM`](super::font::SUB_SHIFT_EM) base ems, and leave out a [`RunKind::Flat`]
//! run (the `_` of `k_v`); [`font::measure_runs`](super::font::measure_runs) measures the
//! text as they draw it.
//!
//! The figure states the runs: a name whose subscript starts at a known place
//! ([`Runs::subscript`]), or a text marked up TeX-like with `_` before each subscript
//! ([`Runs::underscored`]).

use std::ops::Range;

/// How a run of a text is drawn where the writer can draw subscripts (SVG, PNG, PDF).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RunKind {
    /// At the text's size, on its baseline.
    Base,
    /// A subscript: smaller and lowered.
    Sub,
    /// Written only in flat text (DXF): the `_` that marks a subscript there.
    Flat,
}

/// One run: the bytes of the value up to `end` (from the previous run's end) and how they
/// are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Run {
    /// Byte offset in the value where this run ends.
    pub end: usize,
    /// How the run is drawn.
    pub kind: RunKind,
}

/// The runs of a text, in order; no runs (the default) draws the whole value at the base
/// size. Bytes after the last run are drawn at the base size too.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct Runs(pub Vec<Run>);

impl Runs {
    /// The whole value at the base size.
    pub fn flat() -> Runs {
        Runs(Vec::new())
    }

    /// Whether every byte is drawn at the base size (the writers write a plain text).
    pub fn is_flat(&self) -> bool {
        self.0.iter().all(|r| r.kind == RunKind::Base)
    }

    /// The bytes `sub` of a value drawn as a subscript, the rest at the base size (on
    /// character boundaries: `Runs::subscript(1..2)` for `RA`; empty: flat).
    pub fn subscript(sub: Range<usize>) -> Runs {
        if sub.is_empty() {
            return Runs::flat();
        }
        Runs(vec![Run { end: sub.start, kind: RunKind::Base }, Run { end: sub.end, kind: RunKind::Sub }])
    }

    /// The runs of a text marked up TeX-like: each `_` followed by a letter or digit starts a
    /// subscript made of the letters and digits that follow it (`k_v = 0.1 (m/s)/mm`: `v`;
    /// `M_p(F_i)`: `p` and `i`); the `_` itself is written only in flat text (the DXF keeps
    /// `k_v`). A text without such a `_` is flat.
    pub fn underscored(value: &str) -> Runs {
        let mut runs = Vec::new();
        let mut chars = value.char_indices().peekable();
        while let Some((i, c)) = chars.next() {
            if c != '_' || !chars.peek().is_some_and(|(_, n)| n.is_alphanumeric()) {
                continue;
            }
            runs.push(Run { end: i, kind: RunKind::Base });
            runs.push(Run { end: i + 1, kind: RunKind::Flat });
            let mut end = i + 1;
            while let Some(&(j, n)) = chars.peek() {
                if !n.is_alphanumeric() {
                    break;
                }
                end = j + n.len_utf8();
                chars.next();
            }
            runs.push(Run { end, kind: RunKind::Sub });
        }
        Runs(runs)
    }

    /// A text marked up as for [`Runs::underscored`] (`φ_1 = 90°`, `m_21 bar AB`) as the flat
    /// text without its marks (`φ1 = 90°`, `m21 bar AB`) and the runs that draw each marked
    /// part as a subscript: for a text whose flat form must read as written where no
    /// subscript is drawn (a DXF that stays `φ1`, a PDF's searchable text), where
    /// [`Runs::underscored`] keeps the `_` in the flat text (the DXF's `k_v`). A `_` not
    /// followed by a letter or digit stays as written.
    pub fn unmarked(markup: &str) -> (String, Runs) {
        let mut text = String::with_capacity(markup.len());
        let mut runs = Vec::new();
        for (part, kind) in Runs::underscored(markup).split(markup) {
            match kind {
                RunKind::Flat => continue,
                RunKind::Base => text.push_str(part),
                RunKind::Sub => {
                    runs.push(Run { end: text.len(), kind: RunKind::Base });
                    text.push_str(part);
                    runs.push(Run { end: text.len(), kind: RunKind::Sub });
                }
            }
        }
        (text, Runs(runs))
    }

    /// The runs of `value` as (text, kind), empty runs left out; the whole value as one base
    /// run when there are none. A run end past the value or off a character boundary ends
    /// the runs there (the rest at the base size).
    pub fn split<'a>(&'a self, value: &'a str) -> impl Iterator<Item = (&'a str, RunKind)> + 'a {
        let mut parts = Vec::with_capacity(self.0.len() + 1);
        let mut start = 0;
        for r in &self.0 {
            let Some(part) = value.get(start..r.end) else { break };
            parts.push((part, r.kind));
            start = r.end;
        }
        parts.push((&value[start..], RunKind::Base));
        parts.into_iter().filter(|(s, _)| !s.is_empty())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(value: &str, runs: &Runs) -> Vec<(String, RunKind)> {
        runs.split(value).map(|(s, k)| (s.to_string(), k)).collect()
    }

    #[test]
    fn a_name_splits_at_its_subscript() {
        use RunKind::*;
        assert_eq!(parts("RA", &Runs::subscript(1..2)), [("R".into(), Base), ("A".into(), Sub)]);
        assert_eq!(parts("RA", &Runs::flat()), [("RA".into(), Base)]);
        // φ is two bytes: the subscript starts after it.
        assert_eq!(
            parts("φ1 = 90°", &Runs::subscript("φ".len().."φ1".len())),
            [("φ".into(), Base), ("1".into(), Sub), (" = 90°".into(), Base)]
        );
        // A run off a character boundary ends the runs: the rest is base text, never lost.
        assert_eq!(parts("φ1", &Runs::subscript(1..3)), [("φ1".into(), Base)]);
    }

    #[test]
    fn underscores_mark_subscripts_written_flat_in_dxf() {
        use RunKind::*;
        let v = "k_v = 0.1 (m/s)/mm";
        assert_eq!(
            parts(v, &Runs::underscored(v)),
            [("k".into(), Base), ("_".into(), Flat), ("v".into(), Sub), (" = 0.1 (m/s)/mm".into(), Base)]
        );
        let v = "M_p(F_i)";
        let p = parts(v, &Runs::underscored(v));
        let subs: Vec<&str> = p.iter().filter(|(_, k)| *k == Sub).map(|(s, _)| s.as_str()).collect();
        assert_eq!(subs, ["p", "i"]);
        assert!(Runs::underscored("a_ b_").is_flat() && Runs::underscored("plain").0.is_empty());
    }

    #[test]
    fn unmarked_text_reads_without_its_marks() {
        use RunKind::*;
        let (text, runs) = Runs::unmarked("φ_1 = 90°, φ_2 = 12°");
        assert_eq!(text, "φ1 = 90°, φ2 = 12°");
        assert_eq!(
            parts(&text, &runs),
            [
                ("φ".into(), Base),
                ("1".into(), Sub),
                (" = 90°, φ".into(), Base),
                ("2".into(), Sub),
                (" = 12°".into(), Base)
            ]
        );
        // A subscript at the end; a `_` that marks nothing stays; no mark: flat.
        let (text, runs) = Runs::unmarked("m_21");
        assert_eq!((text.as_str(), parts(&text, &runs)), ("m21", vec![("m".into(), Base), ("21".into(), Sub)]));
        let (text, runs) = Runs::unmarked("a_ b");
        assert_eq!(text, "a_ b");
        assert!(runs.is_flat());
    }
}
