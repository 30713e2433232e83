//! What a teacher adds next to the four-bar's run (issue 14, item 10): the transmission
//! angle's diagram with γ_min marked, the instantaneous centres with Kennedy's lines on a
//! sheet, and Joukowski's lever as a graphical check of Me1 (a JSON and CSV value per
//! position, and a sheet). The numbers come from `solve::fourbar::{transmission, centres,
//! joukowski}`, the drawings from `figure::{centres, joukowski}`; [`super::fourbar`] calls
//! these and adds their products.

use serde_json::{Value, json};

use super::products::Sheet;
use crate::draw::Bounds;
use crate::figure::fourbar::centres::centres_sheet;
use crate::figure::fourbar::joukowski::{LeverPanel, LeverUnits, joukowski_sheet};
use crate::figure::fourbar::{ModelUnits, angle_text};
use crate::figure::shared::plot::{Level, Mark, Marks};
use crate::figure::shared::vocab::length_scale;
use crate::geom::{Point, Vector, deg};
use crate::report::Csv;
use crate::solve::fourbar::joukowski::{Lever, lever};
use crate::solve::fourbar::transmission::{GAMMA_LIMIT_DEG, GammaMin};
use crate::solve::fourbar::{Forces, Geometry, MotionSpec, Position};

/// Crank angles (degrees) of the Joukowski sheet's panels: 135° and 200° (the issue's
/// hand-checked angle), both with the template's load F acting and a coupler that turns
/// (at 90° the template's coupler translates, ω2 = 0, and a, b, m fall on one point);
/// the solved position nearest to each is drawn, once.
pub const LEVER_ANGLES_DEG: [f64; 2] = [135.0, 200.0];
/// Crank angles (degrees) of the centres sheet's panels: one in each quadrant, where the
/// template's I20 and I13 lie near the mechanism and apart from the joints (at 0° and 180°
/// I20 falls on C and I13 on A, at 45° I20 on B, at 90° I20 is at infinity).
pub const CENTRE_ANGLES_DEG: [f64; 4] = [30.0, 150.0, 240.0, 330.0];

/// The γ diagram's marks: the usual limit as a dashed line, γ_min marked with its value.
pub fn gamma_marks(min: Option<GammaMin>) -> Marks {
    Marks {
        levels: vec![Level { y: GAMMA_LIMIT_DEG, label: format!("usual limit {}°", angle_text(GAMMA_LIMIT_DEG)) }],
        points: min.map(|m| Mark { x: m.phi1_deg, y: m.gamma_deg, label: gamma_min_text(&m) }).into_iter().collect(),
    }
}

/// `γ_min = 23.07° at φ1 = 0°`.
pub fn gamma_min_text(m: &GammaMin) -> String {
    format!("γ_min = {:.2}° at φ1 = {}°", m.gamma_deg, angle_text(m.phi1_deg))
}

/// The warning when γ_min is below the usual limit.
pub fn gamma_warning(m: &GammaMin) -> Option<String> {
    m.below_limit().then(|| {
        format!(
            "transmission angle {} is below the usual {}° limit: the coupler drives the rocker poorly there",
            gamma_min_text(m),
            angle_text(GAMMA_LIMIT_DEG)
        )
    })
}

/// Joukowski's lever at every position (`None` where a position has no kinematics), when
/// the scene has dynamics.
pub fn levers(spec: &MotionSpec, positions: &[Position]) -> Vec<Option<Lever>> {
    let Some(dynamics) = spec.dynamics.as_ref() else { return Vec::new() };
    positions.iter().map(|p| p.kin.map(|k| lever(&spec.geometry, p, &k, dynamics, spec.omega1))).collect()
}

/// Me1_J of each lever: `None` where a position has no lever (no kinematics: a singular
/// position). A standing crank has one (virtual velocities: `solve::fourbar::joukowski`).
fn me1_values(levers: &[Option<Lever>]) -> Vec<Option<f64>> {
    levers.iter().map(|l| l.as_ref().and_then(|l| l.me1).filter(|v| v.is_finite())).collect()
}

