//! The diagrams over the cycle, [`PER_PAGE`] to a page: each of the run's diagrams (drawn
//! by [`crate::figure::shared::plot`] on its own paper) placed in a framed cell at the
//! largest size that fits it, and the report's chosen positions marked on its curve — a
//! red ring where the curve is at that position, a dashed line down to the abscissa, and
//! the position's number beside the ring.

use crate::draw::{Aci, Bounds, Drawing, Entity, LineType, Shape};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch;
use crate::figure::shared::labels;
use crate::geom::{Point, Vector};

/// Diagrams on one page (two rows of two).
pub const PER_PAGE: usize = 4;

/// The layer of the marks.
pub const MARKS_LAYER: &str = "MARKS";

/// A diagram with the marks of the chosen positions.
#[derive(Debug, Clone)]
pub struct MarkedDiagram {
    /// The diagram as plotted (its own paper mm, y up).
    pub drawing: Drawing,
    /// Where each chosen position is on the curve (the diagram's paper), with its label.
    pub marks: Vec<(Point, String)>,
}

/// Where a marked diagram went on its page: the scale and offset of the map from its paper
/// to the page's (`page = offset + scale · diagram`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Page mm per diagram mm.
    pub scale: f64,
    /// The page point of the diagram's origin.
    pub offset: Vector,
}

impl Placed {
    /// A diagram point on the page.
    pub fn point(&self, p: Point) -> Point {
        Point::from(self.offset + p.coords * self.scale)
    }
}

/// The page of `diagrams` (at most [`PER_PAGE`]); returns it with where each went.
pub fn page(frame: &ReportFrame, title: &PageTitle, diagrams: &[MarkedDiagram]) -> (Drawing, Vec<Placed>) {
    let s = frame.sizes;
    let mut d = frame.page(title);
    let marks_layer = d.layer(MARKS_LAYER, Aci::RED, LineType::Continuous);
    let cells: Vec<Bounds> =
        page::rows(frame.content, 2, 0.0).into_iter().flat_map(|r| page::columns(r, 2, 0.0)).collect();
    let mut placed = Vec::new();
    for (m, cell) in diagrams.iter().take(PER_PAGE).zip(cells) {
        let area = page::panel(&mut d, cell, "", s);
        let Some(b) = crate::figure::report::compose::extent(&m.drawing) else { continue };
        let scale = (area.width() / b.width().max(1e-9)).min(area.height() / b.height().max(1e-9));
        let size = Vector::new(b.width(), b.height()) * scale;
        let corner = area.min + (Vector::new(area.width(), area.height()) - size) / 2.0;
        let offset = corner.coords - b.min.coords * scale;
        let at = Placed { scale, offset };
        let start = d.entities.len();
        d.append(&m.drawing.mapped(scale, offset));
        let mut letters = labels::Polygon::of_names();
        sketch::avoid(&d, start, &mut letters);
        sketch::keep_inside(&mut letters, area);
        let ring = 0.5 * s.joint.max(1.0);
        for (p, label) in &m.marks {
            let pt = at.point(*p);
            if !(pt.x.is_finite() && pt.y.is_finite()) {
                continue;
            }
            let foot = at.point(Point::new(p.x, 0.0));
            if (pt - foot).norm() > ring {
                d.push(Entity {
                    layer: marks_layer,
                    color: None,
                    linetype: Some(LineType::Dashed),
                    shape: Shape::Line { from: foot, to: pt - (pt - foot).normalize() * ring },
                });
            }
            d.add(marks_layer, Shape::Circle { center: pt, radius: ring });
            letters.keep_off(labels::TextBox { min: pt - Vector::new(ring, ring), max: pt + Vector::new(ring, ring) });
            letters.letter_clear(pt, label, s.small_text(), Vector::new(0.3, 1.0), ring);
        }
        letters.draw(&mut d, marks_layer);
        placed.push(at);
    }
    (d, placed)
}
