//! The graph-analytical frame of any mechanism (issue 15 §3: one figure pipeline): the
//! mechanism's panel and, beside it, the velocity polygon's, the acceleration polygon's and
//! the force panel (one force polygon per isolated group or body, captioned, and a table of
//! magnitudes), each panel framed, titled with its scale and carrying a scale bar. The
//! four-bar kind and the linkage kind both draw their frames through [`PanelFrame`]: they
//! describe their polygons as [`PointPolygon`]s and [`ForcePolygon`]s and draw their own
//! mechanism in the first panel; the panels, scales, titles, bars, captions and the
//! polygons' drawing are here, once.
//!
//! # Layout and scales
//! One [`PanelFrame`] is computed per run from every position, so all frames share one
//! window and the mechanism keeps one length scale k_l (model units per paper millimetre, a
//! drafting scale [`drafting_scale`]) that draws its motion at most `mechanism_mm` long on paper;
//! the drawings carry `paper_mm_per_unit = 1/k_l`. The polygons' panels stand in a
//! column right of the mechanism's (in a row under it for a long, low mechanism, when that
//! takes less paper), smaller than it, the force panel under all: the mechanism is the
//! largest figure. The force panel holds its figures in cells, in rows of up to
//! [`FORCE_ROW`] items (the figures, then the table), each under its caption.
//!
//! The polygons' scales per printed millimetre (`k_v = 0.01 (m/s)/mm`: one measured
//! millimetre stands for 0.01 m/s) are chosen one of two ways ([`ScaleChoice`], the scene's
//! `[frames] scales`):
//! - per frame (the default): each polygon, and each force figure on its own, takes at each
//!   position the nice scale at which it fills between half and all of its panel
//!   ([`sheet::frame_scales`]: kept from frame to frame while it does, so the animation
//!   does not flicker), centred in its panel; the scale is printed in the panel's title (a
//!   force figure's in its caption) and drawn as the panel's scale bar in every frame;
//! - fixed: one scale per polygon for the whole run, chosen from the largest polygon over
//!   the motion (its panel about as large as the mechanism), the pole fixed.
//!
//! The forces drawn on the mechanism keep one scale for the run (printed in the mechanism
//! panel's title).

use crate::draw::parts::widest_text_width;
use crate::draw::{Bounds, DimStyle, Drawing, HAlign, ScaleCaption, Shape, VAlign};
use crate::geom::{Point, Vector};

use crate::figure::shared::forces::{self, ForcePolygon, Magnitude};
use crate::figure::shared::labels::{self, Label};
use crate::figure::shared::polygon::{self, PointPolygon};
use crate::figure::shared::sheet;
use crate::figure::shared::vocab::{
    ModelUnits, Scale, Sizes, bar_value, caption_width, content_drawing, drafting_scale, layer_of, layers,
    length_caption, nice_scale, scale_bar, scale_bar_room, scale_text,
};

/// A panel's title: none, plain words, or words stating a scale (each medium writes its
/// value for the millimetres it draws: [`ScaleCaption`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Title {
    /// No title (drawn with each position: a polygon's scale per frame).
    None,
    /// Words without a scale (`Force polygons`).
    Words(String),
    /// Words with a scale (`Velocity polygon   k_v = 0.1 (m/s)/mm`).
    Scale(ScaleCaption),
}

impl Title {
    /// The title as a medium drawing a model unit `mm_per_unit` millimetres long writes it.
    pub fn text(&self, mm_per_unit: f64) -> String {
        match self {
            Title::None => String::new(),
            Title::Words(w) => w.clone(),
            Title::Scale(c) => c.text(mm_per_unit),
        }
    }

    /// The title on its figure's paper.
    pub fn on_paper(&self) -> String {
        match self {
            Title::Scale(c) => c.on_paper(),
            other => other.text(1.0),
        }
    }

    /// The width it takes in the widest reader, in whichever medium writes it wider.
    fn width(&self, units: ModelUnits, height: f64) -> f64 {
        match self {
            Title::None => 0.0,
            Title::Words(w) => widest_text_width(w, height),
            Title::Scale(c) => caption_width(c, units, height),
        }
    }

    /// Draws it left-aligned on its baseline at `at` on `layer`.
    fn draw(&self, d: &mut Drawing, layer: usize, at: Point, height: f64) {
        match self {
            Title::None => {}
            Title::Words(w) => text(d, layer, at, height, w),
            Title::Scale(c) => d.scale_text(layer, at, height, c.clone()),
        }
    }
}

/// A caption stating a scale: `before` then `k_v = 0.1 (m/s)/mm` (`per_mm` per paper mm of a
/// figure printed at `paper_mm_per_unit`), each medium writing the value for its own
/// millimetres.
pub fn scale_caption(before: &str, symbol: &str, per_mm: f64, unit: &str, paper_mm_per_unit: f64) -> ScaleCaption {
    let unit = if unit.contains('/') { format!("({unit})") } else { unit.to_string() };
    ScaleCaption::new(format!("{before}{symbol} = "), per_mm, format!(" {unit}/mm"), paper_mm_per_unit)
}

/// Gap between panels on paper, millimetres.
pub const PANEL_GAP_MM: f64 = 10.0;
/// Items (force figures and the table) in one row of the force panel.
pub const FORCE_ROW: usize = 4;
/// Caption of the table of magnitudes.
pub const TABLE_CAPTION: &str = "Magnitudes";
/// The longest force drawn on the mechanism, as a fraction of the mechanism's drawn size.
pub const MECHANISM_FORCE_FRACTION: f64 = 0.35;
/// Side of a force figure's cell on paper when each figure has its own scale, as a fraction
/// of a polygon panel's.
pub const FORCE_CELL_FRACTION: f64 = 0.8;
/// The smallest a polygon's panel is drawn beside the mechanism, as a fraction of the
/// mechanism's drawn size.
pub const SIDE_PANEL_MIN: f64 = 0.4;
/// The smallest a force figure's cell is drawn (before [`FORCE_CELL_FRACTION`]), as a
/// fraction of the mechanism's drawn size.
pub const FORCE_PANEL_MIN: f64 = 0.6;
/// Room between a polygon and its panel's edges for the letters at its outer points, in
/// letter heights (each side).
pub const LETTER_ROOM: f64 = 2.0;

/// How the polygons' scales are chosen over an animation (the scene's `[frames] scales`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ScaleChoice {
    /// A nice scale per frame, each polygon filling half to all of its panel, kept while it
    /// does (`"per-frame"`, the default).
    #[default]
    PerFrame,
    /// One scale per polygon for the whole run (`"fixed"`).
    Fixed,
}