/// Adds `me1_joukowski` to the CSV (after `Me1`, the last column; an empty field where a
/// position has no lever) and to each JSON position record (`null` there), and
/// `gamma_min_deg`, `gamma_min_phi1_deg` to the summary.
pub fn add_to_tables(csv: &mut Csv, summary: &mut Value, levers: &[Option<Lever>], gamma: Option<GammaMin>) {
    if !levers.is_empty() {
        let values = me1_values(levers);
        csv.column_opt("me1_joukowski", &values);
        if let Some(records) = summary.get_mut("positions").and_then(Value::as_array_mut) {
            for (r, v) in records.iter_mut().zip(&values) {
                if let Some(o) = r.as_object_mut() {
                    o.insert("me1_joukowski".into(), v.map_or(Value::Null, |v| json!(v)));
                }
            }
        }
    }
    if let (Some(m), Some(o)) = (gamma, summary.as_object_mut()) {
        o.insert("gamma_min_deg".into(), json!(m.gamma_deg));
        o.insert("gamma_min_phi1_deg".into(), json!(m.phi1_deg));
    }
}

/// Index of the solved position nearest to each angle of `angles` (modulo 360°), each
/// position once, in the order of `angles`.
fn nearest(positions: &[Position], angles: &[f64]) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for &a in angles {
        let dist = |p: &Position| {
            let d = (deg(p.phi1) - a).rem_euclid(360.0);
            d.min(360.0 - d)
        };
        let best = positions.iter().enumerate().min_by(|(_, p), (_, q)| dist(p).total_cmp(&dist(q))).map(|(i, _)| i);
        if let Some(i) = best
            && !out.contains(&i)
        {
            out.push(i);
        }
    }
    out
}

/// Largest extent of the mechanism's motion in a centres panel, paper millimetres.
const CENTRES_PANEL_MM: f64 = 80.0;

/// The mechanism's extent over the motion (O1, C and every A, B, M), padded for letters.
fn mechanism_window(geom: &Geometry, positions: &[Position]) -> (Bounds, f64) {
    let mut min = geom.o1.coords.inf(&geom.c.coords);
    let mut max = geom.o1.coords.sup(&geom.c.coords);
    for p in positions {
        for q in [p.a, p.b, p.m] {
            min = min.inf(&q.coords);
            max = max.sup(&q.coords);
        }
    }
    let size = (max - min).amax().max(geom.l1.max(geom.l_bc));
    let pad = 0.3 * size;
    (Bounds { min: Point::from(min - Vector::new(pad, pad)), max: Point::from(max + Vector::new(pad, pad)) }, size)
}

/// The centres sheet (`<name>-centres`) at [`CENTRE_ANGLES_DEG`].
pub fn centres(geom: &Geometry, positions: &[Position], units: ModelUnits) -> Option<Sheet> {
    if positions.is_empty() {
        return None;
    }
    let (window, size) = mechanism_window(geom, positions);
    let chosen: Vec<&Position> = nearest(positions, &CENTRE_ANGLES_DEG).into_iter().map(|i| &positions[i]).collect();
    let drawing = centres_sheet(geom, &chosen, window, length_scale(size, CENTRES_PANEL_MM), units);
    Some(Sheet { suffix: "centres".into(), drawing })
}

/// The Joukowski sheet (`<name>-joukowski`) at [`LEVER_ANGLES_DEG`].
pub fn joukowski(
    spec: &MotionSpec,
    positions: &[Position],
    forces: &[Forces],
    levers: &[Option<Lever>],
    units: ModelUnits,
) -> Option<Sheet> {
    let (_, size) = mechanism_window(&spec.geometry, positions);
    let panels: Vec<LeverPanel> = nearest(positions, &LEVER_ANGLES_DEG)
        .into_iter()
        .filter_map(|i| {
            Some(LeverPanel {
                phi1_deg: deg(positions[i].phi1),
                lever: levers.get(i)?.as_ref()?,
                me1_reactions: forces.get(i)?.me1,
                omega1: spec.omega1,
            })
        })
        .collect();
    if panels.is_empty() {
        return None;
    }
    let moment = if units.length == "m" { "N·m" } else { "N·mm" };
    let drawing = joukowski_sheet(&panels, LeverUnits { model: units, moment }, size);
    Some(Sheet { suffix: "joukowski".into(), drawing })
}
