//! The metrics of DejaVu Sans, the font every SVG, PNG and PDF we write draws its text in
//! (the PNG and PDF writers bundle it: assets/fonts), for the characters a drawing writes:
//! each character's advance and the vertical extent of its glyph, in font units, read from
//! the font file once into [`font_table`](self) (a test checks the table against the font).
//! A text's box ([`measure`]) is what a figure's letter placer keeps clear and what the
//! overlap tests check, so that both measure the text as the reader draws it. The table
//! lets the live page's module (built without the font: docs/web.md) measure alike.
//!
//! Sizes: a text's `height` is its cap height (the writers set the font size to
//! `height / CAP_HEIGHT_EM`), so widths, ascents and descents come out in the units of the
//! height. The writers do not kern (the PDF places glyphs by their advances; an SVG reader
//! may kern DejaVu's few kerned pairs, which only narrows a text), so a text's width is the
//! sum of its advances.

#[path = "font_table.rs"]
mod font_table;

use font_table::{GLYPHS, NOTDEF, UNITS_PER_EM};

/// Cap height of DejaVu Sans, in ems (1493 of 2048 font units): the SVG writer sets the
/// font size to the text height / 0.73, so a text height is a cap height.
pub const CAP_HEIGHT_EM: f64 = 0.73;

/// How far round letters overshoot the baseline and the cap height (`o`, `a`, `O`: 0.01–0.015
/// em in DejaVu Sans), in ems: a text whose glyphs stay within this of the line counts as
/// standing on the baseline and ending at the cap height.
pub const OVERSHOOT_EM: f64 = 0.02;

/// A subscript's size, as a fraction of its text's size (font size and cap height alike):
/// `A` of `RA` is drawn 0.7 times as high as `R`.
pub const SUB_SIZE: f64 = 0.7;

/// How far a subscript's baseline lies below its text's, in ems of the text's (base) font
/// size: 0.25 em, about a third of the cap height (0.25 / 0.73), so the subscript's capitals
/// reach 0.26 em above the base baseline and its bottom 0.25 em below it.
pub const SUB_SHIFT_EM: f64 = 0.25;

/// One character's metrics, in ems: its advance, and the lowest and highest points of its
/// glyph (y up from the baseline; both 0 for a space).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Glyph {
    /// Advance width, ems.
    pub advance: f64,
    /// Lowest point of the outline, ems (negative below the baseline: `p`, `φ`, `(`).
    pub y_min: f64,
    /// Highest point of the outline, ems.
    pub y_max: f64,
}

/// The metrics of `c` in DejaVu Sans (the `.notdef` box for a character the table lacks:
/// what a reader draws for a character the font lacks).
pub fn glyph(c: char) -> Glyph {
    let (advance, y_min, y_max) = match GLYPHS.binary_search_by_key(&(c as u32), |g| g.0) {
        Ok(i) => (GLYPHS[i].1, GLYPHS[i].2, GLYPHS[i].3),
        Err(_) => NOTDEF,
    };
    let em = f64::from(UNITS_PER_EM);
    Glyph { advance: f64::from(advance) / em, y_min: f64::from(y_min) / em, y_max: f64::from(y_max) / em }
}

/// The extent of a text drawn `height` high (cap height), model units: its width (the sum of
/// its advances), and how far its glyphs reach above and below the baseline — at least the
/// cap height above, at least nothing below (round letters' overshoot, [`OVERSHOOT_EM`],
/// aside).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextExtent {
    /// Width, from the text's start to the end of its last advance.
    pub width: f64,
    /// Height above the baseline: the highest glyph, at least the cap height.
    pub ascent: f64,
    /// Depth below the baseline (≥ 0): the lowest descender (`p`, `φ`, `,`), 0 without.
    pub descent: f64,
}

/// The extent of `text` drawn `height` high (cap height) in DejaVu Sans.
pub fn measure(text: &str, height: f64) -> TextExtent {
    measure_chars(text.chars(), height)
}

/// [`measure`] of the text made of `chars`.
pub fn measure_chars(chars: impl Iterator<Item = char>, height: f64) -> TextExtent {
    let (mut advance, mut low, mut high) = (0.0, 0.0f64, CAP_HEIGHT_EM);
    for c in chars {
        let g = glyph(c);
        advance += g.advance;
        if g.y_max > g.y_min {
            low = low.min(g.y_min);
            high = high.max(g.y_max);
        }
    }
    extent(advance, low, high, height)
}