impl std::str::FromStr for ScaleChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<ScaleChoice, String> {
        match s {
            "per-frame" => Ok(ScaleChoice::PerFrame),
            "fixed" => Ok(ScaleChoice::Fixed),
            _ => Err(format!(
                "`{s}` is not a choice: \"per-frame\" (each frame's polygons at their own nice scale, the default) or \
                 \"fixed\" (one scale per polygon for the whole run)"
            )),
        }
    }
}

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

    /// Width and height.
    pub fn sides(&self) -> Vector {
        self.max - self.min
    }
}

/// The force panel asked of a [`PanelFrame`]: its figures over the whole motion.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceSpec {
    /// Each figure's caption and the extent of its points at each position (relative to
    /// its pole, N), in the order they are drawn.
    pub figures: Vec<(String, Vec<Option<Extent>>)>,
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
    /// The velocity polygon's points at each position (relative to the pole), when drawn.
    pub velocity: Option<Vec<Option<Extent>>>,
    /// The acceleration polygon's, when drawn.
    pub acceleration: Option<Vec<Option<Extent>>>,
    /// The force panel, when drawn.
    pub forces: Option<ForceSpec>,
    /// How the polygons' scales are chosen.
    pub scales: ScaleChoice,
}

/// One scaled figure of a frame: a polygon in its panel, or a force figure in its cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Slot {
    /// The scale's symbol: `k_v`, `k_a`, `k_f`.
    pub symbol: &'static str,
    /// The unit of its vectors (`m/s`, `N`).
    pub unit: String,
    /// What it is: `Velocity polygon`, a force figure's caption.
    pub title: String,
    /// The left end of its title's baseline, and the title's height.
    pub title_at: (Point, f64),
    /// The area it is fitted in (model units).
    pub area: Bounds,
    /// Where its scale bar starts (`None`: it shares its panel's).
    pub bar_at: Option<Point>,
    /// Physical units per paper millimetre at each position (one for a fixed scale).
    pub scales: Vec<f64>,
    /// The pole when the scale is fixed (`None`: centred in the area at each position).
    pub pole: Option<Point>,
    /// The figure's physical size (width, height) at each position its scales were chosen
    /// for (per frame; empty for a fixed scale).
    pub sides: Vec<Option<Vector>>,
}

impl Slot {
    /// The scale of this figure at position `k` for a figure of physical size `extent` (the
    /// position's own scale, or, between positions, the nearest's while the figure fills
    /// half to all of the area at it: [`sheet::scale_near`]).
    fn per_mm(&self, k: usize, extent: Option<Vector>, k_l: f64) -> f64 {
        let last = self.scales.len().saturating_sub(1);
        let stored = self.scales.get(k.min(last)).copied();
        if self.pole.is_some() {
            return stored.unwrap_or(1.0);
        }
        let area = Vector::new(self.area.width(), self.area.height()) / k_l;
        sheet::scale_near(stored, extent, area)
    }

    /// The scale and the pole of a figure whose points (relative to its pole) span
    /// `extent`, at position `k`.
    pub fn place(&self, k: usize, extent: Option<Extent>, k_l: f64) -> (Scale, Point) {
        let per_mm = self.per_mm(k, extent.map(|e| e.sides()), k_l);
        let scale = Scale::on_paper(per_mm, 1.0 / k_l);
        let pole = self.pole.unwrap_or_else(|| {
            let mid = Point::from((self.area.min.coords + self.area.max.coords) / 2.0);
            match extent {
                Some(e) => mid - scale.draw((e.min + e.max) / 2.0),
                None => mid,
            }
        });
        (scale, pole)
    }

    /// The title with the scale `per_mm`: `Velocity polygon   k_v = 0.1 (m/s)/mm`, on a
    /// figure printed at `paper_mm_per_unit`.
    fn title_with(&self, per_mm: f64, paper_mm_per_unit: f64) -> ScaleCaption {
        scale_caption(&format!("{}   ", self.title), self.symbol, per_mm, &self.unit, paper_mm_per_unit)
    }
}

/// `k_v = 0.1 (m/s)/mm`, `k_f = 50 N/mm`.
pub fn scale_line(symbol: &str, per_mm: f64, unit: &str) -> String {
    let unit = if unit.contains('/') { format!("({unit})") } else { unit.to_string() };
    format!("{symbol} = {} {unit}/mm", scale_text(per_mm))
}

/// The force panel as placed: a slot per figure, the table.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceCells {
    /// One slot per figure, in the order of [`ForceSpec::figures`].
    pub figures: Vec<Slot>,
    /// Upper-left corner of the table of magnitudes.
    pub table_at: Point,
    /// Width of the table (values right-aligned at its right edge).
    pub table_width: f64,
    /// Rows of the table.
    pub row_count: usize,
    /// The table's caption and the left end of its baseline.
    pub table_caption: (String, Point),
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
    /// How the polygons' scales are chosen.
    pub choice: ScaleChoice,
    /// The velocity polygon's slot (when drawn).
    pub velocity: Option<Slot>,
    /// The acceleration polygon's slot (when drawn).
    pub acceleration: Option<Slot>,
    /// The force panel's figures and table (when drawn).
    pub forces: Option<ForceCells>,
    /// The scale of the forces drawn on the mechanism (when drawn).
    pub mechanism_forces: Option<Scale>,
    /// The panels: (title drawn in every frame's base, lower-left, upper-right), the
    /// mechanism's first, then velocity, acceleration, forces as drawn. A polygon's title
    /// with a scale per frame is drawn with each position ([`Slot::title`]).
    pub panels: Vec<(Title, Point, Point)>,
    /// The scale bars drawn in every frame's base: left end, length (model units), label.
    pub bars: Vec<(Point, f64, String)>,
    /// The fixed window of every frame.
    pub window: Bounds,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Which {
    Velocity,
    Acceleration,
    Forces,
}

/// A panel before placing: which, its content's drawn size, its title (widest), and the
/// parts of its slot.
struct Pending {
    which: Which,
    content: Vector,
    title: Title,
    /// The scale's symbol (`k_v`, `k_a`, `k_f`) and the unit of its vectors.
    symbol: &'static str,
    unit: String,
    /// What a polygon's panel shows (`Velocity polygon`); empty for the force panel.
    name: &'static str,
    /// A polygon's extent over the run.
    all: Option<Extent>,
    /// The fixed scale (fixed scales; the force panel's common scale).
    k: Option<f64>,
}

