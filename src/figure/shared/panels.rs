//! The graph-analytical frame of any mechanism (issue 15 §3: one figure pipeline): the
//! mechanism's panel and, beside it, the velocity polygon's, the acceleration polygon's and
//! the force panel (one force polygon per isolated group or body, captioned, and a table of
//! magnitudes), each panel titled with its scale and carrying a scale bar. The four-bar
//! kind and the linkage kind both draw their frames through [`PanelFrame`]: they describe
//! their polygons as [`PointPolygon`]s and [`ForcePolygon`]s and draw their own mechanism in
//! the first panel; the panels, scales, titles, bars, captions and the polygons' drawing
//! are here, once.
//!
//! # Layout and scales
//! One [`PanelFrame`] is computed per run from every position, so all frames share one
//! window and one set of scales and an animation does not jump. The mechanism is drawn at a
//! length scale k_l (model units per paper millimetre, a nice value 1, 2, 2.5, 5 × 10ᵏ) that
//! draws its motion at most `mechanism_mm` long on paper; the drawings carry
//! `paper_mm_per_unit = 1/k_l`. Each polygon's panel is about as large on paper as the
//! mechanism (or a stated size), at a nice scale per printed millimetre (`k_v = 0.01 (m/s)/mm`: one measured
//! millimetre stands for 0.01 m/s) chosen from the largest polygon over the motion. Panels
//! sit in a grid: up to three in a row, four as 2 × 2. The force panel holds its figures in
//! rows of up to [`FORCE_ROW`] items (the figures, then the table), each figure hanging from
//! the top of its row under its caption.

use crate::draw::parts::widest_text_width;
use crate::draw::{Bounds, DimStyle, Drawing, HAlign, ScaleCaption, Shape, VAlign};
use crate::geom::{Point, Vector};

use crate::figure::shared::forces::{self, ForcePolygon, Magnitude};
use crate::figure::shared::labels;
use crate::figure::shared::polygon::{self, PointPolygon};
use crate::figure::shared::vocab::{
    ModelUnits, Scale, Sizes, bar_value, caption_width, content_drawing, layer_of, layers, length_caption,
    length_scale, nice_scale, scale_bar, scale_bar_room, scale_text,
};

/// Gap between panels on paper, millimetres.
pub const PANEL_GAP_MM: f64 = 10.0;
/// Items (force figures and the table) in one row of the force panel.
pub const FORCE_ROW: usize = 3;
/// Caption of the table of magnitudes.
pub const TABLE_CAPTION: &str = "Magnitudes";

/// Bounding box of physical vectors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// Lower-left.
    pub min: Vector,
    /// Upper-right.
    pub max: Vector,
}

impl Extent {
    /// The box of the finite vectors of `vs` (`None` for none).
    pub fn of(vs: impl IntoIterator<Item = Vector>) -> Option<Extent> {
        let mut e: Option<Extent> = None;
        for v in vs {
            if !(v.x.is_finite() && v.y.is_finite()) {
                continue;
            }
            e = Some(match e {
                None => Extent { min: v, max: v },
                Some(e) => Extent { min: e.min.inf(&v), max: e.max.sup(&v) },
            });
        }
        e
    }

    /// The box holding both.
    pub fn union(a: Option<Extent>, b: Option<Extent>) -> Option<Extent> {
        match (a, b) {
            (Some(a), Some(b)) => Some(Extent { min: a.min.inf(&b.min), max: a.max.sup(&b.max) }),
            (a, None) => a,
            (None, b) => b,
        }
    }

    /// The larger side.
    pub fn size(&self) -> f64 {
        (self.max - self.min).amax()
    }
}

/// The force panel asked of a [`PanelFrame`]: its figures over the whole motion.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceSpec {
    /// Each figure's caption and the extent of its points over the motion (relative to its
    /// pole, N), in the order they are drawn.
    pub figures: Vec<(String, Option<Extent>)>,
    /// The rows of the table at every position (for its width).
    pub rows: Vec<Magnitude>,
    /// The number of rows of the table at one position.
    pub row_count: usize,
    /// Every force drawn on the mechanism over the motion: where it acts and the force
    /// (N), so that the mechanism's panel holds their arrows and names.
    pub on_mechanism: Vec<(Point, Vector)>,
}

