//! The neutral drawing: a flat list of absolute primitives in model units, grouped on
//! named layers. Figures (in `crate::figure`) build a [`Drawing`]; the writers translate
//! it and know nothing about mechanisms:
//! [`dxf`] (R12 DXF for any CAD program), [`svg`] (SVG, y axis up as in CAD), `pdf`
//! (pages of drawings as one PDF),
//! `raster` (SVG to PNG with resvg and the bundled font). `pdf` and `raster` are behind the
//! features of the same names (`pdf`, `png`), which the command line has.
//!
//! Coordinates are model coordinates (the scene's units), y up. Angles are radians,
//! counter-clockwise from +x. Text heights, widths and arrow sizes are model lengths too,
//! so a drawing prints at any scale.

pub mod dxf;
pub mod font;
pub mod parts;
#[cfg(feature = "pdf")]
pub mod pdf;
#[cfg(feature = "png")]
pub mod raster;
pub mod runs;
pub mod svg;

/// DejaVu Sans, bundled (licence in assets/fonts/DejaVu-LICENSE.txt): the PNG writer renders
/// text with it and the PDF writer embeds it. Only in builds with one of them (features `png`,
/// `pdf`): the live page's module is 760 KB lighter without it (the SVG and the DXF name the
/// font; [`parts::text_width`] measures with a table of its advances).
#[cfg(any(feature = "png", feature = "pdf"))]
pub static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

use crate::geom::{Point, Vector};
pub use runs::{Run, RunKind, Runs};

/// An AutoCAD Color Index (ACI) colour: 1 red, 2 yellow, 3 green, 4 cyan, 5 blue,
/// 6 magenta, 7 black on a white sheet (white on black), 8 dark grey, 9 light grey,
/// 10–249 the ACI wheel, 250–255 greys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Aci(pub u8);

impl Aci {
    /// ACI 1.
    pub const RED: Aci = Aci(1);
    /// ACI 2.
    pub const YELLOW: Aci = Aci(2);
    /// ACI 3.
    pub const GREEN: Aci = Aci(3);
    /// ACI 4.
    pub const CYAN: Aci = Aci(4);
    /// ACI 5.
    pub const BLUE: Aci = Aci(5);
    /// ACI 6.
    pub const MAGENTA: Aci = Aci(6);
    /// ACI 7: black on paper, white on a dark screen.
    pub const BLACK: Aci = Aci(7);
    /// ACI 8.
    pub const DARK_GREY: Aci = Aci(8);
    /// ACI 9.
    pub const LIGHT_GREY: Aci = Aci(9);
    /// ACI 30: orange.
    pub const ORANGE: Aci = Aci(30);

    /// sRGB of this colour as drawn on a white sheet (ACI 7 is black there).
    pub fn rgb(self) -> (u8, u8, u8) {
        match self.0 {
            1 => (255, 0, 0),
            2 => (200, 170, 0), // pure yellow is unreadable on white
            3 => (0, 160, 0),
            4 => (0, 160, 200),
            5 => (0, 0, 255),
            6 => (200, 0, 200),
            7 | 0 => (0, 0, 0),
            8 => (128, 128, 128),
            9 => (192, 192, 192),
            30 => (255, 127, 0),
            250..=255 => {
                let g = [51, 91, 132, 173, 214, 255][(self.0 - 250) as usize];
                (g, g, g)
            }
            n => aci_wheel(n),
        }
    }
}

/// The ACI colour wheel (10–249): hue in steps of 15°, five lightness/saturation rows.
fn aci_wheel(n: u8) -> (u8, u8, u8) {
    let hue = ((n as u32 - 10) / 10) as f64 * 15.0;
    let row = (n as u32 - 10) % 10;
    let value = [1.0, 1.0, 0.8, 0.8, 0.6, 0.6, 0.5, 0.5, 0.3, 0.3][row as usize];
    let sat = if row.is_multiple_of(2) { 1.0 } else { 0.5 };
    let c = value * sat;
    let x = c * (1.0 - ((hue / 60.0) % 2.0 - 1.0).abs());
    let m = value - c;
    let (r, g, b) = match (hue / 60.0) as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let to = |v: f64| ((v + m) * 255.0).round() as u8;
    (to(r), to(g), to(b))
}