/// A frame's measures before its panels are placed: the length scale, the letters' sizes
/// and rooms, and the mechanism's content box (model units).
struct Measures {
    k_l: f64,
    /// Paper millimetres per model unit (1/k_l).
    paper: f64,
    sizes: Sizes,
    bar_room: f64,
    /// Room for the letters around a polygon, each side.
    room: f64,
    title_room: f64,
    gap: f64,
    /// The mechanism's content box: its motion with room for its symbols, letters, bar and
    /// (when drawn) the forces on it.
    mech_min: Point,
    mech_max: Point,
    /// The mechanism's drawn size (paper mm) and the most a polygon's panel may be.
    size_mm: f64,
    cap_mm: f64,
}

impl Measures {
    /// The measures of `spec`: a drafting scale (1, 1.5, 2, 2.5, 4, 5 × 10ᵏ), the
    /// mechanism as large as it may be.
    fn of(spec: &PanelSpec) -> Measures {
        let size = spec.size.max(f64::MIN_POSITIVE);
        let k_l = drafting_scale(size / spec.mechanism_mm);
        let paper = 1.0 / k_l;
        let sizes = Sizes::on_paper(k_l);
        let bar_room = scale_bar_room(sizes);
        // Room for the symbols and letters around the mechanism, and for the scale bar
        // under it.
        let (pad, below) = (spec.pad)(sizes);
        let mech = spec.mechanism;
        let size_mm = size * paper;
        Measures {
            k_l,
            paper,
            sizes,
            bar_room,
            room: LETTER_ROOM * sizes.text,
            title_room: 2.6 * sizes.text,
            gap: PANEL_GAP_MM * k_l,
            mech_min: Point::from(mech.min) - Vector::new(pad, pad + below + bar_room),
            mech_max: Point::from(mech.max) + Vector::new(pad, pad),
            size_mm,
            cap_mm: spec.polygon_mm.unwrap_or(size_mm).min(size_mm),
        }
    }

    /// The side (paper mm) of the square a polygon is fitted in: the polygons' panels stand
    /// in a column right of the mechanism, together about as tall as its panel: smaller
    /// than the mechanism, never under SIDE_PANEL_MIN of its drawn size, nor over
    /// `polygon_mm`.
    fn polygon_target_mm(&self, spec: &PanelSpec) -> f64 {
        let side_count = usize::from(spec.velocity.is_some()) + usize::from(spec.acceleration.is_some());
        if side_count == 0 {
            return self.cap_mm;
        }
        let (n, s) = (side_count as f64, self.sizes);
        let column = (self.mech_max.y - self.mech_min.y) + self.title_room - (n - 1.0) * self.gap;
        let each = column / n - self.title_room - 2.0 * self.room - self.bar_room - 0.5 * s.text;
        (each * self.paper).min(self.cap_mm).max(SIDE_PANEL_MIN * self.size_mm)
    }

    /// Each polygon's panel before placing (`target` the side of its square, model units):
    /// its content size (the area plus letter room) and widest title.
    fn polygon_pendings(&self, spec: &PanelSpec, target_mm: f64) -> Vec<Pending> {
        let (room, target) = (self.room, target_mm * self.k_l);
        let union = |e: &[Option<Extent>]| e.iter().copied().fold(None, Extent::union);
        let length = spec.units.length;
        let mut pending = Vec::new();
        for (which, points, symbol, unit, name) in [
            (Which::Velocity, &spec.velocity, "k_v", format!("{length}/s"), "Velocity polygon"),
            (Which::Acceleration, &spec.acceleration, "k_a", format!("{length}/s²"), "Acceleration polygon"),
        ] {
            let Some(points) = points else { continue };
            let all = union(points);
            let (content, k) = match spec.scales {
                ScaleChoice::Fixed => {
                    let k = nice_scale(all.map_or(0.0, |e| e.size()) / target_mm);
                    let e = all.map_or(Vector::zeros(), |e| e.sides());
                    (Scale::on_paper(k, self.paper).draw(e) + Vector::new(2.0 * room, 2.0 * room), Some(k))
                }
                ScaleChoice::PerFrame => (Vector::new(target, target) + Vector::new(2.0 * room, 2.0 * room), None),
            };
            // The widest title it takes: with the finest scale of the run (most digits).
            let widest =
                Title::Scale(scale_caption(&format!("{name}   "), symbol, k.unwrap_or(0.0025), &unit, self.paper));
            pending.push(Pending { which, content, title: widest, symbol, unit, name, all, k });
        }
        pending
    }

    /// The force panel before placing, its cells as large as a polygon's or
    /// FORCE_PANEL_MIN of the mechanism; the mechanism's box grown to hold the forces drawn
    /// on it, with their names.
    fn force_pending(&mut self, spec: &PanelSpec, fs: &ForceSpec, target_mm: f64) -> (Pending, ForceLayout) {
        let force_mm = self.cap_mm.min(target_mm.max(FORCE_PANEL_MIN * self.size_mm));
        let cells = ForceLayout::arrange(spec, fs, self.sizes, force_mm, self.k_l);
        let scale = cells.mechanism_scale;
        let room = Vector::new(1.6 * self.sizes.text, 1.6 * self.sizes.text);
        for (at, v) in &fs.on_mechanism {
            let tip = at + scale.draw(*v);
            if tip.x.is_finite() && tip.y.is_finite() {
                let low = tip - room - Vector::new(0.0, self.bar_room);
                self.mech_min = Point::from(self.mech_min.coords.inf(&low.coords));
                self.mech_max = Point::from(self.mech_max.coords.sup(&(tip + room).coords));
            }
        }
        let title = match spec.scales {
            ScaleChoice::Fixed => {
                Title::Scale(scale_caption("Force polygons   ", "k_f", cells.common, "N", self.paper))
            }
            ScaleChoice::PerFrame => Title::Words("Force polygons".to_string()),
        };
        let pending = Pending {
            which: Which::Forces,
            content: cells.size + Vector::new(1.2 * self.sizes.text, self.bar_room),
            title,
            symbol: "k_f",
            unit: "N".to_string(),
            name: "",
            all: None,
            k: Some(cells.common),
        };
        (pending, cells)
    }

