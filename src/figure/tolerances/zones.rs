//! The tolerance zones of a triad (issue 34): in each assembly mode, the triad's links and
//! triangle and, at each watched vertex, the zone it can sit in — the RSS ellipse (the
//! linear 3σ ellipse of the vertex's x and y, from their 2×2 covariance) dashed blue, and
//! the Monte Carlo's percentile box (0.135 % to 99.865 % of x and of y: the samples are not
//! kept, so their convex hull is not known) red — centred on the nominal vertex and
//! magnified by a factor stated in the panel's heading, with a bar of that panel's
//! magnified deviation. One panel per mode, every zone named; the length scale k_l and
//! its bar above the panels. Layers: `PANELS`, `MECHANISM`, `TOL_RSS`, `TOL_MC`, `TEXT`.

use crate::draw::parts::widest_text_width;
use crate::draw::{Aci, Bounds, DimStyle, Drawing, Entity, LineType, Shape};
use crate::figure::shared::construction::{caption, length_scale_block};
use crate::figure::shared::labels;
use crate::figure::shared::vocab::{self, ModelUnits, Sizes, nice_scale, scale_bar, scale_text};
use crate::geom::{Point, Vector};

use super::band::{BAND_SHARE, magnification_for};

/// Largest extent of a panel's triad on paper, millimetres.
pub const PANEL_MM: f64 = 80.0;
/// The largest magnified zone (its half size) as a fraction of the triad's extent, when
/// the magnification is chosen.
pub const ZONE_SHARE: f64 = 0.2;
/// Panels per row.
pub const COLUMNS: usize = 2;
/// The RSS ellipse's half axes in standard deviations (the ±3σ of the RSS band).
pub const ELLIPSE_SIGMAS: f64 = 3.0;
/// Points of a drawn ellipse.
const ELLIPSE_POINTS: usize = 72;

/// One vertex's zone in one mode (deviations in model units).
#[derive(Debug, Clone, PartialEq)]
pub struct Zone {
    /// The vertex's name (`A1`).
    pub name: String,
    /// Its nominal position.
    pub at: Point,
    /// The linear mean shift of its deviation.
    pub shift: Vector,
    /// The linear covariance of its deviation: (xx, xy, yy), model units².
    pub covariance: [f64; 3],
    /// The Monte Carlo's 0.135 % and 99.865 % deviations of x and of y, as the box's
    /// corners (`None` without samples).
    pub mc: Option<(Vector, Vector)>,
}

/// One assembly mode's panel.
#[derive(Debug, Clone, PartialEq)]
pub struct ZonePanel {
    /// The heading (`Mode 1 · counter-clockwise`).
    pub heading: String,
    /// The ground pivots O1, O2, O3.
    pub pivots: [Point; 3],
    /// The vertices A1, A2, A3 in this mode.
    pub vertices: [Point; 3],
    /// The watched vertices' zones.
    pub zones: Vec<Zone>,
}

impl Zone {
    /// The ellipse's half axes (3σ) and the direction of the first, from the covariance's
    /// eigen decomposition.
    fn axes(&self) -> (f64, f64, Vector) {
        let [a, b, c] = self.covariance;
        let mean = 0.5 * (a + c);
        let root = libm::hypot(0.5 * (a - c), b);
        let (l1, l2) = ((mean + root).max(0.0), (mean - root).max(0.0));
        let theta = 0.5 * libm::atan2(2.0 * b, a - c);
        let (s, co) = libm::sincos(theta);
        (ELLIPSE_SIGMAS * libm::sqrt(l1), ELLIPSE_SIGMAS * libm::sqrt(l2), Vector::new(co, s))
    }

    /// Its largest half size: the ellipse's and the box's, about the nominal vertex.
    fn reach(&self) -> f64 {
        let (a, _, _) = self.axes();
        let ellipse = self.shift.norm() + a;
        let mc = self.mc.map_or(0.0, |(lo, hi)| lo.x.abs().max(lo.y.abs()).max(hi.x.abs()).max(hi.y.abs()));
        let r = ellipse.max(mc);
        if r.is_finite() { r } else { 0.0 }
    }