/// Line pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum LineType {
    /// Solid line.
    #[default]
    Continuous,
    /// Dashes; the DXF writer defines the DASHED pattern in the LTYPE table.
    Dashed,
}

/// A named layer with its default colour and line type.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// Layer name as written to DXF (A–Z, 0–9, `_`, `-`; the writers do not rename).
    pub name: String,
    /// Colour of entities on the layer that have none of their own.
    pub color: Aci,
    /// Line type of entities on the layer that have none of their own.
    pub linetype: LineType,
    /// Whether the layer is shown when the file is opened. A DXF layer that is off keeps its
    /// entities (the user switches it on in the layer manager; R12 writes a negative colour
    /// in the LAYER table); the SVG and PDF writers draw every layer of the drawing they are
    /// given. New layers are on.
    pub on: bool,
}

/// Horizontal text alignment relative to the insertion point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum HAlign {
    /// Text starts at the point.
    #[default]
    Left,
    /// Text is centred on the point.
    Center,
    /// Text ends at the point.
    Right,
}

/// Vertical text alignment relative to the insertion point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VAlign {
    /// The baseline passes through the point.
    #[default]
    Baseline,
    /// The middle of capital letters is at the point.
    Middle,
    /// The top of capital letters is at the point.
    Top,
}

/// One drawing primitive, in model coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A full circle.
    Circle {
        /// Centre.
        center: Point,
        /// Radius (> 0).
        radius: f64,
    },
    /// A circular arc from `start` to `end`, counter-clockwise (radians).
    Arc {
        /// Centre.
        center: Point,
        /// Radius (> 0).
        radius: f64,
        /// Start angle, radians from +x.
        start: f64,
        /// End angle, radians from +x; the arc runs counter-clockwise from `start`.
        end: f64,
    },
    /// A straight segment.
    Line {
        /// Start point.
        from: Point,
        /// End point.
        to: Point,
    },
    /// A polyline (AutoCAD `PLINE`), optionally closed, with a constant width
    /// (0 = thinnest line the reader draws).
    Polyline {
        /// Vertices, at least two.
        points: Vec<Point>,
        /// Whether the last vertex joins the first.
        closed: bool,
        /// Constant width in model units (AutoCAD `PLINE … W w w`).
        width: f64,
    },
    /// A filled polygon (DXF SOLID for three or four vertices): arrowheads, hatch marks.
    Filled {
        /// Three or four vertices, in order around the outline.
        points: Vec<Point>,
    },
    /// A vector drawn as a line with a filled arrowhead at `to` (the seeds' `Sageti`).
    Arrow {
        /// Tail.
        from: Point,
        /// Tip, where the arrowhead is.
        to: Point,
        /// Arrowhead length (model units); the head is shortened on short vectors.
        head: f64,
    },
    /// A single line of text.
    Text {
        /// Insertion point, interpreted with `halign` and `valign`.
        at: Point,
        /// Cap height in model units.
        height: f64,
        /// The text, flat (plain; `°`, `φ`, `ω`, `ε`, `π`, `′` are fine): as the DXF writes it.
        value: String,
        /// Which parts of `value` the SVG, PNG and PDF draw as subscripts ([`Runs`]; none:
        /// all at `height`).
        runs: Runs,
        /// Horizontal alignment.
        halign: HAlign,
        /// Vertical alignment.
        valign: VAlign,
        /// Rotation, radians counter-clockwise.
        rotation: f64,
    },
    /// A caption that states a drawing scale (`Velocity polygon   k_v = 0.1 (m/s)/mm`), its
    /// value written by each writer for the millimetres it draws a model unit in
    /// ([`ScaleCaption::text`]): on paper in the SVG and PDF, in the DXF's own millimetres
    /// in the DXF. So a length measured where the user measures, times the printed k, is
    /// the value (design.md §4). Placed and aligned as a [`Shape::Text`].
    ScaleText {
        /// Insertion point, interpreted with `halign` and `valign`.
        at: Point,
        /// Cap height in model units.
        height: f64,
        /// What the caption says.
        caption: ScaleCaption,
        /// Horizontal alignment.
        halign: HAlign,
        /// Vertical alignment.
        valign: VAlign,
        /// Rotation, radians counter-clockwise.
        rotation: f64,
    },
    /// An angular dimension (AutoCAD `DIMANGULAR`, 3-point form): the angle swept
    /// counter-clockwise from the ray `vertex→first` to the ray `vertex→second`, drawn as an
    /// arc of radius `radius` about `vertex` with arrowheads and `text` at its middle.
    AngularDimension {
        /// Vertex of the angle.
        vertex: Point,
        /// A point on the first ray.
        first: Point,
        /// A point on the second ray.
        second: Point,
        /// Radius of the dimension arc.
        radius: f64,
        /// The text shown (e.g. `φ1 = 75.77°`), flat: what the DXF writes.
        text: String,
        /// Its runs where the writer draws subscripts (SVG, PNG, PDF: `φ` + `1` of `φ1`,
        /// [`Runs::subscript`]); [`Runs::flat`] draws the whole text at its size.
        runs: Runs,
    },
    /// A linear dimension (AutoCAD `DIMLINEAR`/rotated): the distance between `p1` and
    /// `p2` measured along direction `angle`, with the dimension line through `line_at`.
    LinearDimension {
        /// First definition point (start of the first extension line).
        p1: Point,
        /// Second definition point.
        p2: Point,
        /// A point the dimension line passes through.
        line_at: Point,
        /// Direction of measurement, radians (0 = horizontal dimension).
        angle: f64,
        /// The text shown (e.g. `25 ±0.1`).
        text: String,
        /// The marks at its ends and where its text sits along the line (the default: an
        /// arrowhead at each end, the text placed by [`parts::linear_layout`]).
        marks: LinearMarks,
    },
}