    /// The panels' rectangles (the mechanism's first, then one per `pending`), placed so
    /// that the mechanism's panel sits where the mechanism is: its content hangs from under
    /// its title, centred in the panel when the panel is larger. Each panel at least as wide
    /// as its title (the mechanism's with the position's text right of it; the title as the
    /// SVG or the DXF states it), as the widest reader draws them.
    fn place(&self, spec: &PanelSpec, mech_title: &Title, pending: &[Pending]) -> Vec<(Point, Point)> {
        let s = self.sizes;
        let wide_enough = |b: Vector, title: &Title, extra: &str| {
            let w = title.width(spec.units, s.text) + widest_text_width(extra, s.text) + 2.0 * s.text;
            Vector::new(b.x.max(w), b.y)
        };
        let mech = self.mech_max - self.mech_min;
        let mut boxes: Vec<(Title, Vector)> =
            vec![(mech_title.clone(), wide_enough(mech, mech_title, &spec.position_text))];
        for p in pending {
            boxes.push((p.title.clone(), wide_enough(p.content + Vector::new(0.0, self.bar_room), &p.title, "")));
        }
        let which: Vec<Which> = pending.iter().map(|p| p.which).collect();
        let rects = arrange_panels(&boxes, &which, self.title_room, self.gap);
        let spare = (rects[0].1 - rects[0].0) - mech - Vector::new(0.0, self.title_room);
        let shift = Point::new(
            self.mech_min.x - 0.5 * spare.x.max(0.0),
            self.mech_max.y + self.title_room + 0.5 * spare.y.max(0.0),
        ) - Point::new(rects[0].0.x, rects[0].1.y);
        rects.into_iter().map(|(a, b)| (a + shift, b + shift)).collect()
    }

    /// Where a panel's scale bar starts, from the panel's lower-left.
    fn bar_at(&self, ll: Point) -> Point {
        ll + Vector::new(2.0 * self.sizes.small_text(), 0.5 * self.bar_room + 0.5 * self.sizes.text)
    }

    /// A polygon's slot in its panel `ll`–`ur`, the panel's title and (fixed scale) its bar:
    /// the whole panel under its title band, over its bar strip, less the letters' room; at
    /// a fixed scale the run's extent centred in it, else a scale per frame.
    fn polygon_slot(&self, spec: &PanelSpec, p: Pending, ll: Point, ur: Point) -> (Slot, Title, Option<Bar>) {
        let (s, room) = (self.sizes, self.room);
        let area = Bounds {
            min: ll + Vector::new(room, self.bar_room + 0.5 * s.text + room),
            max: ur - Vector::new(room, self.title_room + room),
        };
        let points = &fixed_points(&spec.velocity, &spec.acceleration, p.which);
        let (scales, pole, sides) = match p.k {
            Some(k) => {
                let scale = Scale::on_paper(k, self.paper);
                let mid = Point::from((area.min.coords + area.max.coords) / 2.0);
                let pole = mid - scale.draw(p.all.map_or(Vector::zeros(), |e| (e.min + e.max) / 2.0));
                (vec![k], Some(pole), Vec::new())
            }
            None => {
                let a = Vector::new(area.width(), area.height()) / self.k_l;
                let sides: Vec<Option<Vector>> = points.iter().map(|e| e.map(|e| e.sides())).collect();
                (sheet::frame_scales(&sides, a), None, sides)
            }
        };
        let slot = Slot {
            symbol: p.symbol,
            unit: p.unit.clone(),
            title: p.name.to_string(),
            title_at: (Point::new(ll.x + 0.6 * s.text, ur.y - 1.2 * s.text), s.text),
            area,
            bar_at: Some(self.bar_at(ll)),
            scales,
            pole,
            sides,
        };
        let (title, bar) = match slot.pole {
            Some(_) => {
                let k = slot.scales[0];
                let value = bar_value(k);
                let drawn = Scale::on_paper(k, self.paper).draw(Vector::new(value, 0.0)).x;
                let bar = (self.bar_at(ll), drawn, format!("{} {}", scale_text(value), p.unit));
                (Title::Scale(slot.title_with(k, self.paper)), Some(bar))
            }
            None => (Title::None, None),
        };
        (slot, title, bar)
    }
}

/// A scale bar drawn in every frame's base: its left end, length (model units), label.
type Bar = (Point, f64, String);

/// The mechanism panel's title: its k_l, and with forces at a scale per frame, the scale of
/// the forces drawn on it.
fn mechanism_title(spec: &PanelSpec, cells: Option<&ForceLayout>, m: &Measures) -> Title {
    Title::Scale(match (cells, spec.scales) {
        (Some(c), ScaleChoice::PerFrame) => length_caption("Mechanism   ", m.k_l, spec.units).then(scale_caption(
            ", forces ",
            "k_f",
            c.mechanism_scale.per_mm,
            "N",
            m.paper,
        )),
        _ => length_caption("Mechanism   ", m.k_l, spec.units),
    })
}

impl PanelFrame {
    /// The frame of a run (see the module docs).
    pub fn new(spec: &PanelSpec) -> PanelFrame {
        let mut m = Measures::of(spec);
        let target_mm = m.polygon_target_mm(spec);
        let mut pending = m.polygon_pendings(spec, target_mm);
        let mut force_cells = None;
        if let Some(fs) = &spec.forces {
            let (p, cells) = m.force_pending(spec, fs, target_mm);
            pending.push(p);
            force_cells = Some(cells);
        }
        let mech_title = mechanism_title(spec, force_cells.as_ref(), &m);
        let rects = m.place(spec, &mech_title, &pending);
        let length_bar = bar_value(m.k_l);
        let mut panels = vec![(mech_title, rects[0].0, rects[0].1)];
        let mut bars =
            vec![(m.bar_at(rects[0].0), length_bar, format!("{} {}", scale_text(length_bar), spec.units.length))];
        let (mut velocity, mut acceleration, mut forces, mut mechanism_forces) = (None, None, None, None);
        for (p, &(ll, ur)) in pending.into_iter().zip(&rects[1..]) {
            match p.which {
                Which::Velocity | Which::Acceleration => {
                    let which = p.which;
                    let (slot, title, bar) = m.polygon_slot(spec, p, ll, ur);
                    bars.extend(bar);
                    panels.push((title, ll, ur));
                    if which == Which::Velocity {
                        velocity = Some(slot);
                    } else {
                        acceleration = Some(slot);
                    }
                }
                Which::Forces => {
                    // The content under the title band, over the bar strip.
                    let content_ll = Point::new(ll.x, ur.y - m.title_room - p.content.y);
                    if let Some(c) = force_cells.take() {
                        mechanism_forces = Some(c.mechanism_scale);
                        let at = content_ll + Vector::new(0.6 * m.sizes.text, 0.0);
                        forces = Some(c.place(at, spec.scales, m.paper));
                    }
                    if spec.scales == ScaleChoice::Fixed {
                        let k = p.k.unwrap_or(1.0);
                        let value = bar_value(k);
                        let drawn = Scale::on_paper(k, m.paper).draw(Vector::new(value, 0.0)).x;
                        bars.push((m.bar_at(ll), drawn, format!("{} N", scale_text(value))));
                    }
                    panels.push((p.title, ll, ur));
                }
            }
        }
        let mut window = Bounds { min: panels[0].1, max: panels[0].2 };
        for p in &panels {
            window.min = Point::new(window.min.x.min(p.1.x), window.min.y.min(p.1.y));
            window.max = Point::new(window.max.x.max(p.2.x), window.max.y.max(p.2.y));
        }
        PanelFrame {
            units: spec.units,
            k_l: m.k_l,
            sizes: m.sizes,
            choice: spec.scales,
            velocity,
            acceleration,
            forces,
            mechanism_forces,
            panels,
            bars,
            window,
        }
    }

