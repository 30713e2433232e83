//! The polygon panels of a printed sheet, for any mechanism (issue 15 §3: one figure
//! pipeline; the four-bar's and the linkage's sheets both draw through here): each polygon
//! at its own nice scale on each page ([`crate::figure::shared::sheet::fit`]: it fills about two thirds of
//! its panel, at least half), centred in its panel; the force figures side by side in rows
//! of up to [`FIGURES_PER_ROW`] at one scale; a scale bar at the foot of every panel.

use crate::draw::Drawing;
use crate::geom::{Point, Vector};

use crate::figure::shared::forces::{self, ForcePolygon};
use crate::figure::shared::polygon::{self, PointPolygon};
use crate::figure::shared::sheet::{self, Fit, SheetLayout};
use crate::figure::shared::vocab::{ModelUnits, Scale, bar_value, layer_of, layers, scale_bar, scale_text};

/// Gap between force figures on a sheet, in the largest figure's extents.
pub const FIGURE_GAP: f64 = 0.15;
/// Room left between a polygon and its panel's edges for the letters at its outer points,
/// in letter heights.
pub const LETTER_ROOM: f64 = 1.5;
/// Room between force figures on a sheet for their names, in letter heights.
pub const NAME_ROOM: f64 = 3.0;
/// Force figures in one row of the force panel.
pub const FIGURES_PER_ROW: usize = 3;

/// The scales of one page: physical units per paper millimetre (`None`: not drawn).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PageScales {
    /// k_l, model length units per paper mm (the same on every page of a run).
    pub k_l: f64,
    /// k_v, (length unit/s) per mm.
    pub k_v: Option<f64>,
    /// k_a, (length unit/s²) per mm.
    pub k_a: Option<f64>,
    /// k_f, N per mm.
    pub k_f: Option<f64>,
}

/// Which polygon panels a sheet has (after the mechanism's, in this order).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Shown {
    /// The velocity polygon's panel.
    pub velocity: bool,
    /// The acceleration polygon's panel.
    pub acceleration: bool,
    /// The force panel.
    pub forces: bool,
}

impl Shown {
    /// The number of polygon panels.
    pub fn count(&self) -> usize {
        [self.velocity, self.acceleration, self.forces].iter().filter(|s| **s).count()
    }
}

/// One page's polygons.
#[derive(Debug, Clone, Copy, Default)]
pub struct PagePolygons<'a> {
    /// The velocity polygon, when drawn at this position.
    pub velocity: Option<&'a PointPolygon>,
    /// The acceleration polygon.
    pub acceleration: Option<&'a PointPolygon>,
    /// The force figures.
    pub forces: Option<&'a [ForcePolygon]>,
}

/// The polygons of one page fitted to their panels: each polygon's fit and pole, the force
/// figures' shifts from the first figure's pole (physical units).
#[derive(Debug, Clone)]
pub struct PageFit {
    velocity: Option<(Fit, Point)>,
    acceleration: Option<(Fit, Point)>,
    forces: Option<(Fit, Point)>,
    shifts: Vec<Vector>,
}

/// The room a polygon is fitted to in a panel's `area`: [`LETTER_ROOM`] letter heights less
/// each way, for the letters at its outer points.
fn letter_room(area: crate::draw::Bounds, s: crate::figure::shared::vocab::Sizes) -> Vector {
    let room = 2.0 * LETTER_ROOM * s.text;
    Vector::new((area.width() - room).max(0.5 * area.width()), (area.height() - room).max(0.5 * area.height()))
}

/// The smallest box holding the finite vectors of `vs`.
fn extent(vs: impl IntoIterator<Item = Vector>) -> Option<(Vector, Vector)> {
    vs.into_iter()
        .filter(|v| v.x.is_finite() && v.y.is_finite())
        .fold(None, |e, v| Some(e.map_or((v, v), |(lo, hi): (Vector, Vector)| (lo.inf(&v), hi.sup(&v)))))
}