    /// The ellipse's points at magnification `m` (closed).
    fn ellipse(&self, m: f64) -> Vec<Point> {
        let (a, b, u) = self.axes();
        let v = Vector::new(-u.y, u.x);
        let centre = self.at + self.shift * m;
        (0..ELLIPSE_POINTS)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / ELLIPSE_POINTS as f64;
                let (s, c) = libm::sincos(t);
                centre + u * (m * a * c) + v * (m * b * s)
            })
            .collect()
    }
}

/// The triad's extent over every panel (pivots and vertices).
fn extent(panels: &[ZonePanel]) -> (Point, Point) {
    let pts = panels.iter().flat_map(|p| p.pivots.iter().chain(&p.vertices));
    pts.fold(
        (Point::new(f64::INFINITY, f64::INFINITY), Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY)),
        |(a, b), p| (Point::new(a.x.min(p.x), a.y.min(p.y)), Point::new(b.x.max(p.x), b.y.max(p.y))),
    )
}

/// Panel `p`'s magnification: `given`, else the nice value that draws its largest zone at
/// [`ZONE_SHARE`] of the triad's extent.
fn magnification(p: &ZonePanel, extent: f64, given: Option<f64>) -> f64 {
    given.unwrap_or_else(|| {
        let largest = p.zones.iter().map(Zone::reach).fold(0.0, f64::max);
        magnification_for(largest, extent * ZONE_SHARE / BAND_SHARE)
    })
}

/// Text of a deviation bar: mm for SI scenes; for mm scenes µm below 1 mm, else mm.
fn deviation_text(v: f64, units: ModelUnits) -> String {
    match units.length {
        "mm" if v < 1.0 => format!("{} µm", scale_text(v * 1000.0)),
        "mm" => format!("{} mm", scale_text(v)),
        _ => format!("{} mm", scale_text(v * 1000.0)),
    }
}

/// The heading's second line: the magnification.
fn magnification_text(m: f64) -> String {
    format!("deviations × {}: RSS 3σ ellipse, Monte Carlo 0.135–99.865 % box", scale_text(m))
}