    /// A drawing on the content layers, on this frame's paper (1/k_l paper mm per unit).
    pub fn paper_drawing(&self) -> Drawing {
        let mut d = content_drawing(DimStyle { text_height: self.sizes.text, arrow_size: self.sizes.head });
        d.paper_mm_per_unit = Some(1.0 / self.k_l);
        d
    }

    /// Where a panel's title starts (left end of its baseline), for the panel from `ll` to `ur`.
    fn title_at(&self, ll: Point, ur: Point) -> Point {
        Point::new(ll.x + 0.6 * self.sizes.text, ur.y - 1.2 * self.sizes.text)
    }

    /// The scales of position `k` as stored for the run (each force figure's k_f in order).
    pub fn scales_at(&self, k: usize) -> FrameScales {
        let at = |slot: &Slot| slot.scales.get(k.min(slot.scales.len().saturating_sub(1))).copied();
        FrameScales {
            k_v: self.velocity.as_ref().and_then(at),
            k_a: self.acceleration.as_ref().and_then(at),
            k_f: self.forces.as_ref().map_or_else(Vec::new, |f| f.figures.iter().filter_map(at).collect()),
        }
    }

    /// The scales per frame chosen again after an earlier run of the same motion drawn at
    /// `previous[k]` at position `k` (the live page's picture before a field changed): each
    /// polygon and force figure keeps its earlier scale at a position while it fills half to
    /// all of its area there ([`sheet::held_scales`]). Nothing changes with fixed scales or
    /// when `previous` has another number of positions (or of force figures).
    pub fn hold(&mut self, previous: &[FrameScales]) {
        if self.choice != ScaleChoice::PerFrame {
            return;
        }
        let k_l = self.k_l;
        let held = |slot: &mut Slot, earlier: Vec<Option<f64>>| {
            if slot.pole.is_none() && earlier.len() == slot.sides.len() {
                let area = Vector::new(slot.area.width(), slot.area.height()) / k_l;
                slot.scales = sheet::held_scales(&earlier, &slot.sides, area);
            }
        };
        if let Some(slot) = &mut self.velocity {
            held(slot, previous.iter().map(|f| f.k_v).collect());
        }
        if let Some(slot) = &mut self.acceleration {
            held(slot, previous.iter().map(|f| f.k_a).collect());
        }
        if let Some(cells) = &mut self.forces {
            let n = cells.figures.len();
            if previous.iter().all(|f| f.k_f.len() == n) {
                for (i, slot) in cells.figures.iter_mut().enumerate() {
                    held(slot, previous.iter().map(|f| f.k_f.get(i).copied()).collect());
                }
            }
        }
    }

    /// The panel the mechanism is drawn in: lower-left and upper-right.
    pub fn mechanism_panel(&self) -> (Point, Point) {
        (self.panels[0].1, self.panels[0].2)
    }

    /// The boxes of the titles and scale bars every frame shares (for letters to keep off).
    pub fn text_boxes(&self) -> Vec<labels::TextBox> {
        let mut out: Vec<labels::TextBox> = self
            .panels
            .iter()
            .filter(|(t, ..)| *t != Title::None)
            .map(|(title, ll, ur)| {
                let at = self.title_at(*ll, *ur);
                let e = crate::draw::font::measure(&title.on_paper(), self.sizes.text);
                let w = title.width(self.units, self.sizes.text).max(e.width);
                labels::TextBox { min: at - Vector::new(0.0, e.descent), max: at + Vector::new(w, e.ascent) }
            })
            .collect();
        let mut scratch = Drawing::new(DimStyle { text_height: self.sizes.text, arrow_size: self.sizes.head });
        for (at, length, label) in &self.bars {
            out.push(scale_bar(&mut scratch, 0, *at, *length, label, self.sizes));
        }
        if let Some(f) = &self.forces {
            let (c, at) = &f.table_caption;
            out.push(text_box(*at, c, forces::NAME_HEIGHT * self.sizes.text));
            let table_h = forces::TABLE_PITCH * forces::TABLE_TEXT * self.sizes.text * f.row_count as f64;
            out.push(labels::TextBox {
                min: f.table_at - Vector::new(0.0, table_h),
                max: f.table_at + Vector::new(f.table_width, 0.0),
            });
            if self.choice == ScaleChoice::Fixed {
                out.extend(f.figures.iter().map(|s| text_box(s.title_at.0, &s.title, s.title_at.1)));
            }
        }
        out
    }

    /// What every frame shares, drawn after the mechanism's own fixed parts: the panels'
    /// frames (on `PANELS`), the titles and scale bars that do not change, and the
    /// force figures' captions when their scale is fixed (on `DIMENSIONS`).
    pub fn draw_titles(&self, d: &mut Drawing) {
        let dims = layer_of(d, layers::DIMENSIONS);
        let frames = layer_of(d, layers::PANELS);
        for (title, ll, ur) in &self.panels {
            let points = vec![*ll, Point::new(ur.x, ll.y), *ur, Point::new(ll.x, ur.y)];
            d.add(frames, Shape::Polyline { points, closed: true, width: 0.0 });
            title.draw(d, dims, self.title_at(*ll, *ur), self.sizes.text);
        }
        for (at, length, label) in &self.bars {
            scale_bar(d, dims, *at, *length, label, self.sizes);
        }
        if let Some(f) = &self.forces {
            let (c, at) = &f.table_caption;
            text(d, dims, *at, forces::NAME_HEIGHT * self.sizes.text, c);
            if self.choice == ScaleChoice::Fixed {
                for s in &f.figures {
                    text(d, dims, s.title_at.0, s.title_at.1, &s.title);
                }
            }
        }
    }