/// A scale stated in words: `before`, the scale's value in the medium it is written to,
/// `after` (`Velocity polygon   k_v = ` 0.1 ` (m/s)/mm`). The value is a quantity per
/// millimetre of the medium: [`ScaleCaption::per_unit`] (the quantity per model unit the
/// figure draws) over the medium's millimetres per model unit.
#[derive(Debug, Clone, PartialEq)]
pub struct ScaleCaption {
    /// The text before the value (`Mechanism   k_l = `).
    pub before: String,
    /// The quantity one model unit of the drawing stands for, in the caption's unit: 1 for a
    /// length scale (a model unit is a model unit), `k_v` × the paper millimetres per model
    /// unit for a velocity polygon drawn at `k_v` per paper millimetre.
    pub per_unit: f64,
    /// The text after the value, with the unit per millimetre (` (m/s)/mm`).
    pub after: String,
    /// Paper millimetres per model unit of the figure the caption is on: the medium of
    /// [`ScaleCaption::on_paper`], for a writer that has no scale of its own.
    pub paper_mm_per_unit: f64,
    /// A second scale stated after this one on the same line (`Mechanism   k_l = 10 mm/mm`
    /// then `, forces k_f = 200 N/mm`), written for the same medium.
    pub then: Option<Box<ScaleCaption>>,
}

impl ScaleCaption {
    /// A caption for a scale of `per_mm` per paper millimetre on a figure printed at
    /// `paper_mm_per_unit` paper millimetres per model unit.
    pub fn new(before: impl Into<String>, per_mm: f64, after: impl Into<String>, paper_mm_per_unit: f64) -> Self {
        ScaleCaption {
            before: before.into(),
            per_unit: per_mm * paper_mm_per_unit,
            after: after.into(),
            paper_mm_per_unit,
            then: None,
        }
    }

    /// This caption with `next` stated after it on the same line (after any it already has).
    pub fn then(mut self, next: ScaleCaption) -> Self {
        self.then = Some(Box::new(match self.then.take() {
            Some(t) => t.then(next),
            None => next,
        }));
        self
    }

    /// The caption for a medium that draws a model unit `mm_per_unit` millimetres long:
    /// the value [`ScaleCaption::per_unit`] / `mm_per_unit`, written in plain decimals
    /// (no exponent) to 10 significant digits.
    pub fn text(&self, mm_per_unit: f64) -> String {
        let next = self.then.as_ref().map_or_else(String::new, |t| t.text(mm_per_unit));
        format!("{}{}{}{next}", self.before, plain_decimal(self.per_unit / mm_per_unit), self.after)
    }

