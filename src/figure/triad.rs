//! Figure: the triad as the seed's Fig. 3 — the three circles, the approximate triangle at
//! the pattern method's start angle (red, dashed), the exact position (closed polyline of
//! width 0.5) with its links O_iA_i, ground pivots, angular dimensions of phi1, phi2, phi3
//! measured at O1, O2, O3 from +x, point labels, and the other assembly modes, numbered,
//! on their own lighter layer.
//!
//! Layers: `CONSTRUCTION` (circles), `APPROXIMATE` (start triangle), `MECHANISM` (exact
//! position, pivots, joints), `MODES` (other assembly modes), `DIMENSIONS`, `TEXT`.
//! Sizes are the shared table's ([`Sizes::for_length`]) for the triad's size, so a triad in
//! metres looks the same as one in millimetres.

use crate::draw::{Aci, DimStyle, Drawing, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, Vector, angle_of, normalize_angle, polar};
use crate::solve::triad::{Configuration, Triad};

use super::labels::{self, TextBox};
use super::vocab::{self, Sizes};

/// What to draw.
#[derive(Debug, Clone, Copy)]
pub struct TriadFigure<'a> {
    /// The triad's data.
    pub triad: &'a Triad,
    /// The position drawn as the mechanism (the pattern method's, polished).
    pub exact: &'a Configuration,
    /// The approximate triangle at the start angle (A1, A2, A3), if it exists.
    pub approximate: Option<[Point; 3]>,
    /// The other assembly modes with their numbers (1-based).
    pub others: &'a [(usize, Configuration)],
    /// Caption lines under the drawing (may be empty).
    pub caption: &'a [String],
}

/// Height of the small texts (mode numbers, φ names, caption), in letter heights.
const SMALL_TEXT: f64 = 0.8;

/// Direction (radians) in the middle of the widest gap between the `occupied` directions.
fn free_direction(occupied: &[f64]) -> f64 {
    let mut a: Vec<f64> = occupied.iter().map(|&x| normalize_angle(x)).collect();
    if a.is_empty() {
        return std::f64::consts::FRAC_PI_4;
    }
    a.sort_by(f64::total_cmp);
    let mut best = (0.0, 0.0);
    for i in 0..a.len() {
        let next = if i + 1 < a.len() { a[i + 1] } else { a[0] + std::f64::consts::TAU };
        let gap = next - a[i];
        if gap > best.0 {
            best = (gap, a[i] + 0.5 * gap);
        }
    }
    best.1
}