/// Where each force figure's pole goes relative to the first's (physical units): side by
/// side, tops aligned, [`FIGURE_GAP`] of the largest figure apart (at least `min_gap`), in
/// rows of [`FIGURES_PER_ROW`] from the top.
fn figure_shifts(figures: &[ForcePolygon], min_gap: f64) -> Vec<Vector> {
    let extents: Vec<Option<(Vector, Vector)>> = figures.iter().map(|f| extent(f.physical_points())).collect();
    let size = extents.iter().flatten().map(|(lo, hi)| (hi - lo).amax()).fold(0.0, f64::max);
    let gap = (FIGURE_GAP * size).max(min_gap);
    let mut shifts = Vec::with_capacity(figures.len());
    let (Some(Some((_, hi0))), true) = (extents.first(), !figures.is_empty()) else {
        return vec![Vector::zeros(); figures.len()];
    };
    let (mut right, mut top, mut row_bottom) = (0.0, hi0.y, f64::INFINITY);
    for (i, e) in extents.iter().enumerate() {
        let Some((lo, hi)) = e else {
            shifts.push(Vector::zeros());
            continue;
        };
        if i == 0 {
            shifts.push(Vector::zeros());
            right = hi.x;
            row_bottom = lo.y;
            continue;
        }
        if i % FIGURES_PER_ROW == 0 {
            // A new row under the last one, from the first figure's left.
            top = row_bottom - gap;
            let lo0 = extents[0].map_or(Vector::zeros(), |(lo, _)| lo);
            let shift = Vector::new(lo0.x - lo.x, top - hi.y);
            right = hi.x + shift.x;
            row_bottom = lo.y + shift.y;
            shifts.push(shift);
            continue;
        }
        let shift = Vector::new(right - lo.x + gap, top - hi.y);
        right = hi.x + shift.x;
        row_bottom = row_bottom.min(lo.y + shift.y);
        shifts.push(shift);
    }
    shifts
}

impl PageFit {
    /// Fits the polygons of one page into the panels of `layout` after the mechanism's.
    pub fn new(layout: &SheetLayout, shown: Shown, polys: PagePolygons) -> PageFit {
        let mut panels = layout.panels.iter().skip(1);
        let mut fitted = |on: bool, pts: Option<Vec<Vector>>| -> Option<(Fit, Point)> {
            let panel = if on { panels.next() } else { None }?;
            let (lo, hi) = extent(pts?)?;
            let f = sheet::fit(hi - lo, letter_room(panel.area, layout.sizes));
            Some((f, sheet::centre(lo, hi, f.per_mm, panel.area)))
        };
        let velocity = fitted(shown.velocity, polys.velocity.map(PointPolygon::physical_points));
        let acceleration = fitted(shown.acceleration, polys.acceleration.map(PointPolygon::physical_points));
        // The figures at a first gap; then, at the scale that gives, at least
        // [`NAME_ROOM`] letter heights between them for their names, and fitted again.
        let all = |shifts: &[Vector]| {
            polys.forces.map(|figs| {
                figs.iter().zip(shifts).flat_map(|(f, s)| f.physical_points().into_iter().map(move |v| v + s)).collect()
            })
        };
        let force_panel = if shown.forces {
            layout.panels.iter().skip(1).nth(shown.velocity as usize + shown.acceleration as usize)
        } else {
            None
        };
        let mut shifts = polys.forces.map(|f| figure_shifts(f, 0.0)).unwrap_or_default();
        let mut forces = fitted(shown.forces, all(&shifts));
        if let (Some((first, _)), Some(figs)) = (forces, polys.forces) {
            let room = NAME_ROOM * layout.sizes.text * first.per_mm;
            let wider = figure_shifts(figs, room);
            if wider != shifts {
                shifts = wider;
                forces = force_panel.and_then(|panel| {
                    let (lo, hi) = extent(all(&shifts)?)?;
                    let f = sheet::fit(hi - lo, letter_room(panel.area, layout.sizes));
                    Some((f, sheet::centre(lo, hi, f.per_mm, panel.area)))
                });
            }
        }
        PageFit { velocity, acceleration, forces, shifts }
    }