    /// The caption on the figure's paper.
    pub fn on_paper(&self) -> String {
        self.text(self.paper_mm_per_unit)
    }
}

/// `v` in plain decimals with 10 significant digits, trailing zeros trimmed (`0.04`, `2500`,
/// `0.000125`); a non-finite value as `?`.
pub fn plain_decimal(v: f64) -> String {
    if !v.is_finite() {
        return "?".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let decimals = (9.0 - libm::floor(libm::log10(v.abs()))).clamp(0.0, 300.0) as usize;
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.') } else { s.as_str() };
    s.to_string()
}

/// How a linear dimension marks its two ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DimEnds {
    /// A filled arrowhead at each end: the drafting default, for a distance between two
    /// features where neither is the reference.
    #[default]
    Arrows,
    /// A dimension measured from a base (seed 001, Humienny 1989: "points where a dimension
    /// starts are marked with a small circle, end points with an arrow"): a small open
    /// circle ([`parts::BASE_CIRCLE_RADIUS`]) at the foot of the first definition point
    /// (the base) and an arrowhead at the second's (the end), so the base and the sign of
    /// `x_end − x_base` read off the drawing. AutoCAD draws the same with `DIMSAH` on and
    /// `DIMBLK1` an open dot.
    FromBase,
}

/// What a linear dimension draws beyond its [`Shape::LinearDimension`] geometry: the mark at
/// each end and, optionally, where its text sits along the dimension line. The default is
/// what `Shape::LinearDimension` draws by itself ([`parts::explode_dimension`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LinearMarks {
    /// The marks at the two ends.
    pub ends: DimEnds,
    /// Middle of the text, as a signed distance (model units) from the foot of the first
    /// extension line along the direction the text reads ([`parts::LinearLayout::reading`]);
    /// `None` places it as [`parts::linear_layout`] does (between the extension lines when it
    /// fits, else beside one). A text placed elsewhere gets the dimension line extended
    /// under it.
    pub text_along: Option<f64>,
}

/// A shape on a layer, with optional colour and line type overrides.
#[derive(Debug, Clone, PartialEq)]
pub struct Entity {
    /// Index into [`Drawing::layers`].
    pub layer: usize,
    /// Own colour; `None` draws in the layer's colour.
    pub color: Option<Aci>,
    /// Own line type; `None` uses the layer's.
    pub linetype: Option<LineType>,
    /// The geometry.
    pub shape: Shape,
}

/// Sizes of dimension text and arrowheads (DXF `$DIMTXT`, `$DIMASZ`), model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DimStyle {
    /// Text height of dimension text.
    pub text_height: f64,
    /// Arrowhead length of dimensions.
    pub arrow_size: f64,
}

/// The neutral drawing: layers and entities in model units, in drawing order.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Layers in creation order; layer 0 is always `"0"`.
    pub layers: Vec<Layer>,
    /// Entities in drawing order (later ones on top in SVG).
    pub entities: Vec<Entity>,
    /// Dimension text and arrow sizes.
    pub dim_style: DimStyle,
    /// Paper millimetres per model unit when the drawing is printed at its stated scale
    /// (for a mechanism drawn at k_l = 0.002 m/mm in a scene in metres: 1/0.002 = 500);
    /// `None` for a drawing with no paper scale. The SVG writer sizes the page in mm from it
    /// (`width="…mm"`, viewBox in paper mm); the DXF ignores it (model space is true size).
    pub paper_mm_per_unit: Option<f64>,
}

impl Shape {
    /// A [`Shape::ScaleText`] as the [`Shape::Text`] a medium drawing a model unit
    /// `mm_per_unit` millimetres long writes (its paper's when `None`); `None` for any other
    /// shape.
    pub fn scale_text_in(&self, mm_per_unit: Option<f64>) -> Option<Shape> {
        let Shape::ScaleText { at, height, caption, halign, valign, rotation } = self else { return None };
        let value = caption.text(mm_per_unit.unwrap_or(caption.paper_mm_per_unit));
        let runs = Runs::underscored(&value);
        Some(Shape::Text {
            at: *at,
            height: *height,
            value,
            runs,
            halign: *halign,
            valign: *valign,
            rotation: *rotation,
        })
    }

