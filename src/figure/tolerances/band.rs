//! The band drawing: each watched point's nominal path (the coupler curve) with the
//! envelopes of its deviation normal to the path — the RSS band (±3σ) and the Monte Carlo's
//! 0.135 % and 99.865 % points — offset from the path by the deviation × a magnification
//! stated on the drawing, the widest position marked, the mechanism at its first position
//! in thin lines for orientation. Drawn in model units at a nice length scale with its
//! scale bar, and a second bar for the magnified deviations. The same drawing is the DXF of
//! the envelope curves (layers `TOL_NOMINAL`, `TOL_RSS`, `TOL_MC`).

use crate::draw::{Aci, DimStyle, Drawing, HAlign, LineType, Shape, VAlign};
use crate::figure::shared::labels;
use crate::figure::shared::vocab::{self, ModelUnits, Sizes, length_scale, nice_scale, scale_bar, scale_text};
use crate::geom::{Point, Vector};

/// Paper length the drawing's longer side is scaled to, millimetres (A4 landscape's
/// drawing area).
pub const TARGET_MM: f64 = 220.0;
/// The largest magnified deviation as a fraction of the drawing's extent, when the
/// magnification is chosen.
pub const BAND_SHARE: f64 = 0.06;

/// One watched point's path and bands (deviations along the path's normal, model units).
#[derive(Debug, Clone, PartialEq)]
pub struct BandPath {
    /// The point's name (`M`).
    pub name: String,
    /// Its nominal positions.
    pub nominal: Vec<Point>,
    /// The unit normal of the path at each position (zero where undefined).
    pub normals: Vec<Vector>,
    /// The RSS half band (3σ) at each position (`None` at a dead point).
    pub rss: Vec<Option<f64>>,
    /// The Monte Carlo's 0.135 % and 99.865 % deviations (`None` without samples).
    pub mc: Vec<Option<(f64, f64)>>,
    /// The widest position, with its label (`φ1 = 123°`).
    pub worst: Option<(usize, String)>,
}

/// The magnification that draws the largest deviation `largest` (model units) at
/// [`BAND_SHARE`] of `extent`: a nice value (1, 2, 2.5, 5 × 10ᵏ), at least 1.
pub fn magnification_for(largest: f64, extent: f64) -> f64 {
    if !(largest > 0.0 && largest.is_finite()) {
        return 1.0;
    }
    let raw = BAND_SHARE * extent / largest;
    // The nice value at or below raw.
    let mag = libm::pow(10.0, libm::log10(raw).floor());
    let mut m = mag;
    for f in [1.0, 2.0, 2.5, 5.0] {
        if f * mag <= raw * (1.0 + 1e-12) {
            m = f * mag;
        }
    }
    m.max(1.0)
}

/// Text of a deviation bar: the value in the smaller unit (µm for mm scenes, mm for SI).
fn deviation_text(v: f64, units: ModelUnits) -> String {
    match units.length {
        "m" => format!("{} mm", scale_text(v * 1000.0)),
        _ => format!("{} µm", scale_text(v * 1000.0)),
    }
}

