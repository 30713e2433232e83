//! What LibreCAD does with the DXF's text, measured, so that the writer can make up for it:
//! the glyphs of its stroke font for our text style ([`super::TEXT_STYLE`], LibreCAD's
//! `azomix.lff`), how it places aligned text, and the characters that font lacks.
//!
//! LibreCAD 2.2 draws a TEXT of height `h` with its own stroke font, 9 font units to `h`:
//! each glyph at the previous one's right edge plus the font's letter spacing (1 unit), a
//! space as the word spacing (6.75 units). Its glyphs are wider than DejaVu Sans's (the
//! font the SVG draws and every layout measures with, [`parts::text_width`]) and start 2–5
//! units right of the insertion point, so a text laid out for DejaVu runs into what follows
//! it. A centred or right-aligned text is moved left by the width of its *ink* (first
//! glyph's left edge to last glyph's right edge), which leaves it that left edge too far
//! right: a centred digit sits 0.35–0.49 heights right of its point (measured on LibreCAD
//! 2.2's `dxf2pdf` pages, November 2026; the model below is held to such a page by
//! `tests/dxf_librecad.rs`). LibreCAD honours a TEXT's width factor (group 41) and scales
//! the glyphs and their spacing by it; TrueType readers (AutoCAD, ezdxf) do the same.
//!
//! What the writer does with this ([`text_fit`]): every TEXT gets the width factor, at most
//! one, that keeps LibreCAD's ink inside the box DejaVu Sans gives the text, so anything a
//! figure keeps clear of that box stays clear in LibreCAD too; a centred single character
//! (a link's number in its circle) is written left-aligned at the point that centres it
//! halfway between LibreCAD's glyph and DejaVu's, so that both are off by under 0.07
//! heights instead of LibreCAD's by up to 0.49; and the characters the font lacks are
//! written as ones it has ([`for_azomix`]).

use std::borrow::Cow;

use crate::draw::parts;
use crate::draw::{HAlign, VAlign};
use crate::geom::{Point, Vector};

/// LibreCAD font units per text height.
pub const UNITS_PER_HEIGHT: f64 = 9.0;
/// The font's letter spacing, units (`# LetterSpacing` of `azomix.lff`).
pub const LETTER_SPACING: f64 = 1.0;
/// The font's word spacing: the advance of a space, units (`# WordSpacing`).
pub const WORD_SPACING: f64 = 6.75;
/// Where LibreCAD draws a glyph's cap line and base, units above the baseline: 1.25 to 10
/// (digits and capitals), so its text sits 0.14 heights higher than DejaVu's and is 0.97
/// heights tall.
pub const GLYPH_BASE: f64 = 1.25;
/// The cap line of LibreCAD's glyphs, units above the baseline.
pub const GLYPH_TOP: f64 = 10.0;
/// The stand-in LibreCAD draws for a character its font lacks, taken as wide as `W`.
const STAND_IN: (f64, f64) = (1.25, 9.06);