    /// Every number of the shape (coordinates, sizes, angles), in a fixed order.
    pub fn numbers(&self) -> Vec<f64> {
        let xy = |p: &Point| [p.x, p.y];
        match self {
            Shape::Circle { center, radius } => vec![center.x, center.y, *radius],
            Shape::Arc { center, radius, start, end } => vec![center.x, center.y, *radius, *start, *end],
            Shape::Line { from, to } => [xy(from), xy(to)].concat(),
            Shape::Polyline { points, width, .. } => {
                points.iter().flat_map(xy).chain(std::iter::once(*width)).collect()
            }
            Shape::Filled { points } => points.iter().flat_map(xy).collect(),
            Shape::Arrow { from, to, head } => [&xy(from)[..], &xy(to), &[*head]].concat(),
            Shape::Text { at, height, rotation, .. } => vec![at.x, at.y, *height, *rotation],
            Shape::ScaleText { at, height, rotation, caption, .. } => {
                let mut v = vec![at.x, at.y, *height, *rotation];
                let mut next = Some(caption);
                while let Some(c) = next {
                    v.extend([c.per_unit, c.paper_mm_per_unit]);
                    next = c.then.as_deref();
                }
                v
            }
            Shape::AngularDimension { vertex, first, second, radius, .. } => {
                [&xy(vertex)[..], &xy(first), &xy(second), &[*radius]].concat()
            }
            Shape::LinearDimension { p1, p2, line_at, angle, .. } => {
                [&xy(p1)[..], &xy(p2), &xy(line_at), &[*angle]].concat()
            }
        }
    }

    /// The text the shape writes, if any.
    pub fn text(&self) -> Option<&str> {
        match self {
            Shape::Text { value, .. } => Some(value),
            Shape::AngularDimension { text, .. } | Shape::LinearDimension { text, .. } => Some(text),
            _ => None,
        }
    }
}

impl Drawing {
    /// The first entity with a number that is not finite, or whose text writes one (`NaN`,
    /// `inf`: [`crate::text::non_finite_word`]), described for a message (its index, layer
    /// and what is wrong); `None` when every number is finite. The scale and the dimension
    /// style are numbers of the drawing too.
    pub fn first_non_finite(&self) -> Option<String> {
        let style = [self.dim_style.text_height, self.dim_style.arrow_size, self.paper_mm_per_unit.unwrap_or(1.0)];
        if style.iter().any(|v| !v.is_finite()) {
            return Some("its scale or dimension style".into());
        }
        self.entities.iter().enumerate().find_map(|(i, e)| {
            let layer = self.layers.get(e.layer).map_or("?", |l| l.name.as_str());
            if let Some(v) = e.shape.numbers().into_iter().find(|v| !v.is_finite()) {
                return Some(format!("entity {i} on layer {layer} has the coordinate or size {v}"));
            }
            let text = e.shape.text()?;
            crate::text::non_finite_word(text)
                .map(|w| format!("the text \"{}\" on layer {layer} writes {w}", crate::text::excerpt(text)))
        })
    }
}

/// Axis-aligned bounding box in model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl Bounds {
    fn of_point(p: Point) -> Bounds {
        Bounds { min: p, max: p }
    }
    fn add(&mut self, p: Point) {
        self.min = Point::new(self.min.x.min(p.x), self.min.y.min(p.y));
        self.max = Point::new(self.max.x.max(p.x), self.max.y.max(p.y));
    }
    /// Width (x extent).
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }
    /// Height (y extent).
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }
}

impl Drawing {
    /// An empty drawing with layer `"0"` and the given dimension style.
    pub fn new(dim_style: DimStyle) -> Drawing {
        Drawing {
            layers: vec![Layer { name: "0".into(), color: Aci::BLACK, linetype: LineType::Continuous, on: true }],
            entities: Vec::new(),
            dim_style,
            paper_mm_per_unit: None,
        }
    }

    /// Index of the layer `name`, created with `color` and `linetype` if it is new
    /// (an existing layer keeps its settings).
    pub fn layer(&mut self, name: &str, color: Aci, linetype: LineType) -> usize {
        if let Some(i) = self.layers.iter().position(|l| l.name == name) {
            return i;
        }
        self.layers.push(Layer { name: name.to_string(), color, linetype, on: true });
        self.layers.len() - 1
    }