/// The seed's Fig. 3 for `f`.
pub fn drawing(f: &TriadFigure) -> Drawing {
    let t = f.triad;
    let s = Sizes::for_length(t.scale());
    let small_text = SMALL_TEXT * s.text;
    let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
    let construction = d.layer("CONSTRUCTION", Aci::DARK_GREY, LineType::Continuous);
    let modes = d.layer("MODES", Aci::LIGHT_GREY, LineType::Continuous);
    let approximate = d.layer("APPROXIMATE", Aci::RED, LineType::Dashed);
    let mechanism = d.layer("MECHANISM", Aci::BLACK, LineType::Continuous);
    let dimensions = d.layer("DIMENSIONS", Aci::BLUE, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);

    for (o, r) in t.o.iter().zip(t.r) {
        d.add(construction, Shape::Circle { center: *o, radius: r });
    }

    // Other assembly modes first, so the exact position is drawn over them.
    for (n, c) in f.others {
        d.add(modes, Shape::Polyline { points: c.a.to_vec(), closed: true, width: 0.0 });
        for i in 0..3 {
            d.add(modes, Shape::Line { from: t.o[i], to: c.a[i] });
        }
        let centroid = Point::from((c.a[0].coords + c.a[1].coords + c.a[2].coords) / 3.0);
        d.add_colored(
            modes,
            Aci::DARK_GREY,
            Shape::Text {
                at: centroid,
                height: small_text,
                value: n.to_string(),
                halign: HAlign::Center,
                valign: VAlign::Middle,
                rotation: 0.0,
            },
        );
    }

    if let Some(a) = f.approximate {
        d.add(approximate, Shape::Polyline { points: a.to_vec(), closed: true, width: 0.0 });
    }

    // The exact position.
    let a = f.exact.a;
    for (o, p) in t.o.iter().zip(a) {
        vocab::link(&mut d, mechanism, vec![*o, p], false, None, s);
    }
    vocab::link(&mut d, mechanism, a.to_vec(), true, None, s);
    for o in t.o {
        vocab::ground(&mut d, mechanism, o, s);
    }
    for p in a {
        vocab::joint(&mut d, mechanism, p, s);
    }

    let mut phi_names: Vec<(Point, String, f64)> = Vec::new();
    // Angular dimensions phi_i at O_i from +x (value on the dimension, the name φi inside
    // the angle, as a draughtsman writes it).
    for (i, (o, p)) in t.o.iter().zip(a).enumerate() {
        let radius = 0.42 * t.r[i].min(0.3 * t.scale() + 0.1 * t.r[i]);
        let phi = f.exact.phi[i];
        d.add(
            dimensions,
            Shape::AngularDimension {
                vertex: *o,
                first: o + Vector::new(s.joint + 0.3 * s.text, 0.0),
                second: p,
                radius,
                text: format!("{:.2}°", phi.to_degrees()),
            },
        );
        let name_at = polar(*o, 0.62 * radius, 0.5 * phi);
        phi_names.push((name_at, format!("φ{}", i + 1), small_text));
        d.add(
            dimensions,
            Shape::Text {
                at: name_at,
                height: small_text,
                value: format!("φ{}", i + 1),
                halign: HAlign::Center,
                valign: VAlign::Middle,
                rotation: 0.0,
            },
        );
    }

    // Labels: each preferably in the widest free direction around its point, placed by the
    // letter placer clear of the joint, the links, the ground symbols and the φ names.
    let mut letters = labels::Polygon::of_names();
    for i in 0..3 {
        letters.segment(t.o[i], a[i]);
        letters.segment(a[i], a[(i + 1) % 3]);
        letters.keep_off(vocab::ground_extent(t.o[i], s));
    }
    for (at, value, height) in &phi_names {
        letters.keep_off(TextBox::centred(*at, value, *height));
    }
    let toward = |dir: f64| Vector::new(dir.cos(), dir.sin());
    for i in 0..3 {
        let phi = f.exact.phi[i];
        // At O_i: the link, the +x reference line, the dimensioned sector between them and
        // the ground symbol below.
        let mut occupied: Vec<f64> = (0..=8).map(|k| phi * k as f64 / 8.0).collect();
        occupied.extend([-std::f64::consts::FRAC_PI_2 - 0.5, -std::f64::consts::FRAC_PI_2 + 0.5]);
        let dir = free_direction(&occupied);
        letters.letter_clear(t.o[i], &format!("O{}", i + 1), s.text, toward(dir), s.joint);
        // At A_i: the link back to O_i and the two sides.
        let occupied = [angle_of(t.o[i] - a[i]), angle_of(a[(i + 1) % 3] - a[i]), angle_of(a[(i + 2) % 3] - a[i])];
        let dir = free_direction(&occupied);
        letters.letter_clear(a[i], &format!("A{}", i + 1), s.text, toward(dir), s.joint);
    }
    letters.draw(&mut d, text);

    // Caption under everything drawn so far.
    if !f.caption.is_empty() {
        if let Some(b) = d.bounds() {
            let mut y = b.min.y - 2.0 * s.text;
            for line in f.caption {
                d.add(
                    text,
                    Shape::Text {
                        at: Point::new(b.min.x, y),
                        height: small_text,
                        value: line.clone(),
                        halign: HAlign::Left,
                        valign: VAlign::Baseline,
                        rotation: 0.0,
                    },
                );
                y -= 1.8 * small_text;
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_direction_is_the_middle_of_the_widest_gap() {
        let d = free_direction(&[0.0, std::f64::consts::FRAC_PI_2]);
        assert!((d - 1.25 * std::f64::consts::PI).abs() < 1e-12);
        let d = free_direction(&[0.1]);
        assert!((normalize_angle(d) - (0.1 + std::f64::consts::PI)).abs() < 1e-12);
    }
}