/// What a [`PanelFrame`] is made from: the mechanism's motion and what is drawn beside it.
#[derive(Debug, Clone)]
pub struct PanelSpec {
    /// The model's units.
    pub units: ModelUnits,
    /// Extent of the mechanism over the motion (model units).
    pub mechanism: Extent,
    /// The length k_l is chosen from (at least the extent's larger side).
    pub size: f64,
    /// The longest the mechanism's motion is drawn on paper, millimetres.
    pub mechanism_mm: f64,
    /// The size of each polygon's panel on paper, millimetres (`None`: as large as the
    /// mechanism is drawn).
    pub polygon_mm: Option<f64>,
    /// Room (model units) around the mechanism for its symbols and letters, and extra room
    /// under it (above its scale bar), from the sizes at the chosen k_l.
    pub pad: fn(Sizes) -> (f64, f64),
    /// The widest text written right of the mechanism's title (`φ1 = 359.999°`).
    pub position_text: String,
    /// Every point of the velocity polygon over the motion (relative to the pole), when
    /// drawn.
    pub velocity: Option<Vec<Vector>>,
    /// Every point of the acceleration polygon over the motion, when drawn.
    pub acceleration: Option<Vec<Vector>>,
    /// The force panel, when drawn.
    pub forces: Option<ForceSpec>,
}

/// The force panel as placed: every figure's pole, its caption, and the table.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceFigures {
    /// The pole of each figure, in the order of [`ForceSpec::figures`].
    pub poles: Vec<Point>,
    /// Upper-left corner of the table of magnitudes.
    pub table_at: Point,
    /// Width of the table (values right-aligned at its right edge).
    pub table_width: f64,
    /// Rows of the table.
    pub row_count: usize,
    /// Captions: text and the left end of its baseline.
    pub captions: Vec<(String, Point)>,
}

impl ForceFigures {
    /// The boxes of the captions and of the table (for the polygons' names to keep off).
    pub fn text_boxes(&self, s: Sizes) -> Vec<labels::TextBox> {
        let h = forces::NAME_HEIGHT * s.text;
        let mut out: Vec<labels::TextBox> = self
            .captions
            .iter()
            .map(|(t, at)| labels::TextBox { min: *at, max: *at + Vector::new(widest_text_width(t, h), h) })
            .collect();
        let table_h = forces::TABLE_PITCH * forces::TABLE_TEXT * s.text * self.row_count as f64;
        out.push(labels::TextBox {
            min: self.table_at - Vector::new(0.0, table_h),
            max: self.table_at + Vector::new(self.table_width, 0.0),
        });
        out
    }
}

/// Panel placement and scales for one run (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct PanelFrame {
    /// The model's units.
    pub units: ModelUnits,
    /// Length scale k_l: model units per paper millimetre; the drawings'
    /// `paper_mm_per_unit` is 1/k_l.
    pub k_l: f64,
    /// Sizes of letters, arrows, links and joints (from paper millimetres at k_l).
    pub sizes: Sizes,
    /// Velocity scale and the pole p (when drawn).
    pub velocity: Option<(Scale, Point)>,
    /// Acceleration scale and the pole π (when drawn).
    pub acceleration: Option<(Scale, Point)>,
    /// Force scale and the pole of the first force figure, when drawn.
    pub forces: Option<(Scale, Point)>,
    /// The force panel's figures, captions and table, when drawn.
    pub force_figures: Option<ForceFigures>,
    /// The panels with their titles, each a scale caption (`Velocity polygon   k_v = …`):
    /// (title, lower-left, upper-right), the mechanism's first.
    pub panels: Vec<(ScaleCaption, Point, Point)>,
    /// The scale bar of each panel: left end, length (model units), label (value and
    /// unit), in the order of `panels`.
    pub bars: Vec<(Point, f64, String)>,
    /// The fixed window of every frame.
    pub window: Bounds,
}