    /// Switches the layer `name` on or off ([`Layer::on`]); nothing happens when the drawing
    /// has no such layer.
    pub fn set_layer_on(&mut self, name: &str, on: bool) {
        if let Some(l) = self.layers.iter_mut().find(|l| l.name == name) {
            l.on = on;
        }
    }

    /// Adds `shape` on `layer` in the layer's colour and line type.
    pub fn add(&mut self, layer: usize, shape: Shape) {
        self.entities.push(Entity { layer, color: None, linetype: None, shape });
    }

    /// Adds `shape` on `layer` with its own colour.
    pub fn add_colored(&mut self, layer: usize, color: Aci, shape: Shape) {
        self.entities.push(Entity { layer, color: Some(color), linetype: None, shape });
    }

    /// Appends `src`'s entities on layers of the same names (created with `src`'s layer
    /// colour and line type where new); each entity keeps its own overrides. An animation
    /// frame is the shared drawing with one position's drawing appended this way.
    pub fn append(&mut self, src: &Drawing) {
        let map: Vec<usize> = src.layers.iter().map(|l| self.layer(&l.name, l.color, l.linetype)).collect();
        self.entities.reserve(src.entities.len());
        for e in &src.entities {
            self.entities.push(Entity {
                layer: map[e.layer],
                color: e.color,
                linetype: e.linetype,
                shape: e.shape.clone(),
            });
        }
    }

    /// Appends every entity of `src` on the one layer `layer` (created black and continuous
    /// where new), each with the colour and line type it had in `src` written on the entity:
    /// one position of an animation on its own DXF layer (`POS_000`, …) still shows its
    /// velocities green and its construction lines dashed.
    pub fn append_on_layer(&mut self, src: &Drawing, layer: &str) {
        let target = self.layer(layer, Aci::BLACK, LineType::Continuous);
        // Layer "0" of `src` keeps its entities too: everything lands on `layer`.
        self.entities.reserve(src.entities.len());
        for e in &src.entities {
            self.entities.push(Entity {
                layer: target,
                color: Some(src.color_of(e)),
                linetype: Some(src.linetype_of(e)),
                shape: e.shape.clone(),
            });
        }
    }