    /// The position's text (`φ1 = 30°`, `t = 0.25 s`) right-aligned at the top of the
    /// mechanism's panel, on `TEXT`.
    pub fn draw_position_text(&self, d: &mut Drawing, value: impl Into<Label>) {
        let Label { text: value, runs } = value.into();
        let text = layer_of(d, layers::TEXT);
        let ur = self.panels[0].2;
        let s = self.sizes;
        d.add(
            text,
            Shape::Text {
                runs,
                at: Point::new(ur.x - 0.6 * s.text, ur.y - 1.2 * s.text),
                height: s.text,
                value,
                halign: HAlign::Right,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        );
    }

    /// One position's polygons in their panels (position `k` of the run, or the nearest
    /// to a position between them): the velocity and acceleration polygons (their letters
    /// off the panel titles and scale bars, inside their panels), and the force figures with
    /// the table of magnitudes (the names off the captions, the table and each other); with
    /// scales per frame, each panel's title with its scale and its scale bar. Returns the
    /// scales drawn: k_v, k_a, and each force figure's k_f.
    pub fn draw_polygons(
        &self,
        d: &mut Drawing,
        k: usize,
        velocity: Option<&PointPolygon>,
        acceleration: Option<&PointPolygon>,
        force: Option<(&[ForcePolygon], &[Magnitude])>,
    ) -> FrameScales {
        let s = self.sizes;
        let mut keep_off = self.text_boxes();
        let mut drawn = FrameScales::default();
        let per_frame = self.choice == ScaleChoice::PerFrame;
        for (poly, slot, layer, out) in [
            (velocity, &self.velocity, layers::VELOCITY, &mut drawn.k_v),
            (acceleration, &self.acceleration, layers::ACCELERATION, &mut drawn.k_a),
        ] {
            let (Some(poly), Some(slot)) = (poly, slot) else { continue };
            let (scale, pole) = slot.place(k, Extent::of(poly.physical_points()), self.k_l);
            *out = Some(scale.per_mm);
            if per_frame {
                keep_off.extend(self.draw_slot_scale(d, slot, scale.per_mm));
            }
            let within = self.panel_of(slot);
            // Construction lines within the polygon's area and the letters' room around it.
            let room = Vector::new(LETTER_ROOM * s.text, LETTER_ROOM * s.text);
            let clip = labels::TextBox { min: slot.area.min - room, max: slot.area.max + room };
            polygon::draw_within(d, poly, layer, scale, pole, s, &keep_off, within, Some(clip));
        }
        if let (Some((figures, rows)), Some(cells)) = (force, &self.forces) {
            let within = self.panels.last().map(|p| labels::TextBox { min: p.1, max: p.2 });
            for (fig, slot) in figures.iter().zip(&cells.figures) {
                let (scale, pole) = slot.place(k, Extent::of(fig.physical_points()), self.k_l);
                drawn.k_f.push(scale.per_mm);
                if per_frame {
                    keep_off.extend(self.draw_slot_scale(d, slot, scale.per_mm));
                }
                let names = forces::draw_within(d, fig, scale, pole, s, &keep_off, within);
                keep_off.extend(names);
            }
            forces::table(d, rows, cells.table_at, cells.table_width, s);
        }
        drawn
    }

    /// The panel a polygon's slot is in, as a box for its letters to stay inside.
    fn panel_of(&self, slot: &Slot) -> Option<labels::TextBox> {
        let c = Point::from((slot.area.min.coords + slot.area.max.coords) / 2.0);
        self.panels
            .iter()
            .find(|p| c.x >= p.1.x && c.x <= p.2.x && c.y >= p.1.y && c.y <= p.2.y)
            .map(|p| labels::TextBox { min: p.1, max: p.2 })
    }

    /// A slot's title with its scale this frame and its scale bar (on `DIMENSIONS`);
    /// returns their boxes.
    fn draw_slot_scale(&self, d: &mut Drawing, slot: &Slot, per_mm: f64) -> Vec<labels::TextBox> {
        let dims = layer_of(d, layers::DIMENSIONS);
        let title = Title::Scale(slot.title_with(per_mm, 1.0 / self.k_l));
        title.draw(d, dims, slot.title_at.0, slot.title_at.1);
        let (at, h) = slot.title_at;
        let e = crate::draw::font::measure(&title.on_paper(), h);
        let w = title.width(self.units, h).max(e.width);
        let mut out =
            vec![labels::TextBox { min: at - Vector::new(0.0, e.descent), max: at + Vector::new(w, e.ascent) }];
        if let Some(at) = slot.bar_at {
            let value = bar_value(per_mm);
            let drawn = Scale::on_paper(per_mm, 1.0 / self.k_l).draw(Vector::new(value, 0.0)).x;
            out.push(scale_bar(d, dims, at, drawn, &format!("{} {}", scale_text(value), slot.unit), self.sizes));
        }
        out
    }
}

/// The scales one frame was drawn at (physical units per paper mm).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameScales {
    /// The velocity polygon's.
    pub k_v: Option<f64>,
    /// The acceleration polygon's.
    pub k_a: Option<f64>,
    /// Each force figure's.
    pub k_f: Vec<f64>,
}

/// The panels' rectangles (lower-left, upper-right; the mechanism's top-left at the
/// origin) for content boxes `boxes` (the mechanism's first, then one per `which`): the
/// polygons' panels in a column right of the mechanism ([`beside`]) or, for a flat
/// mechanism, in a row under it ([`under`]): the one of the two that takes less paper by
/// [`UNDER_GAIN`] (a long, low slider-crank beside a column of two polygons leaves its tall
/// panel mostly empty); the force panel under all, as wide as they are together.
fn arrange_panels(boxes: &[(Title, Vector)], which: &[Which], title_room: f64, gap: f64) -> Vec<(Point, Point)> {
    let side: Vec<usize> = (0..which.len()).filter(|&j| which[j] != Which::Forces).map(|j| j + 1).collect();
    let mut rects = beside(boxes, &side, title_room, gap);
    if side.len() >= 2 {
        let low = under(boxes, &side, title_room, gap);
        let area = |r: &[(Point, Point)]| {
            let (w, h) = r.iter().fold((0.0f64, 0.0f64), |(w, h), (lo, hi)| (w.max(hi.x), h.max(-lo.y)));
            w * h
        };
        if area(&low) < UNDER_GAIN * area(&rects) {
            rects = low;
        }
    }
    let width = rects.iter().map(|(_, hi)| hi.x).fold(0.0, f64::max);
    let height = rects.iter().map(|(lo, _)| -lo.y).fold(0.0, f64::max);
    for (j, w) in which.iter().enumerate() {
        if *w == Which::Forces {
            let b = boxes[j + 1].1;
            let top = -height - gap;
            rects[j + 1] = (Point::new(0.0, top - b.y - title_room), Point::new(width.max(b.x), top));
        }
    }
    rects
}