/// What a polygon panel is before placing: title, scale, extent, which, unit of its bar.
struct PolygonPanel {
    title: ScaleCaption,
    scale: Scale,
    extent: Extent,
    which: Which,
    unit: String,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Which {
    Velocity,
    Acceleration,
    Forces,
}

impl PanelFrame {
    /// The frame of a run (see the module docs).
    pub fn new(spec: &PanelSpec) -> PanelFrame {
        let units = spec.units;
        let mech = spec.mechanism;
        let size = spec.size.max(f64::MIN_POSITIVE);
        let k_l = length_scale(size, spec.mechanism_mm);
        let paper = 1.0 / k_l;
        let sizes = Sizes::on_paper(k_l);
        let bar_room = scale_bar_room(sizes);
        // Room for the symbols and letters around the mechanism, and for the scale bar
        // under it.
        let (pad, below) = (spec.pad)(sizes);
        let mut mech_min = Point::from(mech.min) - Vector::new(pad, pad + below + bar_room);
        let mut mech_max = Point::from(mech.max) + Vector::new(pad, pad);
        // Each polygon's panel about as large on paper as the mechanism.
        let target_mm = spec.polygon_mm.unwrap_or(size * paper);
        let scale_for = |e: Option<Extent>| -> (Scale, Extent) {
            let e = e.unwrap_or(Extent { min: Vector::zeros(), max: Vector::zeros() });
            (Scale::on_paper(nice_scale(e.size() / target_mm), paper), e)
        };
        let mut polys: Vec<PolygonPanel> = Vec::new();
        if let Some(points) = &spec.velocity {
            let (scale, extent) = scale_for(Extent::of(points.iter().copied()));
            let unit = format!("{}/s", units.length);
            let title = ScaleCaption::new("Velocity polygon   k_v = ", scale.per_mm, format!(" ({unit})/mm"), paper);
            polys.push(PolygonPanel { title, scale, extent, which: Which::Velocity, unit });
        }
        if let Some(points) = &spec.acceleration {
            let (scale, extent) = scale_for(Extent::of(points.iter().copied()));
            let unit = format!("{}/s²", units.length);
            let title =
                ScaleCaption::new("Acceleration polygon   k_a = ", scale.per_mm, format!(" ({unit})/mm"), paper);
            polys.push(PolygonPanel { title, scale, extent, which: Which::Acceleration, unit });
        }
        let mut force_panel = None;
        if let Some(fs) = &spec.forces {
            // The scale of the largest figure.
            let larger = fs.figures.iter().fold(None, |best: Option<Extent>, (_, e)| match (best, e) {
                (Some(b), Some(e)) if e.size() > b.size() => Some(*e),
                (None, e) => *e,
                (b, _) => b,
            });
            let (scale, _) = scale_for(larger);
            let table = forces::table_size(&fs.rows, fs.row_count, sizes);
            let (extent, panel) = ForcePanel::arrange(scale, &fs.figures, table, fs.row_count, sizes);
            force_panel = Some(panel);
            let title = ScaleCaption::new("Force polygons   k_f = ", scale.per_mm, " N/mm", paper);
            polys.push(PolygonPanel { title, scale, extent, which: Which::Forces, unit: "N".into() });
            // The forces drawn on the mechanism, with their names, stay in its panel.
            let room = Vector::new(1.6 * sizes.text, 1.6 * sizes.text);
            for (at, v) in &fs.on_mechanism {
                let tip = at + scale.draw(*v);
                if tip.x.is_finite() && tip.y.is_finite() {
                    mech_min = Point::from(mech_min.coords.inf(&(tip - room - Vector::new(0.0, bar_room)).coords));
                    mech_max = Point::from(mech_max.coords.sup(&(tip + room).coords));
                }
            }
        }

        // Grid: up to three panels in a row, four as 2 × 2.
        let title_room = 2.6 * sizes.text;
        let gap = PANEL_GAP_MM * k_l;
        let mech_title = length_caption("Mechanism   ", k_l, units);
        // Each panel at least as wide as its title (the mechanism's with the position's
        // text right of it, the title as the SVG or the DXF states it) and its scale bar, as
        // the widest reader draws them.
        let wide_enough = |b: Vector, title: &ScaleCaption, extra: &str| {
            let w = caption_width(title, units, sizes.text) + widest_text_width(extra, sizes.text) + 2.0 * sizes.text;
            Vector::new(b.x.max(w), b.y)
        };
        let mut boxes: Vec<(ScaleCaption, Vector)> =
            vec![(mech_title.clone(), wide_enough(mech_max - mech_min, &mech_title, &spec.position_text))];
        for p in &polys {
            let room = Vector::new(2.0 * sizes.text, 2.0 * sizes.text + bar_room);
            boxes.push((p.title.clone(), wide_enough(p.scale.draw(p.extent.max - p.extent.min) + room, &p.title, "")));
        }
        let cols = if boxes.len() == 4 { 2 } else { boxes.len() };
        let rows = boxes.len().div_ceil(cols);
        let mut col_w = vec![0.0f64; cols];
        let mut row_h = vec![0.0f64; rows];
        for (i, (_, b)) in boxes.iter().enumerate() {
            col_w[i % cols] = col_w[i % cols].max(b.x);
            row_h[i / cols] = row_h[i / cols].max(b.y + title_room);
        }
        // Cell i's upper-left corner; row 0 on top, the mechanism's at its own lower-left.
        let mut panels = Vec::new();
        let mut origins = Vec::new();
        for (i, (title, b)) in boxes.iter().enumerate() {
            let (r, c) = (i / cols, i % cols);
            let x = mech_min.x + col_w[..c].iter().sum::<f64>() + gap * c as f64;
            let top = mech_min.y + row_h[0] - row_h[..r].iter().sum::<f64>() - gap * r as f64 - title_room + title_room;
            let y_top = top - title_room;
            let lower_left = Point::new(x, y_top - b.y);
            origins.push(lower_left);
            panels.push((title.clone(), lower_left, Point::new(x + b.x, y_top + title_room)));
        }
        // The mechanism panel must sit where the mechanism is: shift everything so.
        let shift = mech_min - origins[0];
        for p in panels.iter_mut() {
            p.1 += shift;
            p.2 += shift;
        }
        // Scale bars at the foot of each panel: the mechanism's in the scene's length unit.
        let bar_at = |ll: Point| ll + Vector::new(2.0 * sizes.small_text(), 0.5 * bar_room);
        let length = bar_value(k_l);
        let mut bars = vec![(bar_at(panels[0].1), length, format!("{} {}", scale_text(length), units.length))];
        let (mut velocity, mut acceleration, mut force, mut force_figures) = (None, None, None, None);
        for (j, p) in polys.iter().enumerate() {
            let ll = origins[j + 1] + shift + Vector::new(sizes.text, sizes.text + bar_room);
            let pole = ll - p.scale.draw(p.extent.min);
            let value = bar_value(p.scale.per_mm);
            bars.push((
                bar_at(panels[j + 1].1),
                p.scale.draw(Vector::new(value, 0.0)).x,
                format!("{} {}", scale_text(value), p.unit),
            ));
            match p.which {
                Which::Velocity => velocity = Some((p.scale, pole)),
                Which::Acceleration => acceleration = Some((p.scale, pole)),
                Which::Forces => {
                    force = Some((p.scale, pole));
                    force_figures = force_panel.as_ref().map(|fp| fp.place(pole));
                }
            }
        }
        let mut window = Bounds { min: panels[0].1, max: panels[0].2 };
        for p in &panels {
            window.min = Point::new(window.min.x.min(p.1.x), window.min.y.min(p.1.y));
            window.max = Point::new(window.max.x.max(p.2.x), window.max.y.max(p.2.y));
        }
        PanelFrame { units, k_l, sizes, velocity, acceleration, forces: force, force_figures, panels, bars, window }
    }