/// The band drawing of `paths` with the mechanism `sketch` (segments at its first
/// position); `magnification` as given (else chosen), `title` above.
pub fn band_drawing(
    paths: &[BandPath],
    sketch: &[(Point, Point)],
    units: ModelUnits,
    magnification: Option<f64>,
    title: &str,
) -> Drawing {
    let mut pts: Vec<Point> = paths.iter().flat_map(|p| p.nominal.iter().copied()).collect();
    pts.extend(sketch.iter().flat_map(|(a, b)| [*a, *b]));
    let (lo, hi) = pts.iter().fold(
        (Point::new(f64::INFINITY, f64::INFINITY), Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY)),
        |(a, b), p| (Point::new(a.x.min(p.x), a.y.min(p.y)), Point::new(b.x.max(p.x), b.y.max(p.y))),
    );
    let extent = if lo.x.is_finite() { (hi.x - lo.x).max(hi.y - lo.y).max(f64::MIN_POSITIVE) } else { 1.0 };
    let largest = paths
        .iter()
        .flat_map(|p| {
            p.rss.iter().flatten().copied().chain(p.mc.iter().flatten().flat_map(|(a, b)| [a.abs(), b.abs()]))
        })
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let m = magnification.unwrap_or_else(|| magnification_for(largest, extent));
    let k_l = length_scale(extent * 1.15, TARGET_MM);
    let s = Sizes::on_paper(k_l);
    let mut d = Drawing::new(DimStyle { text_height: s.text, arrow_size: s.head });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let mech = d.layer("MECHANISM", Aci::DARK_GREY, LineType::Continuous);
    let nominal = d.layer("TOL_NOMINAL", Aci::BLACK, LineType::Continuous);
    let rss = d.layer("TOL_RSS", Aci::BLUE, LineType::Dashed);
    let mc = d.layer("TOL_MC", Aci::RED, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);
    for (a, b) in sketch {
        d.add(mech, Shape::Line { from: *a, to: *b });
        for p in [a, b] {
            d.add(mech, Shape::Circle { center: *p, radius: 0.25 * s.joint });
        }
    }
    for p in paths {
        let n = p.nominal.len();
        vocab::path(&mut d, nominal, p.nominal.clone());
        let off = |k: usize, v: f64| p.nominal[k] + p.normals[k] * (m * v);
        for pick in [0, 1] {
            runs(
                &mut d,
                mc,
                (0..n).map(|k| {
                    p.mc[k].filter(|_| p.normals[k].norm() > 0.0).map(|(a, b)| off(k, if pick == 0 { a } else { b }))
                }),
            );
        }
        // The RSS band over the Monte Carlo's (dashed: where they agree, both show).
        for side in [1.0, -1.0] {
            runs(&mut d, rss, (0..n).map(|k| p.rss[k].filter(|_| p.normals[k].norm() > 0.0).map(|v| off(k, side * v))));
        }
        if let Some((k, lab)) = &p.worst {
            let (k, nrm) = (*k, p.normals[*k]);
            let half = p.mc[k].map(|(a, b)| a.abs().max(b.abs())).or(p.rss[k]).unwrap_or(0.0);
            let reach = (m * half).max(2.0 * s.text);
            let (a, b) = (p.nominal[k] - nrm * reach, p.nominal[k] + nrm * reach);
            d.add_colored(text, Aci::RED, Shape::Line { from: a, to: b });
            d.add_colored(text, Aci::RED, Shape::Circle { center: p.nominal[k], radius: 0.3 * s.text });
            let tip = if nrm.norm() > 0.0 { b + nrm * (0.5 * s.text) } else { p.nominal[k] };
            let halign = if nrm.x >= 0.0 { HAlign::Left } else { HAlign::Right };
            d.add(text, label(tip, &format!("widest: {lab}"), s.small_text(), halign));
        }
    }
    // Each point's name beside its path's last position, placed clear of the paths, bands
    // and marks (the letter placer: the free side of the path first).
    let mut names = labels::Polygon::of_points();
    names.keep_off_drawing(&d);
    for p in paths {
        if let (Some(q), Some(n)) = (p.nominal.last(), p.normals.last()) {
            names.letter_clear(*q, &p.name, s.text, *n, 0.3 * s.text);
        }
    }
    names.draw(&mut d, text);
    // Title and legend above, scale bars below.
    let top = hi.y + 0.08 * extent;
    d.add(
        text,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: Point::new(lo.x, top + 2.2 * s.text),
            height: s.text,
            value: title.to_string(),
            halign: HAlign::Left,
            valign: VAlign::Baseline,
            rotation: 0.0,
        },
    );
    let legend = format!(
        "deviations normal to the path × {}: RSS ±3σ dashed blue, Monte Carlo 0.135 % and 99.865 % red",
        scale_text(m)
    );
    d.add(text, label(Point::new(lo.x, top + 0.6 * s.text), &legend, s.small_text(), HAlign::Left));
    let bar_y = lo.y - 0.08 * extent - s.text;
    let bar = vocab::bar_value(k_l);
    scale_bar(&mut d, text, Point::new(lo.x + s.text, bar_y), bar, &format!("{} {}", scale_text(bar), units.length), s);
    let k_text = vocab::length_scale_text(k_l, units);
    let mut k_label = label(Point::new(lo.x, bar_y - 2.0 * s.text), &k_text, s.small_text(), HAlign::Left);
    if let Shape::Text { runs, .. } = &mut k_label {
        // k_l: a subscript l.
        *runs = crate::draw::Runs::underscored(&k_text);
    }
    d.add(text, k_label);
    // The deviation bar: a nice deviation drawn m times longer.
    let dev = nice_scale(vocab::BAR_MM * k_l / m);
    let x0 = lo.x + 0.55 * extent;
    scale_bar(&mut d, text, Point::new(x0, bar_y), dev * m, &format!("{} deviation", deviation_text(dev, units)), s);
    d
}

fn label(at: Point, s: &str, h: f64, halign: HAlign) -> Shape {
    Shape::Text {
        runs: crate::draw::Runs::flat(),
        at,
        height: h,
        value: s.to_string(),
        halign,
        valign: VAlign::Middle,
        rotation: 0.0,
    }
}

/// Polylines through the runs of defined points.
fn runs(d: &mut Drawing, layer: usize, points: impl Iterator<Item = Option<Point>>) {
    let mut run: Vec<Point> = Vec::new();
    let flush = |run: &mut Vec<Point>, d: &mut Drawing| {
        if run.len() >= 2 {
            vocab::path(d, layer, std::mem::take(run));
        }
        run.clear();
    };
    for p in points {
        match p.filter(|p| p.x.is_finite() && p.y.is_finite()) {
            Some(p) => run.push(p),
            None => flush(&mut run, d),
        }
    }
    flush(&mut run, d);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chosen_magnification_is_nice_and_keeps_the_band_small() {
        let m = magnification_for(1e-4, 0.3);
        // 0.06 · 0.3 / 1e-4 = 180 → 100.
        assert_eq!(m, 100.0);
        assert_eq!(magnification_for(0.0, 1.0), 1.0);
        assert_eq!(magnification_for(1.0, 1.0), 1.0);
    }
}