/// Below this share of the paper the column beside the mechanism takes, the polygons go in
/// a row under it (a [`PanelFrame`]'s layout).
pub const UNDER_GAIN: f64 = 0.85;

/// The mechanism on the left, the polygons' panels `side` (indices into `boxes`) stacked in a
/// column right of it: the shorter of the two stretched to the other's height, the spare
/// height shared. The force panel's rectangle is left for [`arrange_panels`].
fn beside(boxes: &[(Title, Vector)], side: &[usize], title_room: f64, gap: f64) -> Vec<(Point, Point)> {
    let mech = boxes[0].1 + Vector::new(0.0, title_room);
    let col_w = side.iter().map(|&i| boxes[i].1.x).fold(0.0, f64::max);
    let stack: f64 =
        side.iter().map(|&i| boxes[i].1.y + title_room).sum::<f64>() + gap * side.len().saturating_sub(1) as f64;
    let height = mech.y.max(stack);
    let spare = if side.is_empty() { 0.0 } else { (height - stack) / side.len() as f64 };
    let mut rects = vec![(Point::new(0.0, -height), Point::new(mech.x, 0.0)); boxes.len()];
    let x = mech.x + gap;
    let mut top = 0.0;
    for &i in side {
        let h = boxes[i].1.y + title_room + spare;
        rects[i] = (Point::new(x, top - h), Point::new(x + col_w, top));
        top -= h + gap;
    }
    rects
}

/// The mechanism on top, the polygons' panels `side` in a row under it: the narrower of the
/// two stretched to the other's width, the spare width shared.
fn under(boxes: &[(Title, Vector)], side: &[usize], title_room: f64, gap: f64) -> Vec<(Point, Point)> {
    let mech = boxes[0].1 + Vector::new(0.0, title_room);
    let row_h = side.iter().map(|&i| boxes[i].1.y + title_room).fold(0.0, f64::max);
    let row_w: f64 = side.iter().map(|&i| boxes[i].1.x).sum::<f64>() + gap * side.len().saturating_sub(1) as f64;
    let width = mech.x.max(row_w);
    let spare = if side.is_empty() { 0.0 } else { (width - row_w) / side.len() as f64 };
    let mut rects = vec![(Point::new(0.0, -mech.y), Point::new(width, 0.0)); boxes.len()];
    let top = -mech.y - gap;
    let mut x = 0.0;
    for &i in side {
        let w = boxes[i].1.x + spare;
        rects[i] = (Point::new(x, top - row_h), Point::new(x + w, top));
        x += w + gap;
    }
    rects
}

/// A left-aligned, baseline text on `layer`.
fn text(d: &mut Drawing, layer: usize, at: Point, height: f64, value: &str) {
    d.add(
        layer,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at,
            height,
            value: value.to_string(),
            halign: HAlign::Left,
            valign: VAlign::Baseline,
            rotation: 0.0,
        },
    );
}

/// The box of a left-aligned, baseline text as drawn.
fn text_box(at: Point, value: &str, height: f64) -> labels::TextBox {
    let e = crate::draw::font::measure(value, height);
    let w = widest_text_width(value, height).max(e.width);
    labels::TextBox { min: at - Vector::new(0.0, e.descent), max: at + Vector::new(w, e.ascent) }
}

/// The per-position extents of the velocity or acceleration polygon.
fn fixed_points(
    velocity: &Option<Vec<Option<Extent>>>,
    acceleration: &Option<Vec<Option<Extent>>>,
    which: Which,
) -> Vec<Option<Extent>> {
    match which {
        Which::Velocity => velocity.clone().unwrap_or_default(),
        _ => acceleration.clone().unwrap_or_default(),
    }
}

/// The scale of the forces drawn on the mechanism: the nice scale that draws the largest of
/// them at most [`MECHANISM_FORCE_FRACTION`] of the mechanism's drawn size `mechanism_mm`.
fn mechanism_force_scale(fs: &ForceSpec, mechanism_mm: f64) -> f64 {
    let largest = fs.on_mechanism.iter().map(|(_, v)| v.norm()).filter(|n| n.is_finite()).fold(0.0, f64::max);
    nice_scale(largest / (MECHANISM_FORCE_FRACTION * mechanism_mm))
}

/// How the force panel is arranged: its figures and the table in rows of up to
/// [`FORCE_ROW`] items, each under its caption; with fixed scales each figure's cell is its
/// drawn extent at the common scale, with a scale per frame a square cell for each.
#[derive(Debug, Clone)]
struct ForceLayout {
    /// The common scale (fixed scales; with scales per frame, the mechanism's).
    common: f64,
    /// The scale of the forces on the mechanism.
    mechanism_scale: Scale,
    /// The panel's content size (model units).
    size: Vector,
    /// Each item's cell from the content's lower-left: (lower-left, size, caption's left
    /// baseline point); the table last.
    cells: Vec<(Vector, Vector, Vector)>,
    /// The figures' extents over the run (fixed scales), their per-position sizes (per frame).
    extents: Vec<Option<Extent>>,
    /// The captions, the table's last.
    captions: Vec<String>,
    /// Room kept in a cell for the letters around a figure (per frame).
    room: f64,
    /// The side of the square a figure's scales are chosen for (per frame), model units.
    cell_side: f64,
    /// Rows of the table.
    row_count: usize,
    /// Width of the table.
    table_width: f64,
    /// Each figure's scales at each position (per frame).
    scales: Vec<Vec<f64>>,
    /// Each figure's physical size at each position (per frame).
    sides: Vec<Vec<Option<Vector>>>,
    /// Height of the captions.
    caption_h: f64,
    /// The strip of a cell's scale bar, and the bar's inset from the cell's left.
    bar_room: f64,
    bar_inset: f64,
}