/// The left and right edges of a character's glyph in LibreCAD's `azomix.lff`, font units
/// from the glyph's origin (composite glyphs through the glyphs they reference); `None`
/// for a space and for a character the font lacks (`·`, `–`, `—`) or that is not listed
/// here (ASCII, Latin-1 signs, Greek and the arrows and signs mechdraw writes). Read from
/// LibreCAD 2.2's font file; `tests/dxf_librecad.rs` checks the table against it.
pub fn glyph(c: char) -> Option<(f64, f64)> {
    Some(match c {
        '³' => (0.0, 4.06),
        '*' | '²' | 'µ' => (0.0, 4.38),
        '_' => (0.0, 10.62),
        '→' | '←' => (0.31, 8.75),
        '^' => (0.94, 3.44),
        '″' => (0.94, 3.75),
        '−' => (0.94, 7.81),
        '′' => (1.25, 2.19),
        '%' | '@' | 'W' => (1.25, 9.06),
        '√' => (1.25, 10.62),
        '`' => (1.88, 2.81),
        'θ' => (1.88, 8.12),
        '∞' | 'ω' | 'Φ' => (1.88, 8.75),
        '|' => (2.19, 2.19),
        '#' | '&' | 'A' | 'M' | 'Q' | 'V' | 'X' | 'Y' | 'm' | 'w' | 'Δ' | 'Ω' | 'π' | 'φ' | 'ψ' | 'Ψ' | 'Λ' => {
            (2.19, 8.12)
        }
        '↑' | '↓' => (2.81, 5.94),
        'B' | 'P' => (2.81, 7.5),
        '4' | 'D' | 'G' | 'H' | 'K' | 'N' | 'O' | 'R' | 'S' | 'T' | 'U' | 'Z' | 'Σ' | 'β' | 'γ' | 'λ' | 'Θ' | 'Π' => {
            (2.81, 7.81)
        }
        'α' | 'σ' | 'τ' => (2.81, 8.12),
        '$' | '+' | '-' | '/' | '0' | '2' | '3' | '5' | '6' | '7' | '8' | '9' | '<' | '=' | '>' | '?' | 'C' | 'E'
        | 'F' | 'L' | '\\' | 'b' | 'd' | 'e' | 'g' | 'h' | 'k' | 'n' | 'o' | 'p' | 'q' | 's' | 'u' | 'v' | 'x'
        | 'y' | 'z' | '~' | '±' | '×' | '÷' | '≈' | '≤' | '≥' | '≡' | 'δ' | 'ρ' => (3.12, 7.19),
        'Γ' => (3.12, 7.81),
        'μ' => (3.12, 8.12),
        'a' | 'ε' => (3.44, 7.19),
        '"' | 'J' | 'c' => (3.75, 6.56),
        '1' | 'j' | '{' | '}' => (4.38, 6.25),
        'f' | 'r' | 't' => (4.38, 7.19),
        ';' => (4.69, 5.31),
        '(' | ')' | '[' | ']' => (4.69, 5.62),
        '\'' | ',' => (5.0, 5.31),
        '°' => (5.0, 7.5),
        '!' | '.' | ':' | 'I' | 'i' => (5.31, 5.31),
        'l' => (5.31, 6.25),
        _ => return None,
    })
}

/// The advance of a character in LibreCAD's font, units: its glyph's right edge plus the
/// letter spacing, the word spacing for a space, and for a character the font lacks that
/// of the stand-in glyph LibreCAD draws (as wide as `W`).
pub fn advance(c: char) -> f64 {
    if c == ' ' {
        return WORD_SPACING;
    }
    glyph(c).unwrap_or(STAND_IN).1 + LETTER_SPACING
}

/// The ink of `text` as LibreCAD lays it out left-aligned, in font units from the insertion
/// point: the first glyph's left edge and the last glyph's right edge (`None` for a text of
/// spaces only).
pub fn ink(text: &str) -> Option<(f64, f64)> {
    let (mut pos, mut ink): (f64, Option<(f64, f64)>) = (0.0, None);
    for c in text.chars() {
        if c == ' ' {
            pos += WORD_SPACING;
            continue;
        }
        let (l, r) = glyph(c).unwrap_or(STAND_IN);
        ink = Some(ink.map_or((pos + l, pos + r), |(a, b)| (a.min(pos + l), b.max(pos + r))));
        pos += r + LETTER_SPACING;
    }
    ink
}

/// Whether `text` has a character [`for_azomix`] replaces.
pub fn lacks_glyphs(text: &str) -> bool {
    text.contains(['·', '–', '—'])
}

/// `text` with the characters LibreCAD's font for our text style lacks written as ones it
/// has: a spaced `·` (a separator: `Mode 1 · counter-clockwise`) as a comma, any other `·`
/// (a product: `N·m`, `kg·m²`) as a space (ISO 80000-1 writes a product of units either
/// way), `–` and `—` as `-`. Borrowed when there is nothing to replace.
pub fn for_azomix(text: &str) -> Cow<'_, str> {
    if !lacks_glyphs(text) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    let chars: Vec<char> = text.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        match c {
            '·' => {
                let spaced = i > 0 && chars[i - 1] == ' ' && chars.get(i + 1) == Some(&' ');
                if spaced {
                    // "a · b" → "a, b": the space before the dot goes.
                    out.pop();
                    out.push(',');
                } else {
                    out.push(' ');
                }
            }
            '–' | '—' => out.push('-'),
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

/// How a TEXT is written so that LibreCAD draws it inside the box DejaVu Sans gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextFit {
    /// The alignment point (for a left/baseline text, the insertion point).
    pub at: Point,
    /// Horizontal alignment written.
    pub halign: HAlign,
    /// Vertical alignment written.
    pub valign: VAlign,
    /// Width factor (group 41), in (0, 1]: 1 is not written.
    pub width: f64,
}