/// The extent of `value` drawn `height` high (cap height) in its `runs`, as the SVG, PNG and
/// PDF writers draw it: base runs at `height`, subscript runs [`SUB_SIZE`] × `height` on a
/// baseline [`SUB_SHIFT_EM`] ems lower (their advances scaled alike, their descent below the
/// text's baseline counted from the lowered baseline: `RA` reaches 0.25 em below the
/// baseline, `Ry` 0.25 em + 0.7 × the descender of `y`), flat-only runs left out. The
/// width is the sum of the drawn advances; ascent and descent are at least the cap height
/// and nothing, as in [`measure`].
pub fn measure_runs(value: &str, runs: &super::Runs, height: f64) -> TextExtent {
    use super::RunKind;
    let (mut advance, mut low, mut high) = (0.0, 0.0f64, CAP_HEIGHT_EM);
    for (part, kind) in runs.split(value) {
        let (scale, rise) = match kind {
            RunKind::Base => (1.0, 0.0),
            RunKind::Sub => (SUB_SIZE, -SUB_SHIFT_EM),
            RunKind::Flat => continue,
        };
        for c in part.chars() {
            let g = glyph(c);
            advance += scale * g.advance;
            if kind == RunKind::Sub {
                // A lowered run reaches below the baseline even without a descender.
                low = low.min(rise + scale * g.y_min.min(0.0));
                high = high.max(rise + scale * g.y_max);
            } else if g.y_max > g.y_min {
                low = low.min(g.y_min);
                high = high.max(g.y_max);
            }
        }
    }
    extent(advance, low, high, height)
}

/// The extent of a text `height` high whose advances sum to `advance` and whose glyphs
/// reach from `low` to `high` (ems, y up): round letters' overshoot of the baseline and the
/// cap height ([`OVERSHOOT_EM`]) counts as standing on them.
fn extent(advance: f64, low: f64, high: f64, height: f64) -> TextExtent {
    let em = height / CAP_HEIGHT_EM;
    let low = if low > -OVERSHOOT_EM { 0.0 } else { low };
    let high = if high < CAP_HEIGHT_EM + OVERSHOOT_EM { CAP_HEIGHT_EM } else { high };
    TextExtent { width: advance * em, ascent: high * em, descent: -low * em }
}

/// Width (model units) of `text` drawn `height` high: the sum of its DejaVu Sans advances.
pub fn width(text: &str, height: f64) -> f64 {
    measure(text, height).width
}

/// The characters the table holds: Basic Latin, Latin-1, Greek, general punctuation (′ ″ –
/// — …), super- and subscripts, arrows, mathematical operators (− ≡ ≈ ≤ √ ∠ …).
pub const TABLE_RANGES: [(u32, u32); 7] = [
    (0x20, 0x7E),
    (0xA0, 0xFF),
    (0x370, 0x3FF),
    (0x2000, 0x206F),
    (0x2070, 0x209F),
    (0x2190, 0x21FF),
    (0x2200, 0x22FF),
];

