//! The instantaneous centres of the four-bar drawn on the mechanism, with Kennedy's lines:
//! a sheet `<name>-centres` of a few positions, one panel each.
//!
//! Each panel shows the mechanism (as the frames draw it), the six centres as small red
//! circles named I10, I30, I12, I23, I20, I13, and the four Kennedy lines (dashed, on
//! `CONSTRUCTION`) through the three centres of each triple of links: O1A (I10 I12 I20),
//! CB (I30 I23 I20), AB (I12 I23 I13), O1C (I10 I30 I13). The lines are clipped to the
//! panel; a centre outside the panel, or at infinity (parallel lines), is not drawn as a
//! point but named in the panel's notes with where it is.

use crate::draw::{Aci, Bounds, DimStyle, Drawing, Entity, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, Vector};
use crate::solve::fourbar::centres::{Centre, Centres, centres};
use crate::solve::fourbar::{Geometry, Position};

use crate::figure::fourbar::{angle_text, mechanism};
use crate::figure::shared::labels::{self, Label, TextBox};
use crate::figure::shared::vocab::{ModelUnits, Sizes, content_drawing, ground, layer_of, layers, length_caption};

/// Layer of the centres' circles and names.
pub const CENTRES: layers::Layer = ("CENTRES", Aci::RED, LineType::Continuous);