    /// A drawing on the content layers, on this frame's paper (1/k_l paper mm per unit).
    pub fn paper_drawing(&self) -> Drawing {
        let mut d = content_drawing(DimStyle { text_height: self.sizes.text, arrow_size: self.sizes.head });
        d.paper_mm_per_unit = Some(1.0 / self.k_l);
        d
    }

    /// Where a panel's title starts (left end of its baseline), for the panel from `ll` to `ur`.
    fn title_at(&self, ll: Point, ur: Point) -> Point {
        Point::new(ll.x, ur.y - 1.2 * self.sizes.text)
    }

    /// The boxes of the panels' titles (for letters to keep off).
    pub fn title_boxes(&self) -> Vec<labels::TextBox> {
        self.panels
            .iter()
            .map(|(title, ll, ur)| {
                let at = self.title_at(*ll, *ur);
                let h = self.sizes.text;
                labels::TextBox { min: at, max: at + Vector::new(caption_width(title, self.units, h), h) }
            })
            .collect()
    }

    /// The boxes of the panels' titles and scale bars (for letters to keep off).
    pub fn text_boxes(&self) -> Vec<labels::TextBox> {
        let mut out = self.title_boxes();
        let mut scratch = Drawing::new(DimStyle { text_height: self.sizes.text, arrow_size: self.sizes.head });
        for (at, length, label) in &self.bars {
            out.push(scale_bar(&mut scratch, 0, *at, *length, label, self.sizes));
        }
        out
    }

