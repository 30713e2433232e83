//! The metrics of the bundled DejaVu Sans ([`super::raster::FONT`]), the font every SVG, PNG
//! and PDF we write draws its text in: each character's advance and the vertical extent of
//! its glyph, read from the font file itself (skrifa, as the PDF writer reads it). A text's
//! box ([`measure`]) is what a figure's letter placer keeps clear and what the overlap tests
//! check, so that both measure the text as the reader draws it.
//!
//! Sizes: a text's `height` is its cap height (the writers set the font size to
//! `height / CAP_HEIGHT_EM`), so widths, ascents and descents come out in the units of the
//! height. The writers do not kern (the PDF places glyphs by their advances; an SVG reader
//! may kern DejaVu's few kerned pairs, which only narrows a text), so a text's width is the
//! sum of its advances.

use std::sync::OnceLock;

use rustc_hash::FxHashMap;
use skrifa::MetadataProvider;
use skrifa::instance::{LocationRef, Size};

/// Cap height of DejaVu Sans, in ems (1493 of 2048 font units): the SVG writer sets the
/// font size to the text height / 0.73, so a text height is a cap height.
pub const CAP_HEIGHT_EM: f64 = 0.73;

/// How far round letters overshoot the baseline and the cap height (`o`, `a`, `O`: 0.01–0.015
/// em in DejaVu Sans), in ems: a text whose glyphs stay within this of the line counts as
/// standing on the baseline and ending at the cap height.
pub const OVERSHOOT_EM: f64 = 0.02;

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

/// Every character the font maps, with its metrics, and the `.notdef` glyph's metrics for
/// the others (what a reader draws for a character the font lacks).
struct Table {
    glyphs: FxHashMap<char, Glyph>,
    missing: Glyph,
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        // The font is compiled in: a broken file is a broken build, caught by the tests
        // below; the fallback keeps a drawing (an estimate of 0.6 em a character) rather
        // than a panic.
        let fallback = Glyph { advance: 0.6, y_min: -0.24, y_max: 0.76 };
        let Ok(font) = skrifa::FontRef::new(super::raster::FONT) else {
            return Table { glyphs: FxHashMap::default(), missing: fallback };
        };
        let upem = f64::from(font.metrics(Size::unscaled(), LocationRef::default()).units_per_em);
        let gm = font.glyph_metrics(Size::unscaled(), LocationRef::default());
        let glyph = |gid: skrifa::GlyphId| {
            let advance = gm.advance_width(gid).map_or(fallback.advance, |a| f64::from(a) / upem);
            let (y_min, y_max) =
                gm.bounds(gid).map_or((0.0, 0.0), |b| (f64::from(b.y_min) / upem, f64::from(b.y_max) / upem));
            Glyph { advance, y_min, y_max }
        };
        let glyphs =
            font.charmap().mappings().filter_map(|(code, gid)| Some((char::from_u32(code)?, glyph(gid)))).collect();
        Table { glyphs, missing: glyph(skrifa::GlyphId::NOTDEF) }
    })
}

/// The metrics of `c` in DejaVu Sans (the `.notdef` box for a character it lacks).
pub fn glyph(c: char) -> Glyph {
    let t = table();
    t.glyphs.get(&c).copied().unwrap_or(t.missing)
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
    let em = height / CAP_HEIGHT_EM;
    let low = if low > -OVERSHOOT_EM { 0.0 } else { low };
    let high = if high < CAP_HEIGHT_EM + OVERSHOOT_EM { CAP_HEIGHT_EM } else { high };
    TextExtent { width: advance * em, ascent: high * em, descent: -low * em }
}

/// Width (model units) of `text` drawn `height` high: the sum of its DejaVu Sans advances.
pub fn width(text: &str, height: f64) -> f64 {
    measure(text, height).width
}

#[cfg(test)]
mod tests {
    use super::*;

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
        // A space has no ink.
        assert_eq!((glyph(' ').y_min, glyph(' ').y_max), (0.0, 0.0));
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
        // A character the font lacks takes the .notdef box, never nothing.
        assert!(glyph('\u{10FFFD}').advance > 0.3);
    }
}