/// The part of the line through `p` along `u` inside `window`, if any (Liang–Barsky on
/// an unbounded line).
pub fn clip_line(p: Point, u: Vector, window: &Bounds) -> Option<(Point, Point)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (d, lo, hi, x) in [(u.x, window.min.x, window.max.x, p.x), (u.y, window.min.y, window.max.y, p.y)] {
        if d == 0.0 {
            if x < lo || x > hi {
                return None;
            }
        } else {
            let (a, b) = ((lo - x) / d, (hi - x) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
    }
    (t0 < t1 && t0.is_finite() && t1.is_finite()).then(|| (p + u * t0, p + u * t1))
}

fn inside(p: Point, w: &Bounds) -> bool {
    p.x >= w.min.x && p.x <= w.max.x && p.y >= w.min.y && p.y <= w.max.y
}

/// A number of model units for a note, to 4 significant digits.
fn coord(v: f64) -> String {
    let s = format!("{:.4}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// Draws the centres `c` (small circles) and the Kennedy lines inside `window` on `d` (a
/// [`content_drawing`] with the [`CENTRES`] layer). Returns the centres drawn, to be named
/// ([`name_centres`]), and one note per centre not drawn as a point (outside `window` or at
/// infinity), with its coordinates less `offset` (where the drawing has moved the mechanism
/// to).
pub fn draw_centres(
    d: &mut Drawing,
    c: &Centres,
    window: &Bounds,
    s: Sizes,
    offset: Vector,
) -> (Vec<(&'static str, Point)>, Vec<String>) {
    let con = layer_of(d, layers::CONSTRUCTION);
    let layer =
        d.layers.iter().position(|l| l.name == CENTRES.0).unwrap_or_else(|| d.layer(CENTRES.0, CENTRES.1, CENTRES.2));
    for line in c.kennedy_lines() {
        if let Some((a, b)) = clip_line(line.through, line.direction, window) {
            d.add(con, Shape::Line { from: a, to: b });
        }
    }
    let (mut drawn, mut notes) = (Vec::new(), Vec::new());
    for (name, centre) in c.named() {
        match centre {
            Centre::At(p) if inside(p, window) => {
                d.add(layer, Shape::Circle { center: p, radius: 0.45 * s.joint });
                drawn.push((name, p));
            }
            Centre::At(p) => {
                let q = p - offset;
                notes.push(format!("{name} off the panel, at ({}, {})", coord(q.x), coord(q.y)));
            }
            Centre::AtInfinity(u) => {
                let deg = libm::atan2(u.y, u.x).to_degrees().rem_euclid(180.0);
                notes.push(format!("{name} at infinity, direction {}°", angle_text(deg)))
            }
        }
    }
    (drawn, notes)
}

/// Names the centres drawn by [`draw_centres`] in `window`: each letter away from the
/// window's middle (outside the linkage), clear of everything already in `d` and inside
/// `panel`.
pub fn name_centres(d: &mut Drawing, drawn: &[(&str, Point)], window: &Bounds, s: Sizes, panel: TextBox) {
    let layer =
        d.layers.iter().position(|l| l.name == CENTRES.0).unwrap_or_else(|| d.layer(CENTRES.0, CENTRES.1, CENTRES.2));
    let mut letters = labels::Polygon::of_points();
    let mid = Point::from((window.min.coords + window.max.coords) / 2.0);
    for (name, p) in drawn {
        // On two or three Kennedy lines through the centre: a leader lets the name go out
        // between them.
        letters.name_with_leader(*p, *name, 0.85 * s.text, p - mid, None);
    }
    letters.keep_off_drawing(d);
    letters.keep_within(panel);
    letters.draw(d, layer);
}

/// Panels per row of the centres sheet.
const COLUMNS: usize = 2;

/// The centres sheet: one panel per position of `positions`, two to a row, each the
/// mechanism inside `window` (model units, the same for every panel) with its centres,
/// Kennedy's lines, its crank angle and the notes of centres not drawn; on paper at `k_l`
/// (model units per paper millimetre).
pub fn centres_sheet(geom: &Geometry, positions: &[&Position], window: Bounds, k_l: f64, units: ModelUnits) -> Drawing {
    let s = Sizes::on_paper(k_l);
    let mut d = content_drawing(DimStyle { text_height: s.text, arrow_size: s.head });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    d.layer(CENTRES.0, CENTRES.1, CENTRES.2);
    let frame = d.layer("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    let text = layer_of(&d, layers::TEXT);
    let gap = 2.0 * s.text;
    let notes_room = 3.0 * 1.5 * s.text;
    let title_room = 2.0 * s.text;
    let (w, h) = (window.width(), window.height() + notes_room + title_room);
    for (k, pos) in positions.iter().enumerate() {
        let (col, row) = ((k % COLUMNS) as f64, (k / COLUMNS) as f64);
        let off = Vector::new(col * (w + gap), -row * (h + gap));
        let shift = |p: Point| p + off;
        let g = Geometry { o1: shift(geom.o1), c: shift(geom.c), ..*geom };
        let p = Position { a: shift(pos.a), b: shift(pos.b), m: shift(pos.m), c: shift(pos.c), ..**pos };
        let win = Bounds { min: shift(window.min), max: shift(window.max) };
        let corners = vec![
            Point::new(win.min.x, win.min.y - notes_room),
            Point::new(win.max.x, win.min.y - notes_room),
            Point::new(win.max.x, win.max.y + title_room),
            Point::new(win.min.x, win.max.y + title_room),
        ];
        d.add(frame, Shape::Polyline { points: corners.clone(), closed: true, width: 0.0 });
        let mech = layer_of(&d, layers::MECHANISM);
        for q in [g.o1, g.c] {
            ground(&mut d, mech, q, s);
        }
        let panel = TextBox { min: corners[0], max: corners[2] };
        // The lines and centres first, the title and the notes, then the letters of the
        // mechanism and of the centres clear of them all.
        let (drawn, notes) = draw_centres(&mut d, &centres(&g, &p), &win, s, off);
        // φ_1 where the writer can draw a subscript, `φ1` in the DXF.
        let Label { text: title, runs } = Label::marked(&format!("φ_1 = {}°", angle_text(pos.phi1.to_degrees())));
        let at = Point::new(win.min.x + 0.5 * s.text, win.max.y + 0.6 * s.text);
        d.push(Entity {
            layer: text,
            color: None,
            linetype: None,
            shape: Shape::Text {
                runs,
                at,
                height: s.text,
                value: title,
                halign: HAlign::Left,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        });
        for (i, n) in notes.iter().enumerate() {
            let at = Point::new(win.min.x + 0.5 * s.text, win.min.y - (1.0 + 1.5 * i as f64) * 0.85 * s.text);
            d.push(Entity {
                layer: text,
                color: None,
                linetype: None,
                shape: Shape::Text {
                    runs: crate::draw::Runs::flat(),
                    at,
                    height: 0.85 * s.text,
                    value: n.clone(),
                    halign: HAlign::Left,
                    valign: VAlign::Top,
                    rotation: 0.0,
                },
            });
        }
        let _ = mechanism(&mut d, &g, &p, &[], None, s, labels::Around { backdrop: None, within: Some(panel) });
        name_centres(&mut d, &drawn, &win, s, panel);
    }
    // The sheet's heading above the first row, with its length scale.
    let heading = length_caption("Instantaneous centres and Kennedy's lines   ", k_l, units);
    let at = Point::new(window.min.x, window.max.y + title_room + 1.0 * s.text);
    d.scale_text(text, at, s.text, heading);
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_clipped_to_the_window_and_a_line_outside_is_not_drawn() {
        let w = Bounds { min: Point::new(0.0, 0.0), max: Point::new(2.0, 1.0) };
        let (a, b) = clip_line(Point::new(-5.0, 0.5), Vector::new(1.0, 0.0), &w).unwrap();
        assert_eq!((a, b), (Point::new(0.0, 0.5), Point::new(2.0, 0.5)));
        let (a, b) = clip_line(Point::new(0.0, 0.0), Vector::new(1.0, 1.0), &w).unwrap();
        assert_eq!((a, b), (Point::new(0.0, 0.0), Point::new(1.0, 1.0)));
        assert!(clip_line(Point::new(0.0, 3.0), Vector::new(1.0, 0.0), &w).is_none());
        assert!(clip_line(Point::new(0.0, 3.0), Vector::new(0.0, 0.0), &w).is_none());
    }
}