    /// What every frame shares, drawn after the mechanism's own fixed parts: the panels'
    /// titles with their scales, each panel's scale bar, and the force figures' captions
    /// (on `DIMENSIONS`).
    pub fn draw_titles(&self, d: &mut Drawing) {
        let dims = layer_of(d, layers::DIMENSIONS);
        for (title, ll, ur) in &self.panels {
            let at = self.title_at(*ll, *ur);
            d.scale_text(dims, at, self.sizes.text, title.clone());
        }
        for (at, length, label) in &self.bars {
            scale_bar(d, dims, *at, *length, label, self.sizes);
        }
        if let Some(ff) = &self.force_figures {
            let h = forces::NAME_HEIGHT * self.sizes.text;
            for (caption, at) in &ff.captions {
                let shape = Shape::Text {
                    at: *at,
                    height: h,
                    value: caption.clone(),
                    halign: HAlign::Left,
                    valign: VAlign::Baseline,
                    rotation: 0.0,
                };
                d.add(dims, shape);
            }
        }
    }

    /// The position's text (`φ1 = 30°`, `t = 0.25 s`) right-aligned at the top of the
    /// mechanism's panel, on `TEXT`.
    pub fn draw_position_text(&self, d: &mut Drawing, value: String) {
        let text = layer_of(d, layers::TEXT);
        let ur = self.panels[0].2;
        let s = self.sizes;
        d.add(
            text,
            Shape::Text {
                at: Point::new(ur.x, ur.y - 1.2 * s.text),
                height: s.text,
                value,
                halign: HAlign::Right,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        );
    }

    /// One position's polygons in their panels: the velocity and acceleration polygons
    /// (their letters off the panel titles and scale bars), and the force figures with the table of
    /// magnitudes (the names off the captions, the table and each other).
    pub fn draw_polygons(
        &self,
        d: &mut Drawing,
        velocity: Option<&PointPolygon>,
        acceleration: Option<&PointPolygon>,
        force: Option<(&[ForcePolygon], &[Magnitude])>,
    ) {
        let s = self.sizes;
        let titles = self.text_boxes();
        if let (Some(poly), Some((scale, pole))) = (velocity, self.velocity) {
            polygon::draw_keeping_off(d, poly, layers::VELOCITY, scale, pole, s, &titles);
        }
        if let (Some(poly), Some((scale, pole))) = (acceleration, self.acceleration) {
            polygon::draw_keeping_off(d, poly, layers::ACCELERATION, scale, pole, s, &titles);
        }
        if let (Some((figures, rows)), Some((scale, _)), Some(ff)) = (force, self.forces, &self.force_figures) {
            let mut keep_off = ff.text_boxes(s);
            keep_off.extend(titles.iter().copied());
            for (fig, pole) in figures.iter().zip(&ff.poles) {
                let names = forces::draw(d, fig, scale, *pole, s, &keep_off);
                keep_off.extend(names);
            }
            forces::table(d, rows, ff.table_at, ff.table_width, s);
        }
    }
}

/// How the force panel is arranged: its figures and the table in rows of up to
/// [`FORCE_ROW`] items under their captions, each hanging from the top of its row, at one
/// force scale (drawn units from the panel's lower-left).
#[derive(Debug, Clone)]
struct ForcePanel {
    scale: Scale,
    /// The physical point drawn at the panel's lower-left (the first figure's pole is
    /// placed by the grid from it).
    e_min: Vector,
    /// Each figure: its physical extent's minimum, drawn height, and the drawn offset of
    /// its column and of its row's top from the panel's lower-left.
    figures: Vec<(Vector, f64, Vector)>,
    /// The table's column offset and row top, and its width.
    table: (Vector, f64),
    row_count: usize,
    /// Captions with the drawn offsets of their column and of their row's top.
    captions: Vec<(String, Vector)>,
    /// Caption text height.
    caption_h: f64,
}

impl ForcePanel {
    /// The panel for the figures of physical extents `figures` and a table of drawn size
    /// `table`, at `scale`; returns the physical extent the grid sizes the panel by (its
    /// minimum drawn at the panel's lower-left puts the first figure's pole in place).
    fn arrange(
        scale: Scale,
        figures: &[(String, Option<Extent>)],
        table: Vector,
        row_count: usize,
        sizes: Sizes,
    ) -> (Extent, ForcePanel) {
        let zero = Extent { min: Vector::zeros(), max: Vector::zeros() };
        let caption_h = forces::NAME_HEIGHT * sizes.text;
        let gap = 2.0 * sizes.text;
        // Items: (caption, drawn size, physical minimum); the table last.
        let mut items: Vec<(String, Vector, Option<Vector>)> = figures
            .iter()
            .map(|(caption, e)| {
                let e = e.unwrap_or(zero);
                (caption.clone(), scale.draw(e.max - e.min), Some(e.min))
            })
            .collect();
        items.push((TABLE_CAPTION.to_string(), table, None));
        let rows: Vec<&[(String, Vector, Option<Vector>)]> = items.chunks(FORCE_ROW).collect();
        // Each row's height; the tops from the bottom up (the last row's top at its height).
        let heights: Vec<f64> = rows.iter().map(|r| r.iter().map(|i| i.1.y).fold(0.0, f64::max)).collect();
        let mut tops = vec![0.0; rows.len()];
        let mut below = 0.0;
        for r in (0..rows.len()).rev() {
            tops[r] = if r + 1 == rows.len() { heights[r] } else { below + 2.0 * caption_h + heights[r] };
            below = tops[r];
        }
        let mut placed: Vec<(Vector, f64, Vector)> = Vec::new();
        let mut table_at = (Vector::zeros(), 0.0);
        let mut captions = Vec::new();
        let mut width: f64 = 0.0;
        for (r, row) in rows.iter().enumerate() {
            let mut x = 0.0;
            for (caption, drawn, min) in row.iter() {
                let col = drawn.x.max(widest_text_width(caption, caption_h));
                let at = Vector::new(x, tops[r]);
                captions.push((caption.clone(), Vector::new(x, tops[r])));
                match min {
                    Some(min) => placed.push((*min, drawn.y, at)),
                    None => table_at = (at, col),
                }
                width = width.max(x + col);
                x = x + col + gap;
            }
        }
        let total = Vector::new(width, tops[0] + 2.0 * caption_h);
        // Drawn units per physical unit.
        let k = scale.draw(Vector::new(1.0, 0.0)).x;
        // The first figure hangs from the top of its row.
        let (min0, h0, _) = placed.first().copied().unwrap_or((Vector::zeros(), 0.0, Vector::new(0.0, tops[0])));
        let e_min = min0 - Vector::new(0.0, (tops[0] - h0) / k);
        let e = Extent { min: e_min, max: e_min + total / k };
        (e, ForcePanel { scale, e_min, figures: placed, table: table_at, row_count, captions, caption_h })
    }

    /// The figures around the first figure's pole `pole` as the grid placed it.
    fn place(&self, pole: Point) -> ForceFigures {
        let origin = pole + self.scale.draw(self.e_min);
        let poles = self
            .figures
            .iter()
            .enumerate()
            .map(
                |(i, (min, h, at))| {
                    if i == 0 { pole } else { origin + Vector::new(at.x, at.y - h) - self.scale.draw(*min) }
                },
            )
            .collect();
        ForceFigures {
            poles,
            table_at: origin + self.table.0,
            table_width: self.table.1,
            row_count: self.row_count,
            captions: self
                .captions
                .iter()
                .map(|(c, at)| (c.clone(), Point::new(origin.x + at.x, origin.y + at.y + 0.8 * self.caption_h)))
                .collect(),
        }
    }
}