/// The table's text, written from the font: every character of [`TABLE_RANGES`] the font
/// maps, with its advance and its glyph's lowest and highest points (font units), and
/// `.notdef`'s.
#[cfg(all(test, feature = "pdf"))]
fn table_from_font() -> String {
    use skrifa::MetadataProvider;
    use skrifa::instance::{LocationRef, Size};
    let font = skrifa::FontRef::new(super::FONT).expect("the bundled font reads");
    let upem = font.metrics(Size::unscaled(), LocationRef::default()).units_per_em;
    let gm = font.glyph_metrics(Size::unscaled(), LocationRef::default());
    let charmap = font.charmap();
    let entry = |gid: skrifa::GlyphId| {
        let adv = gm.advance_width(gid).unwrap_or(0.0).round() as i16;
        let (lo, hi) = gm.bounds(gid).map_or((0, 0), |b| (b.y_min.round() as i16, b.y_max.round() as i16));
        (adv, lo, hi)
    };
    let mut out = String::from(
        "//! DejaVu Sans's metrics for the characters a drawing writes (font units): generated from\n\
         //! assets/fonts/DejaVuSans.ttf by `UPDATE_FONT_TABLE=1 cargo test --lib font`; a test\n\
         //! checks it against the font.\n\n",
    );
    out.push_str(&format!("/// Font units per em.\npub const UNITS_PER_EM: u16 = {upem};\n\n"));
    let (a, lo, hi) = entry(skrifa::GlyphId::NOTDEF);
    out.push_str(&format!(
        "/// `.notdef`: advance, lowest and highest point.\npub const NOTDEF: (i16, i16, i16) = ({a}, {lo}, {hi});\n\n"
    ));
    out.push_str("/// (character, advance, lowest point, highest point), sorted by character.\n");
    out.push_str("#[rustfmt::skip]\npub const GLYPHS: &[(u32, i16, i16, i16)] = &[\n");
    for (from, to) in TABLE_RANGES {
        for code in from..=to {
            let Some(c) = char::from_u32(code) else { continue };
            let Some(gid) = charmap.map(c) else { continue };
            let (a, lo, hi) = entry(gid);
            out.push_str(&format!("    (0x{code:04X}, {a}, {lo}, {hi}),\n"));
        }
    }
    out.push_str("];\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(feature = "pdf")]
    #[test]
    fn the_table_is_the_fonts() {
        let fresh = table_from_font();
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/draw/font_table.rs");
        if std::env::var_os("UPDATE_FONT_TABLE").is_some_and(|v| v == "1") {
            std::fs::write(path, &fresh).unwrap();
        }
        let committed = std::fs::read_to_string(path).unwrap();
        assert!(
            committed == fresh,
            "src/draw/font_table.rs differs from the font: UPDATE_FONT_TABLE=1 cargo test --lib font"
        );
    }

    #[test]
    fn advances_and_extents_are_the_fonts_own() {
        // DejaVu Sans (2048 units per em): digits 1303, `m` 1995, `i` 569, U+2212 minus
        // 1716, `A` 1401.
        for (c, units) in [('0', 1303.0), ('9', 1303.0), ('m', 1995.0), ('i', 569.0), ('−', 1716.0), ('A', 1401.0)] {
            assert!((glyph(c).advance - units / 2048.0).abs() < 1e-9, "{c}: {:?}", glyph(c));
        }
        // Descenders reach below the baseline, capitals to the cap height.
        assert!(glyph('p').y_min < -0.2 && glyph('φ').y_min < -0.2 && glyph('a').y_min > -0.02);
        assert!((glyph('H').y_max - CAP_HEIGHT_EM).abs() < 0.002);
        // A space has no ink; ≡, ′ and the subscripts are in the table.
        assert_eq!((glyph(' ').y_min, glyph(' ').y_max), (0.0, 0.0));
        for c in ['≡', '′', '₀', '²', 'π', 'ω', '→'] {
            assert!(GLYPHS.binary_search_by_key(&(c as u32), |g| g.0).is_ok(), "{c}");
        }
    }

    #[test]
    fn a_texts_extent_is_its_advances_and_its_deepest_and_highest_glyph() {
        let h = 3.5;
        let em = h / CAP_HEIGHT_EM;
        let e = measure("mp", h);
        assert!((e.width - (1995.0 + 1300.0) / 2048.0 * em).abs() < 0.01 * em, "{e:?}");
        assert!((e.descent + glyph('p').y_min * em).abs() < 1e-12);
        assert!((e.ascent - h).abs() < 0.01 * h, "{e:?}");
        // No descender: nothing below the baseline (`a` overshoots it by 0.01 em); `b` reaches
        // a little above the capitals.
        let e = measure("ab", h);
        assert!(e.descent == 0.0 && e.ascent > 1.03 * h, "{e:?}");
        assert!((measure("ao", h).ascent - h).abs() < 1e-12);
        assert_eq!(measure("", h).width, 0.0);
        // A character the table lacks takes the .notdef box, never nothing.
        assert!(glyph('\u{10FFFD}').advance > 0.3);
    }

    #[test]
    fn a_subscript_is_measured_smaller_and_lowered() {
        use crate::draw::Runs;
        let h = 3.5;
        let em = h / CAP_HEIGHT_EM;
        // RA with A a subscript: advance of R plus 0.7 × the advance of A (DejaVu Sans:
        // R 1423, A 1401 of 2048 units per em).
        let e = measure_runs("RA", &Runs::subscript(1..2), h);
        assert!((e.width - (1423.0 + 0.7 * 1401.0) / 2048.0 * em).abs() < 1e-12, "{e:?}");
        assert!((e.width - (width("R", h) + SUB_SIZE * width("A", h))).abs() < 1e-12);
        // The lowered A reaches 0.25 em below the baseline; R sets the top.
        assert!((e.descent - SUB_SHIFT_EM * em).abs() < 1e-12 && (e.ascent - h).abs() < 1e-12, "{e:?}");
        // A descender in the subscript goes deeper: 0.25 em + 0.7 × p's.
        let e = measure_runs("ap", &Runs::subscript(1..2), h);
        assert!((e.descent - (SUB_SHIFT_EM - SUB_SIZE * glyph('p').y_min) * em).abs() < 1e-12);
        // Flat runs (the `_` of k_v) are not drawn; flat text measures as `measure`.
        let k = "k_v = 2";
        let e = measure_runs(k, &Runs::underscored(k), h);
        let expect = width("k", h) + SUB_SIZE * width("v", h) + width(" = 2", h);
        assert!((e.width - expect).abs() < 1e-12, "{e:?}");
        assert_eq!(measure_runs("mp", &Runs::flat(), h), measure("mp", h));
    }
}