impl ForceLayout {
    fn arrange(spec: &PanelSpec, fs: &ForceSpec, sizes: Sizes, target_mm: f64, k_l: f64) -> ForceLayout {
        let paper = 1.0 / k_l;
        let caption_h = forces::NAME_HEIGHT * sizes.text;
        let gap = 2.0 * sizes.text;
        let bar_room = scale_bar_room(sizes);
        let extents: Vec<Option<Extent>> =
            fs.figures.iter().map(|(_, e)| e.iter().copied().fold(None, Extent::union)).collect();
        let largest = extents.iter().flatten().map(Extent::size).fold(0.0, f64::max);
        let common = nice_scale(largest / target_mm);
        let room = LETTER_ROOM * sizes.text;
        let cell_side = FORCE_CELL_FRACTION * target_mm * k_l;
        // Each figure's content size (and per frame its scales), then the table.
        let mut items: Vec<(String, Vector)> = Vec::new();
        let (mut scales, mut all_sides) = (Vec::new(), Vec::new());
        for ((caption, per_position), all) in fs.figures.iter().zip(&extents) {
            let (content, widest) = match spec.scales {
                ScaleChoice::Fixed => {
                    let e = all.map_or(Vector::zeros(), |e| e.sides());
                    let widest = widest_text_width(caption, caption_h);
                    (Scale::on_paper(common, paper).draw(e) + Vector::new(0.0, 1.0 * room), widest)
                }
                ScaleChoice::PerFrame => {
                    let area = Vector::new(cell_side, cell_side) / k_l;
                    let sides: Vec<Option<Vector>> = per_position.iter().map(|e| e.map(|e| e.sides())).collect();
                    let k = sheet::frame_scales(&sides, area);
                    // Its caption with the widest of its scales, as the SVG or the DXF writes it.
                    let widest = k
                        .iter()
                        .map(|k| {
                            let c = scale_caption(&format!("{caption}   "), "k_f", *k, "N", paper);
                            caption_width(&c, spec.units, caption_h)
                        })
                        .fold(widest_text_width(caption, caption_h), f64::max);
                    scales.push(k);
                    all_sides.push(sides);
                    (Vector::new(cell_side + 2.0 * room, cell_side + 2.0 * room + bar_room), widest)
                }
            };
            let w = content.x.max(widest);
            items.push((caption.clone(), Vector::new(w, content.y)));
        }
        let table = forces::table_size(&fs.rows, fs.row_count, sizes);
        let table_w = table.x.max(widest_text_width(TABLE_CAPTION, caption_h));
        items.push((TABLE_CAPTION.to_string(), Vector::new(table_w, table.y)));
        // Rows from the top: each row as tall as its tallest item plus a caption band.
        let band = 2.0 * caption_h;
        let rows: Vec<&[(String, Vector)]> = items.chunks(FORCE_ROW).collect();
        let heights: Vec<f64> = rows.iter().map(|r| r.iter().map(|i| i.1.y).fold(0.0, f64::max) + band).collect();
        let total_h: f64 = heights.iter().sum::<f64>() + gap * (rows.len().saturating_sub(1)) as f64;
        let mut cells = Vec::new();
        let mut width: f64 = 0.0;
        let mut top = total_h;
        for (r, row) in rows.iter().enumerate() {
            let mut x = 0.0;
            for (_, sz) in row.iter() {
                let caption_at = Vector::new(x, top - 1.2 * caption_h);
                let ll = Vector::new(x, top - band - sz.y);
                cells.push((ll, *sz, caption_at));
                width = width.max(x + sz.x);
                x += sz.x + gap;
            }
            top -= heights[r] + gap;
        }
        let mechanism_scale = Scale::on_paper(
            match spec.scales {
                ScaleChoice::Fixed => common,
                ScaleChoice::PerFrame => mechanism_force_scale(fs, spec.size.max(f64::MIN_POSITIVE) * paper),
            },
            paper,
        );
        ForceLayout {
            common,
            mechanism_scale,
            size: Vector::new(width, total_h),
            cells,
            extents,
            captions: fs.figures.iter().map(|(c, _)| c.clone()).collect(),
            room,
            cell_side,
            row_count: fs.row_count,
            table_width: table.x,
            scales,
            sides: all_sides,
            caption_h,
            bar_room,
            bar_inset: 2.0 * sizes.small_text(),
        }
    }

    /// The cells placed with the content's lower-left at `origin`.
    fn place(self, origin: Point, choice: ScaleChoice, paper: f64) -> ForceCells {
        let n = self.captions.len();
        let mut figures = Vec::with_capacity(n);
        for (i, caption) in self.captions.iter().enumerate() {
            let (ll, sz, cap) = self.cells[i];
            let ll = origin + ll;
            let title_at = (origin + cap, self.caption_h);
            let slot = match choice {
                ScaleChoice::Fixed => {
                    let scale = Scale::on_paper(self.common, paper);
                    let e = self.extents[i].unwrap_or(Extent { min: Vector::zeros(), max: Vector::zeros() });
                    // Hanging from the top of its cell.
                    let drawn = scale.draw(e.sides());
                    let top_left = Point::new(ll.x, ll.y + sz.y);
                    let min = top_left - Vector::new(0.0, drawn.y);
                    Slot {
                        symbol: "k_f",
                        unit: "N".into(),
                        title: caption.clone(),
                        title_at,
                        area: Bounds { min, max: min + drawn },
                        bar_at: None,
                        scales: vec![self.common],
                        pole: Some(min - scale.draw(e.min)),
                        sides: Vec::new(),
                    }
                }
                ScaleChoice::PerFrame => Slot {
                    symbol: "k_f",
                    unit: "N".into(),
                    title: caption.clone(),
                    title_at,
                    // The square its scales were chosen for, over the strip of its scale
                    // bar, letter room all round, centred across a cell its caption widened.
                    area: {
                        let inset = Vector::new(0.5 * (sz.x - self.cell_side), self.bar_room + self.room);
                        Bounds { min: ll + inset, max: ll + inset + Vector::new(self.cell_side, self.cell_side) }
                    },
                    bar_at: Some(ll + Vector::new(self.bar_inset, 0.5 * self.bar_room)),
                    scales: self.scales.get(i).cloned().unwrap_or_default(),
                    pole: None,
                    sides: self.sides.get(i).cloned().unwrap_or_default(),
                },
            };
            figures.push(slot);
        }
        let (tll, tsz, tcap) = self.cells[n];
        ForceCells {
            figures,
            table_at: origin + tll + Vector::new(0.0, tsz.y),
            table_width: self.table_width,
            row_count: self.row_count,
            table_caption: (TABLE_CAPTION.to_string(), origin + tcap),
        }
    }
}