/// The zones of every mode as small multiples (see the module docs); `magnification` as
/// given for every panel, else chosen per panel; `title` lines above.
pub fn zones_drawing(
    panels: &[ZonePanel],
    units: ModelUnits,
    magnification_given: Option<f64>,
    title: &[String],
) -> Drawing {
    let (lo, hi) = extent(panels);
    let size = if lo.x.is_finite() { (hi.x - lo.x).max(hi.y - lo.y).max(f64::MIN_POSITIVE) } else { 1.0 };
    let k_l = vocab::length_scale(size * 1.1, PANEL_MM);
    let s = Sizes::on_paper(k_l);
    let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let frames = d.layer("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    let mechanism = d.layer("MECHANISM", Aci::DARK_GREY, LineType::Continuous);
    let rss = d.layer("TOL_RSS", Aci::BLUE, LineType::Dashed);
    let mc = d.layer("TOL_MC", Aci::RED, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);

    let small = s.small_text();
    let (pad, gap) = (s.text, s.text);
    let mags: Vec<f64> = panels.iter().map(|p| magnification(p, size, magnification_given)).collect();
    // Content: the triad with its ground symbols and the magnified zones, a zone's name
    // beside it; the same box in every panel.
    let margin = mags
        .iter()
        .zip(panels)
        .map(|(m, p)| m * p.zones.iter().map(Zone::reach).fold(0.0, f64::max))
        .fold(0.0, f64::max)
        + 2.5 * s.text;
    let content = Bounds {
        min: lo - Vector::new(margin.max(1.3 * s.ground), margin.max(s.joint + 1.3 * s.ground)),
        max: hi + Vector::new(margin, margin),
    };
    let heading_base = pad + s.text;
    let mag_base = heading_base + 1.8 * small;
    let bar_base = mag_base + 2.4 * small;
    let header = bar_base + small + pad;
    let widest = panels.iter().zip(&mags).fold(0.0f64, |w, (p, m)| {
        w.max(widest_text_width(&p.heading, s.text)).max(widest_text_width(&magnification_text(*m), small))
    });
    let cell_w = content.width().max(widest) + 2.0 * pad;
    let cell_h = header + content.height() + pad;
    let columns = COLUMNS.min(panels.len()).max(1);
    let mut names = labels::Polygon::of_points();
    for (k, (p, m)) in panels.iter().zip(&mags).enumerate() {
        let (col, row) = (k % columns, k / columns);
        let top_left = Point::new(col as f64 * (cell_w + gap), -(row as f64) * (cell_h + gap));
        let off = Vector::new(top_left.x + pad - content.min.x, top_left.y - header - content.max.y);
        let corners = vec![
            top_left,
            top_left + Vector::new(cell_w, 0.0),
            top_left + Vector::new(cell_w, -cell_h),
            top_left + Vector::new(0.0, -cell_h),
        ];
        d.push(Entity {
            layer: frames,
            color: None,
            linetype: None,
            shape: Shape::Polyline { points: corners, closed: true, width: 0.0 },
        });
        let (o, a) = (p.pivots.map(|q| q + off), p.vertices.map(|q| q + off));
        for (o, a) in o.iter().zip(a) {
            vocab::link(&mut d, mechanism, vec![*o, a], false, None, s);
        }
        vocab::link(&mut d, mechanism, a.to_vec(), true, None, s);
        for q in o {
            vocab::ground(&mut d, mechanism, q, s);
        }
        let centroid = Point::from((a[0].coords + a[1].coords + a[2].coords) / 3.0);
        for z in &p.zones {
            let z = Zone { at: z.at + off, ..z.clone() };
            d.add(rss, Shape::Polyline { points: z.ellipse(*m), closed: true, width: 0.0 });
            if let Some((lo, hi)) = z.mc {
                let (lo, hi) = (z.at + lo * *m, z.at + hi * *m);
                let points = vec![lo, Point::new(hi.x, lo.y), hi, Point::new(lo.x, hi.y)];
                d.add(mc, Shape::Polyline { points, closed: true, width: 0.0 });
            }
            // The name outside the triangle, clear of the zone.
            let out = z.at - centroid;
            let dir = if out.norm() > 0.0 { out / out.norm() } else { Vector::new(1.0, 0.0) };
            names.letter_clear(z.at, &z.name, s.text, dir, m * z.reach() + 0.3 * s.text);
        }
        let x = top_left.x + pad;
        d.text(text, Point::new(x, top_left.y - heading_base), s.text, p.heading.clone());
        d.text(text, Point::new(x, top_left.y - mag_base), small, magnification_text(*m));
        // The panel's deviation bar: a nice deviation drawn m times longer.
        let dev = nice_scale(vocab::BAR_MM * k_l / m);
        let at = Point::new(x + 0.5 * small, top_left.y - bar_base);
        scale_bar(&mut d, text, at, dev * m, &format!("{} deviation", deviation_text(dev, units)), s);
    }
    names.keep_off_drawing(&d);
    names.draw(&mut d, text);
    let scale_top = Point::new(0.0, gap + 3.0 * small);
    length_scale_block(&mut d, text, scale_top, k_l, units, s);
    let lines = title.len().saturating_sub(1) as f64;
    caption(&mut d, text, Point::new(0.0, scale_top.y + gap + 0.3 * s.text + 1.8 * s.text * lines), title, s.text);
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ellipse_axes_are_the_covariance_eigenvalues() {
        // σx = 2, σy = 1, rotated by 30°.
        let (t, sx, sy) = (30f64.to_radians(), 2.0, 1.0);
        let (s, c) = libm::sincos(t);
        let xx = c * c * sx * sx + s * s * sy * sy;
        let yy = s * s * sx * sx + c * c * sy * sy;
        let xy = c * s * (sx * sx - sy * sy);
        let z =
            Zone { name: "A1".into(), at: Point::origin(), shift: Vector::zeros(), covariance: [xx, xy, yy], mc: None };
        let (a, b, u) = z.axes();
        assert!((a - 6.0).abs() < 1e-12 && (b - 3.0).abs() < 1e-12, "{a} {b}");
        assert!((u.x - c).abs() < 1e-12 && (u.y - s).abs() < 1e-12);
        // Every drawn point on the 3σ ellipse: dᵀ C⁻¹ d = 9.
        let det = xx * yy - xy * xy;
        for p in z.ellipse(1.0) {
            let q = (yy * p.x * p.x - 2.0 * xy * p.x * p.y + xx * p.y * p.y) / det;
            assert!((q - 9.0).abs() < 1e-9, "{q}");
        }
    }
}