/// Width factors are rounded down to hundredths, so that files do not carry 17 digits of a
/// factor that only needs to be small enough.
const WIDTH_STEPS: f64 = 100.0;
#[cfg(test)]
const WIDTH_STEP: f64 = 1.0 / WIDTH_STEPS;
/// The smallest width factor written: a text that LibreCAD would draw more than three
/// times as wide as DejaVu (one full of spaces) is written at this.
const MIN_WIDTH: f64 = 0.3;

/// How a TEXT `value` (already [`for_azomix`]) `height` high, aligned `halign`/`valign` at
/// `at` and turned by `rotation` (radians), is written (see the module documentation):
/// - the width factor: the largest multiple of 0.01 in [0.3, 1] that keeps LibreCAD's ink
///   within DejaVu's width `w` ([`parts::text_width`]) — left-aligned, the ink's right edge
///   at most `w` from the start; centred, at most `w/2` right of the point (LibreCAD leaves
///   the ink its left edge to the right); right-aligned, the ink at most `w` wide (it ends
///   its left edge past the point, as in AutoCAD it cannot be moved without moving the
///   text there);
/// - a single centred character: left-aligned on its baseline, its start where LibreCAD's
///   glyph centre and DejaVu's advance centre fall on either side of `at` by the same
///   amount, and the baseline where LibreCAD's glyph (1.25–10 units) and DejaVu's cap
///   height (0–1) are as far above and below the point asked for.
pub fn text_fit(at: Point, height: f64, value: &str, halign: HAlign, valign: VAlign, rotation: f64) -> TextFit {
    let fitted = TextFit { at, halign, valign, width: 1.0 };
    let Some((l, r)) = ink(value) else { return fitted };
    let unit = height / UNITS_PER_HEIGHT;
    let w = parts::text_width(value, height);
    if halign == HAlign::Center && value.chars().count() == 1 {
        // From a left start: LibreCAD's glyph centre and DejaVu's (half its advance).
        let along = 0.5 * (0.5 * (l + r) * unit + 0.5 * w);
        // Down to the baseline from the point: halfway between LibreCAD's glyph (its middle
        // or top) and DejaVu's caps.
        let drop = match valign {
            VAlign::Baseline => 0.0,
            VAlign::Middle => 0.5 * (0.5 * (GLYPH_BASE + GLYPH_TOP) * unit + 0.5 * height),
            VAlign::Top => 0.5 * (GLYPH_TOP * unit + height),
        };
        let (sin, cos) = if rotation == 0.0 { (0.0, 1.0) } else { libm::sincos(rotation) };
        let (u, v) = (Vector::new(cos, sin), Vector::new(-sin, cos));
        return TextFit { at: at - u * along - v * drop, halign: HAlign::Left, valign: VAlign::Baseline, width: 1.0 };
    }
    // The ink LibreCAD draws, against the width DejaVu gives the text.
    let needed = match halign {
        HAlign::Left => r,
        HAlign::Center => l + r,
        HAlign::Right => r - l,
    } * unit;
    if needed <= w {
        return fitted;
    }
    let width = (w / needed * WIDTH_STEPS).floor() / WIDTH_STEPS;
    TextFit { width: width.clamp(MIN_WIDTH, 1.0), ..fitted }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advances_are_the_glyphs_right_edges_and_the_spacing() {
        assert_eq!(advance(' '), 6.75);
        assert!((advance('2') - 8.19).abs() < 1e-12);
        assert_eq!(advance('·'), advance('W'));
        // "12": 1 from 4.38, 2 at 6.25 + 1 = 7.25, its right edge at 7.25 + 7.19.
        let (l, r) = ink("12").unwrap();
        assert!((l - 4.38).abs() < 1e-12 && (r - 14.44).abs() < 1e-12);
        assert_eq!(ink("   "), None);
    }

    #[test]
    fn missing_characters_are_written_as_ones_the_font_has() {
        assert_eq!(for_azomix("N·m"), "N m");
        assert_eq!(
            for_azomix("Mode 1 · counter-clockwise · drawn in Fig. 3"),
            "Mode 1, counter-clockwise, drawn in Fig. 3"
        );
        assert_eq!(for_azomix("Dyad 2–3 (Fig. 4)"), "Dyad 2-3 (Fig. 4)");
        assert!(matches!(for_azomix("φ1 = 75.77°"), Cow::Borrowed(_)));
        for text in ["N·m", "Mode 1 · a", "2–3", "a—b"] {
            assert!(for_azomix(text).chars().all(|c| c == ' ' || glyph(c).is_some()), "{text}");
        }
    }

    #[test]
    fn the_width_factor_keeps_librecads_ink_in_the_dejavu_box() {
        let h = 2.0;
        let unit = h / UNITS_PER_HEIGHT;
        for text in ["k_v = 0.04 (m/s)/mm", "RBgas", "Velocity polygon   k_v = 0.1 (m/s)/mm", "38 ±0.1", "W", "ii"] {
            let w = parts::text_width(text, h);
            let (l, r) = ink(text).unwrap();
            for halign in [HAlign::Left, HAlign::Center, HAlign::Right] {
                let fit = text_fit(Point::origin(), h, text, halign, VAlign::Baseline, 0.0);
                if text.chars().count() == 1 && halign == HAlign::Center {
                    continue;
                }
                assert!(fit.width > 0.0 && fit.width <= 1.0);
                let k = fit.width * unit;
                // LibreCAD's ink, as it aligns it.
                let (lo, hi) = match halign {
                    HAlign::Left => (k * l, k * r),
                    HAlign::Center => (k * l - 0.5 * k * (r - l), k * l + 0.5 * k * (r - l)),
                    HAlign::Right => (k * l - k * (r - l), k * l),
                };
                let (box_lo, box_hi) = match halign {
                    HAlign::Left => (0.0, w),
                    HAlign::Center => (-0.5 * w, 0.5 * w),
                    HAlign::Right => (-w, 0.0),
                };
                assert!(lo >= box_lo - 1e-12, "{text} {halign:?}: {lo} < {box_lo}");
                if halign != HAlign::Right {
                    assert!(hi <= box_hi + 1e-12, "{text} {halign:?}: {hi} > {box_hi}");
                } else {
                    assert!(hi - lo <= w + 1e-12);
                }
                // And no narrower than it needs to be: one step wider would not fit.
                if fit.width < 1.0 {
                    let wider = (fit.width + WIDTH_STEP) / fit.width;
                    let (lo, hi) = (lo * wider, hi * wider);
                    assert!(lo < box_lo - 1e-12 || hi > box_hi + 1e-12 || (halign == HAlign::Right && hi - lo > w));
                }
            }
        }
    }

    #[test]
    fn a_centred_digit_is_centred_between_librecads_glyph_and_dejavus() {
        let h = 10.0;
        let unit = h / UNITS_PER_HEIGHT;
        for c in ["1", "2", "4", "W"] {
            let target = Point::new(20.0, 30.0);
            let fit = text_fit(target, h, c, HAlign::Center, VAlign::Middle, 0.0);
            assert_eq!((fit.halign, fit.valign, fit.width), (HAlign::Left, VAlign::Baseline, 1.0));
            let (l, r) = ink(c).unwrap();
            let librecad = fit.at.x + 0.5 * (l + r) * unit - target.x;
            let dejavu = fit.at.x + 0.5 * parts::text_width(c, h) - target.x;
            assert!((librecad + dejavu).abs() < 1e-9, "{c}: {librecad} and {dejavu}");
            assert!(librecad.abs() < 0.1 * h, "{c}: LibreCAD {librecad}");
            let lc_mid = fit.at.y + 0.5 * (GLYPH_BASE + GLYPH_TOP) * unit - target.y;
            let dv_mid = fit.at.y + 0.5 * h - target.y;
            assert!((lc_mid + dv_mid).abs() < 1e-9 && lc_mid.abs() < 0.07 * h);
        }
    }
}