    /// The page's scales, with the run's `k_l`.
    pub fn scales(&self, k_l: f64) -> PageScales {
        PageScales {
            k_l,
            k_v: self.velocity.map(|(f, _)| f.per_mm),
            k_a: self.acceleration.map(|(f, _)| f.per_mm),
            k_f: self.forces.map(|(f, _)| f.per_mm),
        }
    }

    /// Draws the polygons in their panels, each at its scale (the drawing in paper mm).
    pub fn draw(&self, d: &mut Drawing, polys: PagePolygons, s: crate::figure::shared::vocab::Sizes) {
        if let (Some(poly), Some((f, pole))) = (polys.velocity, self.velocity) {
            polygon::draw(d, poly, layers::VELOCITY, Scale::on_paper(f.per_mm, 1.0), pole, s);
        }
        if let (Some(poly), Some((f, pole))) = (polys.acceleration, self.acceleration) {
            polygon::draw(d, poly, layers::ACCELERATION, Scale::on_paper(f.per_mm, 1.0), pole, s);
        }
        if let (Some(figs), Some((f, pole))) = (polys.forces, self.forces) {
            let scale = Scale::on_paper(f.per_mm, 1.0);
            let mut names = Vec::new();
            for (fig, shift) in figs.iter().zip(&self.shifts) {
                let at = if *shift == Vector::zeros() { pole } else { pole + scale.draw(*shift) };
                let placed = forces::draw(d, fig, scale, at, s, &names);
                names.extend(placed);
            }
        }
    }
}

/// The title of each panel and the title block's scale cells, for `scales` (the polygons'
/// `None` when not drawn on this page): (panel titles, cells).
pub fn titles(scales: &PageScales, shown: Shown, units: ModelUnits) -> (Vec<String>, Vec<String>) {
    let len = units.length;
    let k_texts: Vec<(&str, Option<f64>, String)> = vec![
        ("k_v", scales.k_v, format!("({len}/s)/mm")),
        ("k_a", scales.k_a, format!("({len}/s²)/mm")),
        ("k_f", scales.k_f, "N/mm".to_string()),
    ];
    let on = [shown.velocity, shown.acceleration, shown.forces];
    let scale_cell = |n: &str, v: Option<f64>, u: &str| match v {
        Some(v) => format!("{n} = {} {u}", scale_text(v)),
        None => format!("{n} –"),
    };
    let k_l_text = format!("k_l = {} {len}/mm", scale_text(scales.k_l));
    let mut titles = vec![format!("Mechanism   {k_l_text}")];
    let mut cells = vec![k_l_text];
    for (((n, v, u), on), title) in
        k_texts.iter().zip(on).zip(["Velocity polygon", "Acceleration polygon", "Force polygons"])
    {
        if on {
            titles.push(format!("{title}   {}", scale_cell(n, *v, u)));
            cells.push(scale_cell(n, *v, u));
        }
    }
    (titles, cells)
}

/// A scale bar at the foot of every panel: the mechanism's in the scene's length unit,
/// each polygon's at this page's scale.
pub fn scale_bars(d: &mut Drawing, layout: &SheetLayout, scales: &PageScales, shown: Shown, units: ModelUnits) {
    let len = units.length;
    let s = layout.sizes;
    let dims = layer_of(d, layers::DIMENSIONS);
    let mut panels = layout.panels.iter();
    let per_mm = [
        (true, Some(scales.k_l), len.to_string()),
        (shown.velocity, scales.k_v, format!("{len}/s")),
        (shown.acceleration, scales.k_a, format!("{len}/s²")),
        (shown.forces, scales.k_f, "N".to_string()),
    ];
    for (on, k, unit) in per_mm {
        let panel = if on { panels.next() } else { None };
        if let (Some(panel), Some(k)) = (panel, k) {
            let value = bar_value(k);
            scale_bar(d, dims, panel.bar_at(s), value / k, &format!("{} {unit}", scale_text(value)), s);
        }
    }
}