    /// The drawing moved and resized: every point p to `offset + scale·p`, every length
    /// (radii, widths, text heights, arrowheads) times `scale` (> 0); dimensions exploded
    /// first into the lines, arrowheads and texts their own style draws, so that they keep
    /// their look in a drawing of another style. A figure placed on a page of a report.
    pub fn mapped(&self, scale: f64, offset: Vector) -> Drawing {
        let p = |q: &Point| Point::from(offset + q.coords * scale);
        let map = |s: &Shape| -> Shape {
            match s {
                Shape::Circle { center, radius } => Shape::Circle { center: p(center), radius: radius * scale },
                Shape::Arc { center, radius, start, end } => {
                    Shape::Arc { center: p(center), radius: radius * scale, start: *start, end: *end }
                }
                Shape::Line { from, to } => Shape::Line { from: p(from), to: p(to) },
                Shape::Polyline { points, closed, width } => {
                    Shape::Polyline { points: points.iter().map(p).collect(), closed: *closed, width: width * scale }
                }
                Shape::Filled { points } => Shape::Filled { points: points.iter().map(p).collect() },
                Shape::Arrow { from, to, head } => Shape::Arrow { from: p(from), to: p(to), head: head * scale },
                Shape::Text { at, height, value, runs, halign, valign, rotation } => Shape::Text {
                    at: p(at),
                    height: height * scale,
                    value: value.clone(),
                    runs: runs.clone(),
                    halign: *halign,
                    valign: *valign,
                    rotation: *rotation,
                },
                // Exploded before mapping (see below).
                other => other.clone(),
            }
        };
        let mut out = Drawing {
            layers: self.layers.clone(),
            entities: Vec::with_capacity(self.entities.len()),
            dim_style: DimStyle {
                text_height: self.dim_style.text_height * scale,
                arrow_size: self.dim_style.arrow_size * scale,
            },
            paper_mm_per_unit: self.paper_mm_per_unit.map(|k| k / scale),
        };
        for e in &self.entities {
            match &e.shape {
                dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                    for part in parts::explode_dimension(dim, &self.dim_style) {
                        out.entities.push(Entity { shape: map(&part), ..e.clone() });
                    }
                }
                s => out.entities.push(Entity { shape: map(s), ..e.clone() }),
            }
        }
        out
    }

    /// Adds an entity as given.
    pub fn push(&mut self, entity: Entity) {
        self.entities.push(entity);
    }

    /// A left/baseline [`Shape::ScaleText`] without rotation.
    pub fn scale_text(&mut self, layer: usize, at: Point, height: f64, caption: ScaleCaption) {
        self.add(
            layer,
            Shape::ScaleText { at, height, caption, halign: HAlign::Left, valign: VAlign::Baseline, rotation: 0.0 },
        );
    }

    /// Convenience: a left/baseline text without rotation.
    pub fn text(&mut self, layer: usize, at: Point, height: f64, value: impl Into<String>) {
        self.add(
            layer,
            Shape::Text {
                at,
                height,
                value: value.into(),
                runs: Runs::flat(),
                halign: HAlign::Left,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        );
    }

    /// Colour an entity is drawn in (its own, else its layer's).
    pub fn color_of(&self, e: &Entity) -> Aci {
        e.color.unwrap_or(self.layers[e.layer].color)
    }

    /// Line type an entity is drawn with (its own, else its layer's).
    pub fn linetype_of(&self, e: &Entity) -> LineType {
        e.linetype.unwrap_or(self.layers[e.layer].linetype)
    }

    /// Bounding box of everything drawn (text approximated by its insertion box),
    /// or `None` for an empty drawing.
    pub fn bounds(&self) -> Option<Bounds> {
        self.bounds_of(self.entities.iter())
    }

    /// Bounding box of the given entities.
    pub fn bounds_of<'a>(&self, entities: impl Iterator<Item = &'a Entity>) -> Option<Bounds> {
        let mut b: Option<Bounds> = None;
        let mut add = |p: Point| match b.as_mut() {
            None => b = Some(Bounds::of_point(p)),
            Some(b) => b.add(p),
        };
        for e in entities {
            shape_extent_points(&e.shape, &self.dim_style, &mut add);
        }
        b
    }
}

/// The corners of a text's box as drawn in DejaVu Sans ([`font::measure_runs`]: its advances,
/// a subscript's smaller and lowered,
/// from the baseline less its deepest descender to its highest glyph, at least the cap
/// height), turned with the text about its insertion point: lower-left, lower-right,
/// upper-right, upper-left; a scale's caption as its paper writes it. `None` for a shape that
/// is not a text.
pub fn text_corners(shape: &Shape) -> Option<[Point; 4]> {
    if let Some(text) = shape.scale_text_in(None) {
        return text_corners(&text);
    }
    let Shape::Text { at, height, value, runs, halign, valign, rotation } = shape else { return None };
    let e = font::measure_runs(value, runs, *height);
    let x0 = match halign {
        HAlign::Left => 0.0,
        HAlign::Center => -0.5 * e.width,
        HAlign::Right => -e.width,
    };
    let base = match valign {
        VAlign::Baseline => 0.0,
        VAlign::Middle => -0.5 * height,
        VAlign::Top => -height,
    };
    let (y0, y1) = (base - e.descent, base + e.ascent);
    let (sin, cos) = if *rotation == 0.0 { (0.0, 1.0) } else { (libm::sin(*rotation), libm::cos(*rotation)) };
    let turn = |x: f64, y: f64| *at + Vector::new(cos * x - sin * y, sin * x + cos * y);
    Some([turn(x0, y0), turn(x0 + e.width, y0), turn(x0 + e.width, y1), turn(x0, y1)])
}

/// Calls `add` with points whose bounding box covers the shape (dimensions: their
/// exploded geometry, as drawn).
fn shape_extent_points(shape: &Shape, style: &DimStyle, add: &mut impl FnMut(Point)) {
    match shape {
        Shape::Circle { center, radius } => {
            add(center + Vector::new(-radius, -radius));
            add(center + Vector::new(*radius, *radius));
        }
        Shape::Arc { center, radius, start, end } => {
            // The end points and every axis direction the arc passes through.
            let sweep = parts::arc_sweep(*start, *end);
            add(crate::geom::polar(*center, *radius, *start));
            add(crate::geom::polar(*center, *radius, start + sweep));
            for k in 0..4 {
                let axis = k as f64 * std::f64::consts::FRAC_PI_2;
                if crate::geom::normalize_angle(axis - start) <= sweep {
                    add(crate::geom::polar(*center, *radius, axis));
                }
            }
        }
        Shape::Line { from, to } | Shape::Arrow { from, to, .. } => {
            add(*from);
            add(*to);
        }
        Shape::Polyline { points, .. } | Shape::Filled { points } => points.iter().for_each(|p| add(*p)),
        Shape::ScaleText { .. } => {
            if let Some(text) = shape.scale_text_in(None) {
                shape_extent_points(&text, style, add);
            }
        }
        Shape::Text { .. } => {
            if let Some([a, b, c, d]) = text_corners(shape) {
                [a, b, c, d].into_iter().for_each(&mut *add);
            }
        }
        Shape::AngularDimension { .. } | Shape::LinearDimension { .. } => {
            for part in parts::explode_dimension(shape, style) {
                shape_extent_points(&part, style, add);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A caption states its scale per millimetre of the medium: the four-bar's velocity
    /// polygon at k_v = 0.1 (m/s)/mm on paper at k_l = 0.0025 m/mm (400 paper mm per metre)
    /// is 0.04 (m/s)/mm in a DXF that draws a metre as 1000 mm.
    #[test]
    fn a_scale_caption_states_the_scale_of_its_medium() {
        let c = ScaleCaption::new("k_v = ", 0.1, " (m/s)/mm", 1.0 / 0.0025);
        assert_eq!(c.on_paper(), "k_v = 0.1 (m/s)/mm");
        assert_eq!(c.text(1000.0), "k_v = 0.04 (m/s)/mm");
        let shape = Shape::ScaleText {
            at: Point::new(1.0, 2.0),
            height: 3.0,
            caption: c,
            halign: HAlign::Right,
            valign: VAlign::Top,
            rotation: 0.5,
        };
        let text = |mm| match shape.scale_text_in(mm) {
            Some(Shape::Text { value, at, halign: HAlign::Right, valign: VAlign::Top, .. })
                if at == Point::new(1.0, 2.0) =>
            {
                value
            }
            other => panic!("{other:?}"),
        };
        assert_eq!((text(None), text(Some(1000.0))), ("k_v = 0.1 (m/s)/mm".into(), "k_v = 0.04 (m/s)/mm".into()));
        for (v, s) in [(0.001, "0.001"), (2500.0, "2500"), (1.25e-4, "0.000125"), (1e5, "100000"), (0.1 + 0.2, "0.3")] {
            assert_eq!(plain_decimal(v), s);
        }
        assert_eq!(
            (plain_decimal(0.0), plain_decimal(f64::NAN), plain_decimal(-0.5)),
            ("0".into(), "?".into(), "-0.5".into())
        );
    }

    #[test]
    fn arc_bounds_cover_only_the_drawn_part() {
        let mut d = Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 });
        // Quarter arc from 0° to 90° of radius 2 about (1, 1): box (1,1)–(3,3).
        d.add(
            0,
            Shape::Arc { center: Point::new(1.0, 1.0), radius: 2.0, start: 0.0, end: std::f64::consts::FRAC_PI_2 },
        );
        let b = d.bounds().unwrap();
        assert!((b.min - Point::new(1.0, 1.0)).norm() < 1e-12 && (b.max - Point::new(3.0, 3.0)).norm() < 1e-12);
        // 300° → 40° passes through 0°: x reaches centre + r.
        let mut d = Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 });
        d.add(
            0,
            Shape::Arc {
                center: Point::new(0.0, 0.0),
                radius: 1.0,
                start: 300f64.to_radians(),
                end: 40f64.to_radians(),
            },
        );
        let b = d.bounds().unwrap();
        assert!((b.max.x - 1.0).abs() < 1e-12 && (b.min.x - 0.5).abs() < 1e-12);
    }
}
