//! DXF writer: AutoCAD R12 (AC1009) by default, the version every CAD program reads; R2000
//! and R2007 on request. See `../shared/dxf-notes.md` and `docs/dxf.md` (what each reader
//! shows) for what was measured.
//!
//! Every file is in millimetres: [`to_bytes`] first scales the drawing by
//! [`DxfOptions::mm_per_unit`] (a scene in metres: 1000). Dimensions are DIMENSION entities
//! with their blocks, or with [`Dimensions::Exploded`] the blocks' entities in model space.
//!
//! How it is written: R12 entirely by hand (`r12.rs`, its HEADER and TABLES in `r12/head.rs`),
//! straight into the output buffer in exactly the form the `dxf` crate and the fix-up pass
//! below give them, because the crate route (a struct per entity, a `String` per value, a
//! re-parse of the whole text) took about 185 ms for the four-bar run's 8 MB animation
//! drawing against about 15 ms by hand, and because the live page's module is smaller
//! without the crate. The crate route (`via_crate.rs`, Cargo feature `dxf-r2000`, which the
//! command line has) stays as the reference, `to_bytes_via_crate`, and the tests compare
//! the two byte for byte; R2000 and R2007 are written entirely by the crate, and a build
//! without the feature (the page's) refuses them ([`DxfError::NotInThisBuild`]).
//!
//! What is written (R12):
//! - HEADER: fixed, no timestamps (`$TDCREATE`/`$TDUPDATE` = 2415021.0, i.e. 1 Jan 1900, the
//!   DXF epoch), `$EXTMIN/$EXTMAX` from [`Drawing::bounds`], `$LIMMIN/$LIMMAX` and
//!   `$PLIMMIN/$PLIMMAX` from the bounds with a 5 % margin grown to at least A4 ([`MIN_SHEET_MM`])
//!   and `$PINSBASE` = −`$PLIMMIN`
//!   (LibreCAD prints the sheet `$PLIMMIN`–`$PLIMMAX` with the drawing's origin at `$PINSBASE`),
//!   `$DIMTXT`, `$DIMASZ` (and `$DIMEXO`, `$DIMEXE`, `$DIMGAP`, `$DIMTAD`) from
//!   [`Drawing::dim_style`] as [`parts::explode_dimension`] draws them, `$LTSCALE` = 1,
//!   `$TEXTSTYLE` and `$DIMTXSTY` = [`TEXT_STYLE`]. R12 has no `$INSUNITS`/`$MEASUREMENT`
//!   (R2000+ states mm and metric).
//! - TABLES: LTYPE `CONTINUOUS` and `DASHED` (pattern from [`parts::dash_pattern`], scaled to
//!   the drawing); LAYER with each layer's ACI colour and line type (a layer that is not
//!   [`super::Layer::on`] is off and frozen: a negative colour and flag 1, since AutoCAD and
//!   ezdxf hide a layer that is off, LibreCAD one that is frozen); STYLE `STANDARD` and
//!   [`TEXT_STYLE`]; DIMSTYLE `STANDARD` with the drawing's dimension sizes; APPID `ACAD`;
//!   VPORT `*ACTIVE` centred on the drawing. Every record has its handle (group 5; 105 in
//!   DIMSTYLE, where 5 is `$DIMBLK`): FreeCAD reads no LAYER without one.
//! - BLOCKS: one anonymous block `*D1`, `*D2`, … per dimension holding its exploded geometry
//!   ([`parts::explode_dimension`]: lines, arc, SOLID arrowheads, TEXT) on the dimension's
//!   layer in its colour.
//! - ENTITIES in drawing order: CIRCLE, ARC (degrees, counter-clockwise), LINE, POLYLINE +
//!   VERTEX (start and end widths, closed flag) + SEQEND, SOLID (for `Filled`; quads in SOLID's
//!   1-2-4-3 vertex order), arrows as LINE + SOLID ([`parts::arrow`], as in the SVG), TEXT
//!   (style [`TEXT_STYLE`]; alignment groups 72/73 with the alignment point 11/21 when not
//!   left/baseline and 10/20 the start of the text, rotation in degrees), DIMENSION (2-line
//!   angular, type 2, under 180°, else 3-point, type 5; rotated linear, type 0; all with flags
//!   32 "block used by this dimension only" and 128 "text at a user-defined location", the
//!   drawing's text as override and the definition points readers measure from).
//!   Entities carry their own ACI colour and line type when they have one (DASHED also
//!   when their layer is dashed), else BYLAYER.
//!
//! Text: R12 and R2000 files are code-page based; every non-ASCII character is written as a
//! `\U+XXXX` escape (the crate does this for R12–R2004), which AutoCAD, ezdxf, LibreCAD and
//! Inkscape decode (`φ1 = 75.77°` is written `\U+03C61 = 75.77\U+00B0`); R2007 is UTF-8.
//!
//! Determinism: handles are assigned in a fixed order (tables, then blocks, then entities),
//! floats are written with at most 12 decimals (trailing zeros trimmed, `-0`
//! written as `0`), and nothing depends on time or randomness: the same drawing gives the
//! same bytes. Lines end in CRLF, as the crate (and AutoCAD) write them; every reader accepts
//! that, and the golden comparison normalises line ends.
//!
//! A small pass over the crate's text output (`fix_up`) fixes what its API cannot express:
//! VERTEX and SEQEND on the POLYLINE's layer (the crate writes them on layer 0), the
//! alignment point 11/21 of justified text at (0, 0) (the crate omits a zero point, and
//! ezdxf's renderer then fails), `$PINSBASE` and `$DIMTXSTY` in R12, for R12 the removal of
//! subclass markers (group 100, R13+ only), DIMSTYLE handles in group 105, and the frozen
//! flag (70 = 1) of a layer that is off.
//!
//! [`DxfVersion::R2000`] (AC1015) and [`DxfVersion::R2007`] (AC1021) are there for programs
//! that want a newer file (R2007: UTF-8 text, which GDAL, dxf-parser, dxfgrabber and FreeCAD
//! need to show the letters). Polylines stay POLYLINE/VERTEX. The crate's R2000+ faults are
//! repaired: lineweight BYLAYER (−1) instead of 0 mm on every entity, opaque transparency
//! (the vertices too), and in the text pass handles for the TABLE heads (ezdxf fix code 110,
//! AutoCAD LT's "Bad handle 0"), own handles for ENDBLK (the crate repeats the BLOCK's),
//! `$HANDSEED` after them, `$PSVPSCALE` = 1 (LibreCAD draws the default 0 as a dot), the
//! subclass marker of the 2-line angular dimension (the crate writes it as its 3-point
//! struct). GUIDs are nil. Group 42 (actual measurement) is not written: readers recompute
//! it from the definition points.

use std::borrow::Cow;
use std::io::Write;

pub mod librecad;
mod r12;
mod scale;
#[cfg(feature = "dxf-r2000")]
mod via_crate;

use super::parts::{self, arrow, explode_dimension};
use super::{Aci, Bounds, Drawing, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, Vector, angle_of, normalize_angle, polar};

/// Name of the dashed line type in the LTYPE table.
pub const DASHED: &str = "DASHED";
/// Name of the solid line type in the LTYPE table.
pub const CONTINUOUS: &str = "CONTINUOUS";
/// Margin added around the drawing's bounds for the limits, as a fraction of its larger
/// extent (the SVG uses the same).
pub const LIMITS_MARGIN: f64 = 0.05;
/// An angular dimension is written 2-line (type 2) when its sweep lies between this and
/// 180° minus this (radians); nearer 0° or 180° the two lines are almost parallel, and
/// from 180° on two lines cannot hold the angle: 3-point (type 5) then.
pub const TWO_LINE_MARGIN: f64 = 1e-6;
/// How wide LibreCAD draws a character of TEXT, in text heights, with some room: its font
/// for [`TEXT_STYLE`] (AZOMIX) took 0.94 a character on the triad's first caption line and
/// 0.98 on its second (many spaces), measured on LibreCAD 2.2's PDF page; DejaVu Sans, which
/// the bounds assume, about 0.55.
pub const LIBRECAD_ADVANCE: f64 = 1.05;
/// The smallest sheet (limits) written, width × height in mm: A4 landscape.
pub const MIN_SHEET_MM: (f64, f64) = (297.0, 210.0);
/// The text style of every TEXT and of dimension text. LibreCAD takes a text's font from
/// its style *name* (not the font file): `AZOMIX` is its font with every letter mechdraw
/// writes (φ π ω ε ≡ → ′ ° ± ²; its default font has no Greek). Other programs take the
/// font file, [`TEXT_FONT_FILE`].
pub const TEXT_STYLE: &str = "AZOMIX";
/// The font file of [`TEXT_STYLE`]: a TrueType font with Greek letters that Windows CAD
/// programs have (ezdxf and others substitute a font of their own when it is missing).
pub const TEXT_FONT_FILE: &str = "arial.ttf";
/// `$DWGCODEPAGE` of an R2007 file, whose text is UTF-8: Windows' name for UTF-8.
pub const R2007_CODE_PAGE: &str = "ANSI_65001";
/// Values smaller than this in magnitude are written as 0, so that rounding noise such as
/// `cos(π/2) = 6e-17` does not appear as `-0.0` or `0.000000000000` in the file.
pub const ZERO_SNAP: f64 = 5e-13;

/// DXF version written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DxfVersion {
    /// AutoCAD R12 (AC1009): read by every CAD program; audits clean with ezdxf. The default.
    /// Non-ASCII text as `\U+XXXX` escapes; no `$INSUNITS`.
    #[default]
    R12,
    /// AutoCAD 2000 (AC1015): `$INSUNITS` = mm and `$MEASUREMENT` = metric in the header;
    /// non-ASCII text as `\U+XXXX` escapes.
    R2000,
    /// AutoCAD 2007 (AC1021): as R2000, with text in UTF-8 (readers that leave `\U+XXXX`
    /// escapes literal show the letters).
    R2007,
}

impl DxfVersion {
    /// Every version, in the order of the `--dxf-version` help.
    pub const ALL: [DxfVersion; 3] = [DxfVersion::R12, DxfVersion::R2000, DxfVersion::R2007];

    /// The name on the command line and in the docs (`R12`, `R2000`, `R2007`).
    pub fn name(self) -> &'static str {
        match self {
            DxfVersion::R12 => "R12",
            DxfVersion::R2000 => "R2000",
            DxfVersion::R2007 => "R2007",
        }
    }
}

impl std::str::FromStr for DxfVersion {
    type Err = String;

    /// `R12`, `R2000` or `R2007` (any case; `AC1009`, `AC1015`, `AC1021` too).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_uppercase().as_str() {
            "R12" | "AC1009" => Ok(DxfVersion::R12),
            "R2000" | "AC1015" => Ok(DxfVersion::R2000),
            "R2007" | "AC1021" => Ok(DxfVersion::R2007),
            _ => Err(format!("unknown DXF version {s:?}: use R12, R2000 or R2007")),
        }
    }
}

/// How dimensions are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Dimensions {
    /// DIMENSION entities (a 2-line angular one for angles under 180°, else 3-point; rotated
    /// linear), each with its anonymous `*D` block holding what it looks like: AutoCAD, ezdxf
    /// and LibreCAD show them as dimensions the user can edit. The default.
    #[default]
    Entities,
    /// Exploded into plain LINE, ARC, SOLID (arrowheads) and TEXT entities on the dimension's
    /// layer: every reader shows them (FreeCAD, dxfgrabber and `dxf` (npm) drop or change
    /// DIMENSION entities), but they are no longer dimensions.
    Exploded,
}

impl Dimensions {
    /// The name on the command line (`entities`, `exploded`).
    pub fn name(self) -> &'static str {
        match self {
            Dimensions::Entities => "entities",
            Dimensions::Exploded => "exploded",
        }
    }
}

impl std::str::FromStr for Dimensions {
    type Err = String;

    /// `entities` or `exploded` (any case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "entities" => Ok(Dimensions::Entities),
            "exploded" => Ok(Dimensions::Exploded),
            _ => Err(format!("unknown dimension encoding {s:?}: use entities or exploded")),
        }
    }
}

/// Options of the DXF writer. Build with struct update syntax from the default:
/// `DxfOptions { version: DxfVersion::R2000, ..DxfOptions::default() }`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DxfOptions {
    /// File version; [`DxfVersion::R12`] by default.
    pub version: DxfVersion,
    /// How dimensions are written; [`Dimensions::Entities`] by default.
    pub dimensions: Dimensions,
    /// Millimetres per model unit (1 for a drawing in mm, 1000 for one in metres; > 0). The
    /// file is always in millimetres: the writer scales every coordinate, length and text
    /// height by this factor.
    pub mm_per_unit: f64,
}

impl Default for DxfOptions {
    fn default() -> Self {
        DxfOptions { version: DxfVersion::R12, dimensions: Dimensions::Entities, mm_per_unit: 1.0 }
    }
}

/// Errors of the DXF writer. All but [`DxfError::Io`] mean the [`Drawing`] holds something
/// DXF cannot represent; nothing is written then.
#[derive(Debug, thiserror::Error)]
pub enum DxfError {
    /// Writing to the output failed.
    #[error("writing DXF failed: {0}")]
    Io(#[from] std::io::Error),
    /// The `dxf` crate reported an error while serialising.
    #[error("DXF serialisation failed: {0}")]
    Crate(String),
    /// An R2000 or R2007 file asked of a build without the `dxf` crate (the live page's).
    #[error(
        "this build has no {version} DXF writer (the live page writes R12 and leaves R2000 and R2007 to the command line: `mechdraw run --dxf-version {version}`; a library build needs the Cargo feature `dxf-r2000`)"
    )]
    NotInThisBuild {
        /// The version asked for (`R2000`, `R2007`).
        version: &'static str,
    },
    /// An entity refers to a layer index the drawing does not have.
    #[error("entity {entity} is on layer index {layer}, but the drawing has {count} layers")]
    NoSuchLayer {
        /// Index of the entity in [`Drawing::entities`].
        entity: usize,
        /// The layer index it refers to.
        layer: usize,
        /// Number of layers in the drawing.
        count: usize,
    },
    /// A layer name DXF cannot hold (empty, a character from `<>/\":;?*|=`` ` or a control
    /// character, or a name used twice).
    #[error("layer name {name:?} cannot be written to DXF: {reason}")]
    BadLayerName {
        /// The layer name.
        name: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A coordinate, length or angle is NaN or infinite.
    #[error("entity {entity} ({kind}) has a non-finite coordinate, length or angle")]
    NonFinite {
        /// Index of the entity in [`Drawing::entities`].
        entity: usize,
        /// Shape kind.
        kind: &'static str,
    },
    /// The model-unit-to-millimetre factor is not a positive finite number (e.g. 0 or NaN).
    #[error("the DXF scale {mm_per_unit} mm per model unit is not a positive finite number")]
    BadScale {
        /// The factor given in [`DxfOptions::mm_per_unit`].
        mm_per_unit: f64,
    },
    /// A shape DXF cannot draw (too few vertices, non-positive radius or text height,
    /// negative width).
    #[error("entity {entity} ({kind}) cannot be written: {reason}")]
    BadShape {
        /// Index of the entity in [`Drawing::entities`].
        entity: usize,
        /// Shape kind.
        kind: &'static str,
        /// What is wrong with it.
        reason: &'static str,
    },
}

/// Writes `drawing` as DXF into a byte vector (CRLF line ends; ASCII for R12 and R2000,
/// UTF-8 for R2007), in millimetres (the drawing scaled by [`DxfOptions::mm_per_unit`]).
///
/// R12 is written by hand (`r12.rs`); R2000 and R2007 through the `dxf` crate, with the
/// Cargo feature `dxf-r2000` (the command line has it; without it they are refused with
/// [`DxfError::NotInThisBuild`]: the live page writes R12 only).
pub fn to_bytes(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    let drawing = prepare(drawing, opts)?;
    match opts.version {
        DxfVersion::R12 => r12::to_bytes(&drawing, opts),
        DxfVersion::R2000 | DxfVersion::R2007 => newer_bytes(&drawing, opts),
    }
}

/// [`to_bytes`] in pieces, the file being the one after the other; for R12 the blocks and
/// the entities (most of a motion's file) are written in parallel jobs, each its own piece,
/// so that a writer can put the file together without copying them. (R2000 and R2007: the
/// whole file in one piece.)
pub fn to_pieces(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<Vec<u8>>, DxfError> {
    let drawing = prepare(drawing, opts)?;
    match opts.version {
        DxfVersion::R12 => r12::to_pieces(&drawing, opts),
        DxfVersion::R2000 | DxfVersion::R2007 => Ok(vec![newer_bytes(&drawing, opts)?]),
    }
}

/// An R2000 or R2007 file of a validated drawing, through the crate.
#[cfg(feature = "dxf-r2000")]
fn newer_bytes(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    via_crate::crate_bytes(drawing, opts)
}

/// Without the crate (the live page's module) an R2000 or R2007 file is refused by name.
#[cfg(not(feature = "dxf-r2000"))]
fn newer_bytes(_drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    Err(DxfError::NotInThisBuild { version: opts.version.name() })
}

/// The reference writer: the same file as [`to_bytes`], with every entity built as a `dxf`
/// crate struct and serialised by the crate, then fixed up. Several times slower than
/// [`to_bytes`] for R12; kept to check the hand-written R12 path against (tests and
/// benchmarks).
#[cfg(feature = "dxf-r2000")]
pub fn to_bytes_via_crate(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    let drawing = prepare(drawing, opts)?;
    via_crate::crate_bytes(&drawing, opts)
}

/// The validated drawing in millimetres, its scale captions stating the DXF's scales and
/// its texts written with characters the text style has ([`librecad::for_azomix`]);
/// borrowed when it already is all that.
fn prepare<'a>(drawing: &'a Drawing, opts: &DxfOptions) -> Result<Cow<'a, Drawing>, DxfError> {
    let k = opts.mm_per_unit;
    if !(k.is_finite() && k > 0.0) {
        return Err(DxfError::BadScale { mm_per_unit: k });
    }
    validate(drawing)?;
    if k == 1.0 && !drawing.entities.iter().any(|e| scale::changes(&e.shape)) {
        return Ok(Cow::Borrowed(drawing));
    }
    let scaled = scale::scaled(drawing, k);
    // Scaling can overflow a huge finite coordinate to infinity.
    validate(&scaled)?;
    Ok(Cow::Owned(scaled))
}

/// Writes `drawing` as DXF to `out`.
pub fn write(drawing: &Drawing, opts: &DxfOptions, mut out: impl Write) -> Result<(), DxfError> {
    let bytes = to_bytes(drawing, opts)?;
    out.write_all(&bytes)?;
    Ok(())
}

fn kind(shape: &Shape) -> &'static str {
    match shape {
        Shape::Circle { .. } => "circle",
        Shape::Arc { .. } => "arc",
        Shape::Line { .. } => "line",
        Shape::Polyline { .. } => "polyline",
        Shape::Filled { .. } => "filled polygon",
        Shape::Arrow { .. } => "arrow",
        Shape::Text { .. } => "text",
        Shape::ScaleText { .. } => "scale caption",
        Shape::AngularDimension { .. } => "angular dimension",
        Shape::LinearDimension { .. } => "linear dimension",
    }
}

/// Checks everything the writer relies on, so that it never panics and never writes `NaN`.
fn validate(drawing: &Drawing) -> Result<(), DxfError> {
    let mut seen = std::collections::HashSet::new();
    for layer in &drawing.layers {
        let bad = |reason| DxfError::BadLayerName { name: layer.name.clone(), reason };
        if layer.name.is_empty() {
            return Err(bad("it is empty"));
        }
        if layer.name.chars().any(|c| c.is_control() || "<>/\\\":;?*|=`".contains(c)) {
            return Err(bad("it contains a character DXF forbids in table names"));
        }
        if !seen.insert(layer.name.to_uppercase()) {
            return Err(bad("another layer has the same name (DXF names ignore case)"));
        }
    }
    if drawing.layers.first().is_none_or(|l| l.name != "0") {
        return Err(DxfError::BadLayerName {
            name: drawing.layers.first().map(|l| l.name.clone()).unwrap_or_default(),
            reason: "the first layer must be \"0\"",
        });
    }
    let style = drawing.dim_style;
    for (i, e) in drawing.entities.iter().enumerate() {
        let kind = kind(&e.shape);
        if e.layer >= drawing.layers.len() {
            return Err(DxfError::NoSuchLayer { entity: i, layer: e.layer, count: drawing.layers.len() });
        }
        let bad = |reason| DxfError::BadShape { entity: i, kind, reason };
        let pts_ok = |ps: &[Point]| ps.iter().all(|p| p.x.is_finite() && p.y.is_finite());
        let finite = match &e.shape {
            Shape::Circle { center, radius } => pts_ok(&[*center]) && radius.is_finite(),
            Shape::Arc { center, radius, start, end } => {
                pts_ok(&[*center]) && radius.is_finite() && start.is_finite() && end.is_finite()
            }
            Shape::Line { from, to } => pts_ok(&[*from, *to]),
            Shape::Polyline { points, width, .. } => pts_ok(points) && width.is_finite(),
            Shape::Filled { points } => pts_ok(points),
            Shape::Arrow { from, to, head } => pts_ok(&[*from, *to]) && head.is_finite(),
            Shape::Text { at, height, rotation, .. } | Shape::ScaleText { at, height, rotation, .. } => {
                pts_ok(&[*at]) && height.is_finite() && rotation.is_finite()
            }
            Shape::AngularDimension { vertex, first, second, radius, .. } => {
                pts_ok(&[*vertex, *first, *second]) && radius.is_finite()
            }
            Shape::LinearDimension { p1, p2, line_at, angle, .. } => pts_ok(&[*p1, *p2, *line_at]) && angle.is_finite(),
        };
        if !finite {
            return Err(DxfError::NonFinite { entity: i, kind });
        }
        match &e.shape {
            Shape::Circle { radius, .. } | Shape::Arc { radius, .. } if *radius <= 0.0 => {
                return Err(bad("the radius must be positive"));
            }
            Shape::Polyline { points, .. } if points.len() < 2 => return Err(bad("a polyline needs two vertices")),
            Shape::Polyline { width, .. } if *width < 0.0 => return Err(bad("the width must not be negative")),
            Shape::Filled { points } if points.len() < 3 => {
                return Err(bad("a filled polygon needs at least three vertices"));
            }
            Shape::Arrow { head, .. } if *head < 0.0 => return Err(bad("the head length must not be negative")),
            Shape::Text { height, .. } | Shape::ScaleText { height, .. } if *height <= 0.0 => {
                return Err(bad("the text height must be positive"));
            }
            Shape::AngularDimension { .. } | Shape::LinearDimension { .. } => {
                if !(style.text_height.is_finite() && style.text_height > 0.0) {
                    return Err(bad("the drawing's dimension text height must be positive"));
                }
                if !(style.arrow_size.is_finite() && style.arrow_size > 0.0) {
                    return Err(bad("the drawing's dimension arrow size must be positive"));
                }
                if let Shape::AngularDimension { vertex, first, second, radius, .. } = &e.shape {
                    if *radius <= 0.0 {
                        return Err(bad("the dimension arc radius must be positive"));
                    }
                    if first == vertex || second == vertex {
                        return Err(bad("a ray point coincides with the vertex"));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// `v` with rounding noise below [`ZERO_SNAP`] (and `-0`) written as 0.
fn snap(v: f64) -> f64 {
    if v.abs() < ZERO_SNAP { 0.0 } else { v }
}

fn deg(rad: f64) -> f64 {
    snap(rad.to_degrees())
}

/// The layer-table colour index: 1–255 (0 would mean BYBLOCK, which a layer cannot have).
fn layer_aci(c: Aci) -> u8 {
    if c.0 == 0 { 7 } else { c.0 }
}

fn linetype_name(lt: LineType) -> &'static str {
    match lt {
        LineType::Continuous => CONTINUOUS,
        LineType::Dashed => DASHED,
    }
}

/// The line type an entity is written with: its own, else `DASHED` when its layer is dashed
/// (Inkscape draws an entity that takes DASHED from its layer solid), else BYLAYER (`None`).
fn entity_linetype(drawing: &Drawing, e: &super::Entity) -> Option<&'static str> {
    match e.linetype {
        Some(lt) => Some(linetype_name(lt)),
        None => match drawing.layers.get(e.layer).map(|l| l.linetype) {
            Some(LineType::Dashed) => Some(DASHED),
            _ => None,
        },
    }
}

/// The sheet (limits): the drawing's bounds with a [`LIMITS_MARGIN`] margin, grown about
/// its centre to at least [`MIN_SHEET_MM`] (landscape, or portrait for a tall drawing), so
/// that a small drawing still prints on a real page (LibreCAD prints the limits at 1:1).
///
/// The bounds are grown to hold every TEXT as LibreCAD draws it, in its font
/// ([`TEXT_STYLE`]) at [`LIBRECAD_ADVANCE`] text heights a character: wider than the
/// DejaVu Sans estimate of the bounds, so a long caption would run off LibreCAD's page.
fn sheet(drawing: &Drawing, bounds: &Bounds, extent: f64) -> (Point, Point) {
    let (mut lo, mut hi) = (bounds.min, bounds.max);
    for e in &drawing.entities {
        if let Shape::Text { at, height, value, halign, rotation, .. } = &e.shape {
            let w = LIBRECAD_ADVANCE * *height * value.chars().count() as f64;
            let x0 = match halign {
                HAlign::Left => 0.0,
                HAlign::Center => -0.5 * w,
                HAlign::Right => -w,
            };
            // Most text is level: no sine and cosine for it (the same numbers: cos 0 = 1, sin 0 = 0).
            let (c, s) = if *rotation == 0.0 { (1.0, 0.0) } else { (libm::cos(*rotation), libm::sin(*rotation)) };
            let (u, v) = (Vector::new(c, s), Vector::new(-s, c));
            for (x, y) in [(x0, -0.3), (x0 + w, -0.3), (x0, 1.0), (x0 + w, 1.0)] {
                let p = at + u * x + v * (y * *height);
                if p.x.is_finite() && p.y.is_finite() {
                    (lo, hi) = (Point::new(lo.x.min(p.x), lo.y.min(p.y)), Point::new(hi.x.max(p.x), hi.y.max(p.y)));
                }
            }
        }
    }
    let m = Vector::new(LIMITS_MARGIN * extent, LIMITS_MARGIN * extent);
    let (lo, hi) = (lo - m, hi + m);
    let (w, h) = (hi.x - lo.x, hi.y - lo.y);
    let (min_w, min_h) = if h > w { (MIN_SHEET_MM.1, MIN_SHEET_MM.0) } else { MIN_SHEET_MM };
    let grow = Vector::new(0.5 * (min_w - w).max(0.0), 0.5 * (min_h - h).max(0.0));
    (lo - grow, hi + grow)
}

/// One DXF entity of a shape, as both writers draw it: the geometry decided once (arc
/// wrapping, SOLID vertex order, degrees), the serialisation left to the writer.
#[derive(Debug, Clone, Copy)]
enum Prim<'a> {
    /// CIRCLE (also a full-turn arc).
    Circle { center: Point, radius: f64 },
    /// ARC, angles in degrees (snapped), counter-clockwise from `start_deg` to `end_deg`.
    Arc { center: Point, radius: f64, start_deg: f64, end_deg: f64 },
    /// LINE.
    Line { from: Point, to: Point },
    /// POLYLINE with its VERTEXes and SEQEND.
    Polyline { points: &'a [Point], closed: bool, width: f64 },
    /// SOLID, corners in the order written (1-2-3-4).
    Solid([Point; 4]),
    /// A triangle's outline: a closed POLYLINE of width 0 (an arrowhead's, for readers that
    /// drop SOLID).
    Outline([Point; 3]),
    /// TEXT, rotation in degrees (snapped): `at` the alignment point (11/21, written for
    /// justified text), `insert` the left end of the baseline (10/20) computed from the
    /// estimated text width ([`text_insertion`]), `width` the width factor (41, written
    /// when not 1). Alignment, point and width factor as [`librecad::text_fit`] makes them.
    Text {
        at: Point,
        insert: Point,
        height: f64,
        value: &'a str,
        halign: HAlign,
        valign: VAlign,
        rotation_deg: f64,
        width: f64,
    },
}

/// Calls `f` with the DXF entities of a shape other than a dimension, in order. A filled
/// polygon is a triangle as 1-2-3-3, a quad a-b-c-d in SOLID's 1-2-4-3 order (a, b, d, c),
/// larger polygons a fan of triangles (exact for convex outlines); an arrow a LINE and the
/// SOLID head; a zero-sweep arc nothing (as in the SVG; DXF would read equal angles as a
/// full turn). With `outlined` (the exploded mode, for readers that drop SOLID: FreeCAD)
/// a filled polygon and an arrowhead are followed by their outline, a closed POLYLINE of
/// width 0.
fn prims<'a>(shape: &'a Shape, outlined: bool, mut f: impl FnMut(Prim<'a>)) {
    let solids = |points: &[Point], f: &mut dyn FnMut(Prim<'a>)| match points {
        [a, b, c] => f(Prim::Solid([*a, *b, *c, *c])),
        [a, b, c, d] => f(Prim::Solid([*a, *b, *d, *c])),
        [a, rest @ ..] => rest.windows(2).for_each(|w| f(Prim::Solid([*a, w[0], w[1], w[1]]))),
        [] => {}
    };
    match shape {
        Shape::Circle { center, radius } => f(Prim::Circle { center: *center, radius: *radius }),
        Shape::Arc { center, radius, start, end } => {
            let sweep = parts::arc_sweep(*start, *end);
            if sweep == 0.0 {
            } else if sweep >= std::f64::consts::TAU {
                f(Prim::Circle { center: *center, radius: *radius });
            } else {
                let a0 = normalize_angle(*start);
                let (start_deg, end_deg) = (deg(a0), deg(normalize_angle(a0 + sweep)));
                f(Prim::Arc { center: *center, radius: *radius, start_deg, end_deg });
            }
        }
        Shape::Line { from, to } => f(Prim::Line { from: *from, to: *to }),
        Shape::Polyline { points, closed, width } => f(Prim::Polyline { points, closed: *closed, width: *width }),
        Shape::Filled { points } => {
            solids(points, &mut f);
            if outlined {
                f(Prim::Polyline { points, closed: true, width: 0.0 });
            }
        }
        Shape::Arrow { from, to, head } => {
            if let Some((base, tri)) = arrow(*from, *to, *head) {
                f(Prim::Line { from: *from, to: base });
                solids(&tri, &mut f);
                if outlined {
                    f(Prim::Outline(tri));
                }
            }
        }
        Shape::Text { at, height, value, halign, valign, rotation, .. } => {
            let fit = librecad::text_fit(*at, *height, value, *halign, *valign, *rotation);
            f(Prim::Text {
                at: fit.at,
                insert: text_insertion(fit.at, *height, value, fit.halign, fit.valign, *rotation),
                height: *height,
                value,
                halign: fit.halign,
                valign: fit.valign,
                rotation_deg: deg(normalize_angle(*rotation)),
                width: fit.width,
            })
        }
        // Written as TEXT by `prepare`; dimensions by the writers.
        Shape::ScaleText { .. } | Shape::AngularDimension { .. } | Shape::LinearDimension { .. } => {}
    }
}

/// The left end of the baseline of a text aligned `halign`/`valign` at `at`: where a reader
/// that ignores the alignment (Inkscape, for one) starts it. The width is the estimate of
/// [`parts::text_width`]; readers that honour the alignment use the alignment point.
fn text_insertion(at: Point, height: f64, value: &str, halign: HAlign, valign: VAlign, rotation: f64) -> Point {
    let along = match halign {
        HAlign::Left => 0.0,
        HAlign::Center => 0.5 * parts::text_width(value, height),
        HAlign::Right => parts::text_width(value, height),
    };
    let up = match valign {
        VAlign::Baseline => 0.0,
        VAlign::Middle => 0.5 * height,
        VAlign::Top => height,
    };
    if along == 0.0 && up == 0.0 {
        return at;
    }
    let (sin, cos) = libm::sincos(rotation);
    Point::new(at.x - along * cos + up * sin, at.y - along * sin - up * cos)
}

/// The definition points of a DIMENSION entity, as both writers write them.
#[derive(Debug, Clone, Copy)]
enum DimPrim {
    /// Angular, `defs` the points 13, 14, 15, 16 in that order, `def1` the point 10.
    /// 2-line (type 2, `two_line`; what AutoCAD's DIMANGULAR makes when two lines are
    /// picked, and the only angular dimension LibreCAD 2.2 draws): the first line 13→14
    /// (vertex → first ray point), the second 15→10 (vertex → second ray point), 16 on the
    /// arc. 3-point (type 5, for an angle within [`TWO_LINE_MARGIN`] of 0° or 360°): 13/14
    /// the ray points, 15 the vertex, 10 and 16 on the arc.
    Angular { two_line: bool, def1: Point, text_at: Point, defs: [Point; 4] },
    /// Rotated linear (type 0): 10 on the dimension line, 13/14 the feature points, 50 the
    /// angle in degrees (snapped).
    Rotated { on_line: Point, text_mid: Point, p1: Point, p2: Point, angle_deg: f64 },
}

/// The text override of the second half of an angle of 180° or more: a space, which AutoCAD,
/// ezdxf and LibreCAD draw as no text (the first half carries the angle's text).
pub const NO_TEXT: &str = " ";

/// One DIMENSION entity of a dimension shape: its definition points, its text (the
/// override) and the geometry its anonymous block holds.
#[derive(Debug, Clone)]
struct DimPiece<'a> {
    prim: DimPrim,
    text: &'a str,
    geometry: Vec<Shape>,
}

/// The sweep of the part of an angle of 180° or more that carries its text, radians: 170°
/// (the text at its middle, well away from both rays, where LibreCAD writes it along the
/// arc) while the rest keeps at least 10°, and half the angle once that would leave the
/// rest 170° or more (over 340°).
fn text_part(sweep: f64) -> f64 {
    let (most, least) = (170f64.to_radians(), 10f64.to_radians());
    (0.5 * sweep).max(most.min(sweep - least))
}

/// The DIMENSION entities of a dimension shape (none for other shapes). An angle between
/// [`TWO_LINE_MARGIN`] and 180° minus it is one 2-line angular dimension; one from 180° (less
/// the margin) up to a full turn (less twice it) is two, split where [`text_part`] says
/// ([`parts::explode_angular_split`]: LibreCAD draws no angular dimension of 180° or more,
/// and two lines cannot hold one), the first with the text, the second with [`NO_TEXT`], so
/// that readers which draw the blocks show one dimension and LibreCAD, which redraws each,
/// shows the whole arc with its text (and two arrowheads where the parts meet); nearer 0°
/// or 360° one 3-point dimension. A linear dimension is one rotated dimension.
fn dimension_pieces<'a>(shape: &'a Shape, style: &super::DimStyle) -> Vec<DimPiece<'a>> {
    use std::f64::consts::PI;
    match shape {
        Shape::AngularDimension { vertex, first, second, radius, text, .. } => {
            let a1 = angle_of(first - vertex);
            let sweep = normalize_angle(angle_of(second - vertex) - a1);
            let on_arc = |a: f64| polar(*vertex, *radius, a);
            // Where the exploded block draws the text.
            let text_at = parts::angular_text_mid(*vertex, *first, *second, *radius, text, style);
            let whole = || explode_dimension(shape, style);
            if sweep > TWO_LINE_MARGIN && sweep < PI - TWO_LINE_MARGIN {
                let defs = [*vertex, *first, *vertex, on_arc(a1 + 0.5 * sweep)];
                let prim = DimPrim::Angular { two_line: true, def1: *second, text_at, defs };
                return vec![DimPiece { prim, text, geometry: whole() }];
            }
            if (PI - TWO_LINE_MARGIN..2.0 * (PI - TWO_LINE_MARGIN)).contains(&sweep) {
                let first_sweep = text_part(sweep);
                if let Some(([one, two], mid)) = parts::explode_angular_split(shape, first_sweep, style) {
                    let rest = sweep - first_sweep;
                    let (q1, q3) = (on_arc(a1 + 0.5 * first_sweep), on_arc(a1 + first_sweep + 0.5 * rest));
                    let first_half =
                        DimPrim::Angular { two_line: true, def1: mid, text_at, defs: [*vertex, *first, *vertex, q1] };
                    let second_half = DimPrim::Angular {
                        two_line: true,
                        def1: *second,
                        text_at: q3,
                        defs: [*vertex, mid, *vertex, q3],
                    };
                    return vec![
                        DimPiece { prim: first_half, text, geometry: one },
                        DimPiece { prim: second_half, text: NO_TEXT, geometry: two },
                    ];
                }
            }
            let on_mid = on_arc(a1 + 0.5 * sweep);
            let prim =
                DimPrim::Angular { two_line: false, def1: on_mid, text_at, defs: [*first, *second, *vertex, on_mid] };
            vec![DimPiece { prim, text, geometry: whole() }]
        }
        Shape::LinearDimension { p1, p2, line_at, angle, text, marks } => {
            // The text's middle where the exploded block draws it (inside or beside an
            // extension line, or where the figure placed it).
            let lay = parts::linear_layout_placed(*p1, *p2, *line_at, *angle, text, marks.text_along, style);
            let prim = DimPrim::Rotated {
                on_line: lay.f2,
                text_mid: lay.text_mid,
                p1: *p1,
                p2: *p2,
                angle_deg: deg(normalize_angle(*angle)),
            };
            vec![DimPiece { prim, text, geometry: explode_dimension(shape, style) }]
        }
        _ => Vec::new(),
    }
}
#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::draw::{DimStyle, Entity, LinearMarks};

    /// The file as (group code, value) pairs.
    fn pairs(bytes: &[u8]) -> Vec<(i32, String)> {
        let text = std::str::from_utf8(bytes).expect("DXF is ASCII");
        let lines: Vec<&str> = text.split("\r\n").collect();
        lines.chunks_exact(2).map(|c| (c[0].trim().parse().expect("group code"), c[1].to_string())).collect()
    }

    /// The records (group-0 pair and what follows) of type `kind`.
    fn records(p: &[(i32, String)], kind: &str) -> Vec<Vec<(i32, String)>> {
        let mut out = Vec::new();
        for (i, (c, v)) in p.iter().enumerate() {
            if *c == 0 && v == kind {
                let end = p[i + 1..].iter().position(|(c, _)| *c == 0).map_or(p.len(), |k| i + 1 + k);
                out.push(p[i..end].to_vec());
            }
        }
        out
    }

    fn get(rec: &[(i32, String)], code: i32) -> Vec<&str> {
        rec.iter().filter(|(c, _)| *c == code).map(|(_, v)| v.as_str()).collect()
    }

    fn f(rec: &[(i32, String)], code: i32) -> Vec<f64> {
        get(rec, code).iter().map(|v| v.trim().parse().unwrap()).collect()
    }

    fn drawing() -> Drawing {
        Drawing::new(DimStyle { text_height: 2.5, arrow_size: 3.0 })
    }

    fn write(d: &Drawing) -> Vec<(i32, String)> {
        pairs(&to_bytes(d, &DxfOptions::default()).unwrap())
    }

    #[test]
    fn polyline_has_widths_closed_flag_and_vertices_on_its_layer() {
        let mut d = drawing();
        let l = d.layer("LINKS", Aci::BLUE, LineType::Continuous);
        let pts = vec![Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(10.0, 5.0)];
        d.add(l, Shape::Polyline { points: pts, closed: true, width: 0.5 });
        let p = write(&d);
        let poly = &records(&p, "POLYLINE")[0];
        assert_eq!(get(poly, 8), ["LINKS"]);
        assert_eq!(get(poly, 66)[0].trim(), "1");
        assert_eq!(get(poly, 70)[0].trim(), "1", "closed flag");
        assert_eq!(f(poly, 40), [0.5]);
        assert_eq!(f(poly, 41), [0.5]);
        let vertices = records(&p, "VERTEX");
        assert_eq!(vertices.len(), 3);
        for v in &vertices {
            assert_eq!(get(v, 8), ["LINKS"]);
            assert_eq!(f(v, 40), [0.5]);
            assert_eq!(f(v, 41), [0.5]);
            assert!(get(v, 100).is_empty(), "no subclass markers in R12");
        }
        assert_eq!(f(&vertices[2], 10), [10.0]);
        assert_eq!(f(&vertices[2], 20), [5.0]);
        assert_eq!(get(&records(&p, "SEQEND")[0], 8), ["LINKS"]);
    }

    #[test]
    fn each_dimension_has_its_own_anonymous_block() {
        let mut d = drawing();
        let o = Point::new(0.0, 0.0);
        for text in ["a", "b"] {
            d.add(
                0,
                Shape::AngularDimension {
                    vertex: o,
                    first: Point::new(1.0, 0.0),
                    second: Point::new(0.0, 1.0),
                    radius: 5.0,
                    text: text.into(),
                    runs: Default::default(),
                },
            );
        }
        d.add(
            0,
            Shape::LinearDimension {
                p1: o,
                p2: Point::new(10.0, 0.0),
                line_at: Point::new(0.0, -5.0),
                angle: 0.0,
                text: "10".into(),
                marks: LinearMarks::default(),
            },
        );
        let p = write(&d);
        let dims = records(&p, "DIMENSION");
        let names: Vec<&str> = dims.iter().map(|r| get(r, 2)[0]).collect();
        assert_eq!(names, ["*D1", "*D2", "*D3"]);
        assert!(!p.iter().any(|(_, v)| v == "*MODEL_SPACE"));
        // Types 2 (2-line angular: the 90° angles) and 0 (rotated), each with flags 32 + 128.
        let types: Vec<i32> = dims.iter().map(|r| get(r, 70)[0].trim().parse().unwrap()).collect();
        assert_eq!(types, [2 | 32 | 128, 2 | 32 | 128, 32 | 128]);
        assert_eq!(get(&dims[1], 1), ["b"]);
        // 2-line angular: the first line 13→14 from the vertex to the first ray point, the
        // second 15→10 from the vertex to the second ray point, 16 on the arc (radius 5, 45°).
        let xy = |r: &[(i32, String)], c: i32| (f(r, c)[0], f(r, c + 10)[0]);
        assert_eq!(
            [xy(&dims[0], 13), xy(&dims[0], 14), xy(&dims[0], 15), xy(&dims[0], 10)],
            [(0.0, 0.0), (1.0, 0.0), (0.0, 0.0), (0.0, 1.0)]
        );
        let (x16, y16) = xy(&dims[0], 16);
        assert!((x16 - 5.0 / 2f64.sqrt()).abs() < 1e-12 && (y16 - 5.0 / 2f64.sqrt()).abs() < 1e-12);
        // Rotated: 13/14 the feature points, 50 the angle in degrees, 10 on the dimension line.
        assert_eq!((f(&dims[2], 14), f(&dims[2], 50), f(&dims[2], 20)), (vec![10.0], vec![0.0], vec![-5.0]));
        let blocks = records(&p, "BLOCK");
        let block_names: Vec<&str> = blocks.iter().map(|r| get(r, 2)[0]).collect();
        assert_eq!(block_names, ["*D1", "*D2", "*D3"]);
        for b in &blocks {
            assert_eq!(get(b, 70)[0].trim(), "1", "anonymous");
        }
        // Each block holds its geometry: extension lines out to the arc (the ray points lie
        // inside it), the arc, two SOLID arrowheads and the text.
        let first_block = p.iter().position(|(c, v)| *c == 0 && v == "BLOCK").unwrap();
        let first_end = p.iter().position(|(c, v)| *c == 0 && v == "ENDBLK").unwrap();
        let kinds: Vec<&str> =
            p[first_block + 1..first_end].iter().filter(|(c, _)| *c == 0).map(|(_, v)| v.as_str()).collect();
        assert_eq!(kinds, ["LINE", "LINE", "ARC", "SOLID", "SOLID", "TEXT"]);
        // Header dimension sizes.
        let header_value = |name: &str| {
            let i = p.iter().position(|(c, v)| *c == 9 && v == name).unwrap();
            p[i + 1].1.trim().parse::<f64>().unwrap()
        };
        assert_eq!(header_value("$DIMTXT"), 2.5);
        assert_eq!(header_value("$DIMASZ"), 3.0);
    }

    /// LibreCAD draws no angular dimension of 180° or more (issue 29): such an angle is two
    /// 2-line dimensions split at its bisector, the first with the text, the second with
    /// none, whose sweeps add up to the angle; together their blocks hold what the whole
    /// dimension draws.
    #[test]
    fn angles_of_180_degrees_and_more_are_two_2_line_halves() {
        let o = Point::new(0.0, 0.0);
        for (deg_sweep, text) in [(180.0, "180"), (270.0, "270"), (300.0, "φ1 = 300°")] {
            let mut d = drawing();
            let second = polar(o, 1.0, f64::to_radians(deg_sweep));
            let dim = Shape::AngularDimension {
                vertex: o,
                first: Point::new(1.0, 0.0),
                second,
                radius: 5.0,
                text: text.into(),
                runs: Default::default(),
            };
            d.add(0, dim.clone());
            let p = write(&d);
            let dims = records(&p, "DIMENSION");
            assert_eq!(dims.len(), 2, "{text}");
            let escaped = text.replace('φ', "\\U+03C6").replace('°', "\\U+00B0");
            assert_eq!((get(&dims[0], 1), get(&dims[1], 1)), (vec![escaped.as_str()], vec![NO_TEXT]));
            // Each a 2-line angular dimension: 13→14 and 15→10 its lines from the vertex.
            let dir = |r: &[(i32, String)], c: i32| f(r, c + 10)[0].atan2(f(r, c)[0]).to_degrees();
            let mut total = 0.0;
            for dim in &dims {
                assert_eq!(get(dim, 70)[0].trim(), format!("{}", 2 | 32 | 128));
                assert_eq!(
                    (f(dim, 13), f(dim, 23), f(dim, 15), f(dim, 25)),
                    (vec![0.0], vec![0.0], vec![0.0], vec![0.0])
                );
                let sweep = (dir(dim, 10) - dir(dim, 14)).rem_euclid(360.0);
                assert!(sweep < 180.0, "{text}: a half of {sweep}°");
                total += sweep;
            }
            assert!((total - deg_sweep).abs() < 1e-9, "{text}: halves add up to {total}°");
            // The two blocks hold the whole dimension's parts: two arcs that make its arc, two
            // arrowheads, one text.
            let kinds = |k: &str| records(&p, k).len();
            assert_eq!((kinds("ARC"), kinds("SOLID"), kinds("TEXT")), (2, 2, 1), "{text}");
        }
    }

    #[test]
    fn dashed_line_type_has_its_pattern() {
        let mut d = drawing();
        let l = d.layer("C", Aci::RED, LineType::Dashed);
        d.add(l, Shape::Line { from: Point::new(0.0, 0.0), to: Point::new(200.0, 100.0) });
        let p = write(&d);
        let lt = records(&p, "LTYPE").into_iter().find(|r| get(r, 2) == ["DASHED"]).unwrap();
        assert_eq!(get(&lt, 73)[0].trim(), "2");
        // Extent 200: 1.8 % is 3.6, rounded down to the 1-2-5 series: dash 2, gap 1.
        assert_eq!(f(&lt, 49), [2.0, -1.0]);
        assert_eq!(f(&lt, 40), [3.0]);
        let layer = records(&p, "LAYER").into_iter().find(|r| get(r, 2) == ["C"]).unwrap();
        assert_eq!(get(&layer, 6), ["DASHED"]);
        assert_eq!(get(&layer, 62)[0].trim(), "1");
    }

    #[test]
    fn colours_are_by_layer_unless_given() {
        let mut d = drawing();
        let l = d.layer("L", Aci::GREEN, LineType::Continuous);
        d.add(l, Shape::Circle { center: Point::new(0.0, 0.0), radius: 1.0 });
        d.add_colored(l, Aci(42), Shape::Circle { center: Point::new(0.0, 0.0), radius: 2.0 });
        let p = write(&d);
        let circles = records(&p, "CIRCLE");
        assert!(get(&circles[0], 62).is_empty(), "BYLAYER is the default, not written");
        assert_eq!(get(&circles[1], 62)[0].trim(), "42");
    }

    #[test]
    fn arcs_wrap_counter_clockwise_and_degenerate_ones_are_skipped() {
        let mut d = drawing();
        let c = Point::new(0.0, 0.0);
        d.add(0, Shape::Arc { center: c, radius: 1.0, start: 300f64.to_radians(), end: 40f64.to_radians() });
        d.add(0, Shape::Arc { center: c, radius: 1.0, start: 1.0, end: 1.0 });
        d.add(0, Shape::Arc { center: c, radius: 2.0, start: 0.0, end: std::f64::consts::TAU });
        let p = write(&d);
        let arcs = records(&p, "ARC");
        assert_eq!(arcs.len(), 1);
        assert!((f(&arcs[0], 50)[0] - 300.0).abs() < 1e-9 && (f(&arcs[0], 51)[0] - 40.0).abs() < 1e-9);
        assert_eq!(f(&records(&p, "CIRCLE")[0], 40), [2.0], "a full turn is a circle");
    }

    #[test]
    fn solid_quads_use_the_1_2_4_3_order() {
        let mut d = drawing();
        let sq = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
        d.add(0, Shape::Filled { points: sq });
        let p = write(&d);
        let s = &records(&p, "SOLID")[0];
        // Corners 1, 2, 3, 4 = (0,0), (1,0), (0,1), (1,1): a quad a-b-c-d as a, b, d, c.
        let corners: Vec<(f64, f64)> = (0..4).map(|k| (f(s, 10 + k)[0], f(s, 20 + k)[0])).collect();
        assert_eq!(corners, [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]);
    }

    #[test]
    fn text_alignment_rotation_and_unicode_escapes() {
        let mut d = drawing();
        let t = |at, halign, valign, rotation: f64, value: &str| Shape::Text {
            runs: crate::draw::Runs::flat(),
            at,
            height: 2.0,
            value: value.into(),
            halign,
            valign,
            rotation: rotation.to_radians(),
        };
        d.add(0, t(Point::new(3.0, 4.0), HAlign::Left, VAlign::Baseline, 0.0, "φ1 = 75.77°"));
        d.add(0, t(Point::new(0.0, 0.0), HAlign::Center, VAlign::Middle, 90.0, "ω ε π ′"));
        d.add(0, t(Point::new(5.0, 6.0), HAlign::Right, VAlign::Top, 0.0, "x"));
        let p = write(&d);
        let texts = records(&p, "TEXT");
        assert_eq!(get(&texts[0], 1), ["\\U+03C61 = 75.77\\U+00B0"]);
        assert!(get(&texts[0], 72).is_empty() && get(&texts[0], 11).is_empty());
        assert_eq!(get(&texts[1], 1), ["\\U+03C9 \\U+03B5 \\U+03C0 \\U+2032"]);
        assert_eq!((get(&texts[1], 72)[0].trim(), get(&texts[1], 73)[0].trim()), ("1", "2"));
        assert_eq!((f(&texts[1], 11), f(&texts[1], 21)), (vec![0.0], vec![0.0]), "alignment point at the origin");
        assert_eq!(f(&texts[1], 50), [90.0]);
        assert_eq!((get(&texts[2], 72)[0].trim(), get(&texts[2], 73)[0].trim()), ("2", "3"));
        assert_eq!((f(&texts[2], 11), f(&texts[2], 21)), (vec![5.0], vec![6.0]));
    }

    #[test]
    fn output_is_deterministic_and_has_no_timestamps() {
        let mut d = drawing();
        d.add(0, Shape::Arrow { from: Point::new(0.0, 0.0), to: Point::new(3.0, 4.0), head: 1.0 });
        let a = to_bytes(&d, &DxfOptions::default()).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1100));
        let b = to_bytes(&d, &DxfOptions::default()).unwrap();
        assert_eq!(a, b);
        let p = pairs(&a);
        for var in ["$TDCREATE", "$TDUPDATE"] {
            let i = p.iter().position(|(c, v)| *c == 9 && v == var).unwrap();
            assert_eq!(p[i + 1].1, "2415021.0", "{var}");
        }
        // The sheet for LibreCAD: the drawing's origin at −$PLIMMIN on it.
        let var = |name: &str, k: usize| {
            let i = p.iter().position(|(c, v)| *c == 9 && v == name).unwrap();
            p[i + 1 + k].1.trim().parse::<f64>().unwrap()
        };
        assert_eq!((var("$PINSBASE", 0), var("$PINSBASE", 1)), (-var("$PLIMMIN", 0), -var("$PLIMMIN", 1)));
        assert!(var("$PLIMMIN", 0) < 0.0 && var("$PLIMMAX", 1) > 4.0, "limits around the arrow with a margin");
        assert_eq!(p[1].1, "HEADER");
        assert!(p.iter().any(|(c, v)| *c == 1 && v == "AC1009"));
        assert!(!p.iter().any(|(c, _)| *c == 100), "no subclass markers in R12");
    }

    #[test]
    fn r2000_is_deterministic_with_fixed_guids_and_table_handles() {
        let mut d = drawing();
        d.add(
            0,
            Shape::Polyline { points: vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0)], closed: false, width: 0.2 },
        );
        let opts = DxfOptions { version: DxfVersion::R2000, ..DxfOptions::default() };
        let a = to_bytes(&d, &opts).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1100));
        assert_eq!(a, to_bytes(&d, &opts).unwrap());
        let p = pairs(&a);
        assert!(p.iter().any(|(c, v)| *c == 1 && v == "AC1015"));
        for var in ["$FINGERPRINTGUID", "$VERSIONGUID"] {
            let i = p.iter().position(|(c, v)| *c == 9 && v == var).unwrap();
            assert_eq!(p[i + 1].1, "00000000-0000-0000-0000-000000000000", "{var}");
        }
        for t in records(&p, "TABLE") {
            assert_eq!(get(&t, 5).len(), 1, "TABLE {:?} has a handle", get(&t, 2));
        }
        for v in records(&p, "VERTEX") {
            assert_eq!(get(&v, 370)[0].trim(), "-1", "lineweight BYLAYER");
        }
        // Handles are unique.
        let handles: Vec<&str> = p.iter().filter(|(c, _)| *c == 5 || *c == 105).map(|(_, v)| v.as_str()).collect();
        let unique: std::collections::HashSet<&str> = handles.iter().copied().collect();
        assert_eq!(unique.len(), handles.len());
    }

    /// The fast R12 path and the crate path give the same bytes.
    /// (With dimensions as entities and exploded, at 1 mm per unit and scaled by 25.4.)
    fn same_as_crate(d: &Drawing) {
        for dimensions in [Dimensions::Entities, Dimensions::Exploded] {
            for mm_per_unit in [1.0, 25.4] {
                let opts = DxfOptions { dimensions, mm_per_unit, ..DxfOptions::default() };
                let fast = to_bytes(d, &opts).unwrap();
                let reference = to_bytes_via_crate(d, &opts).unwrap();
                if fast != reference {
                    let (f, r) = (String::from_utf8_lossy(&fast), String::from_utf8_lossy(&reference));
                    let at = f.lines().zip(r.lines()).position(|(a, b)| a != b).unwrap_or(0);
                    let show = |s: &str| s.lines().skip(at.saturating_sub(12)).take(16).collect::<Vec<_>>().join("|");
                    panic!("{opts:?}: differ at line {at}:\nfast: {}\ncrate: {}", show(&f), show(&r));
                }
                // Written in parallel jobs of a few entities: every job boundary, the same bytes.
                let mm = prepare(d, &opts).unwrap();
                for per_job in [1, 2, 3, 7] {
                    let pieces = r12::to_pieces_in(&mm, &opts, per_job).unwrap();
                    assert!(pieces.concat() == reference, "{opts:?}, {per_job} entities per job");
                }
            }
        }
    }

    /// The hand-written HEADER and TABLES (`r12/head.rs`) against the crate's: layers off
    /// (the first one too), a dashed first layer, an empty drawing, a single
    /// point, a tall and a wide drawing, odd dimension sizes and text that widens the sheet.
    #[test]
    fn hand_written_r12_head_is_the_crate_paths() {
        let p = Point::new;
        same_as_crate(&drawing());
        for (w, h, text) in
            [(0.0, 0.0, ""), (10.0, 900.0, "φ tall"), (3000.0, 0.5, "wide ^ caption"), (1e-7, 2e-7, "x")]
        {
            let mut d = Drawing::new(DimStyle { text_height: 3.3, arrow_size: 1.0 / 3.0 });
            let a = d.layer("A", Aci(0), LineType::Dashed);
            let b = d.layer("B-off", Aci(9), LineType::Continuous);
            d.layers[0].linetype = LineType::Dashed;
            d.layers[0].color = Aci(3);
            d.set_layer_on("B-off", false);
            d.add(a, Shape::Line { from: p(-1.5, 2.0), to: p(-1.5 + w, 2.0 + h) });
            if !text.is_empty() {
                let value = text.into();
                d.add(
                    b,
                    Shape::Text {
                        at: p(w, 0.0),
                        height: 2.0,
                        value,
                        runs: crate::draw::Runs::flat(),
                        halign: HAlign::Right,
                        valign: VAlign::Baseline,
                        rotation: 0.3,
                    },
                );
            }
            same_as_crate(&d);
            d.set_layer_on("0", false);
            same_as_crate(&d);
        }
    }

    #[test]
    fn fast_r12_is_byte_identical_to_the_crate_path_for_every_shape() {
        let p = Point::new;
        let mut d = drawing();
        same_as_crate(&d);
        let dashed = d.layer("DASHED_L", Aci::RED, LineType::Dashed);
        let uni = d.layer("Lφ°^x", Aci(0), LineType::Continuous);
        let layers: Vec<usize> =
            (0..40).map(|i| d.layer(&format!("POS_{i:03}"), Aci(i as u8 + 1), LineType::Continuous)).collect();
        let styles = [
            (None, None),
            (Some(Aci(5)), None),
            (None, Some(LineType::Dashed)),
            (Some(Aci(0)), Some(LineType::Continuous)),
        ];
        let values = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            4e-13,
            -4e-13,
            5e-13,
            6e-13,
            -1e-12,
            1.0 / 8192.0,
            1e-9,
            123456.789_012_345_67,
            1e12,
            -3.3e15,
            9.9e18,
            2e19,
        ];
        let mut k = 0usize;
        let mut add = |d: &mut Drawing, shape: Shape| {
            let (color, linetype) = styles[k % styles.len()];
            let layer = [0, dashed, uni, layers[k % layers.len()]][k % 4];
            d.push(Entity { layer, color, linetype, shape });
            k += 1;
        };
        for (i, &v) in values.iter().enumerate() {
            let w = values[(i + 3) % values.len()];
            let c = p(v, w);
            add(&mut d, Shape::Circle { center: c, radius: v.abs().max(1e-14) });
            add(&mut d, Shape::Line { from: c, to: p(w, v) });
            add(&mut d, Shape::Arc { center: c, radius: 1.0 + v.abs(), start: v, end: w });
            add(&mut d, Shape::Arc { center: c, radius: 2.0, start: v, end: v });
            add(&mut d, Shape::Arc { center: c, radius: 2.0, start: 0.0, end: std::f64::consts::TAU });
            add(&mut d, Shape::Arc { center: c, radius: 2.0, start: 1.0, end: 1.0 + 1e-13 });
            for closed in [false, true] {
                for width in [0.0, -0.0, 0.5, 4e-13] {
                    add(&mut d, Shape::Polyline { points: vec![c, p(w, v), p(1.0, 2.0)], closed, width });
                }
            }
            for n in 3..=6 {
                let pts = (0..n).map(|j| p(v + (j as f64).cos(), w + (j as f64).sin())).collect();
                add(&mut d, Shape::Filled { points: pts });
            }
            add(&mut d, Shape::Arrow { from: c, to: p(w + 3.0, v), head: 1.0 });
            add(&mut d, Shape::Arrow { from: c, to: c, head: 1.0 });
            add(&mut d, Shape::Arrow { from: c, to: p(v + 1.0, w), head: 0.0 });
            add(&mut d, Shape::Arrow { from: c, to: p(v + 1.0, w), head: 5.0 });
        }
        let texts = ["A", "φ1 = 75.77°", "ω ε π ′ αβγΔΣ", "x^y\ttab", "", " 𝄞 ", "0"];
        for (i, halign) in [HAlign::Left, HAlign::Center, HAlign::Right].into_iter().enumerate() {
            for (j, valign) in [VAlign::Baseline, VAlign::Middle, VAlign::Top].into_iter().enumerate() {
                for (r, rotation) in
                    [0.0, -0.0, 1e-15, 90f64.to_radians(), -30f64.to_radians(), 7.0].into_iter().enumerate()
                {
                    for at in [p(0.0, 0.0), p(-0.0, 1e-14), p(3.0, -4.0), p(0.0, 2.0)] {
                        let value = texts[(i + j + r) % texts.len()].to_string();
                        add(
                            &mut d,
                            Shape::Text {
                                runs: crate::draw::Runs::flat(),
                                at,
                                height: 1.0 + r as f64,
                                value,
                                halign,
                                valign,
                                rotation,
                            },
                        );
                    }
                }
            }
        }
        let o = p(0.0, 0.0);
        for (i, (a, b)) in [(0.3, 1.2), (2.0, 0.1), (0.0, 3.5), (-1.0, 1.0)].into_iter().enumerate() {
            let text = format!("φ{i} = {a}°");
            add(
                &mut d,
                Shape::AngularDimension {
                    vertex: p(a, b),
                    first: p(a + 5.0, b),
                    second: polar(p(a, b), 4.0, a + b),
                    radius: 6.0 + b,
                    text,
                    runs: Default::default(),
                },
            );
            for angle in [0.0, a, -b, std::f64::consts::PI] {
                add(
                    &mut d,
                    Shape::LinearDimension {
                        p1: o,
                        p2: p(10.0 * a, b),
                        line_at: p(0.0, -5.0),
                        angle,
                        text: format!("{a}"),
                        marks: LinearMarks::default(),
                    },
                );
            }
        }
        same_as_crate(&d);
        // Dimensions only; no dimensions; one shape of each kind alone.
        let only_dims = Drawing {
            entities: d
                .entities
                .iter()
                .filter(|e| matches!(e.shape, Shape::AngularDimension { .. } | Shape::LinearDimension { .. }))
                .cloned()
                .collect(),
            ..d.clone()
        };
        same_as_crate(&only_dims);
        let no_dims = Drawing {
            entities: d
                .entities
                .iter()
                .filter(|e| !matches!(e.shape, Shape::AngularDimension { .. } | Shape::LinearDimension { .. }))
                .cloned()
                .collect(),
            ..d.clone()
        };
        same_as_crate(&no_dims);
        for e in &d.entities {
            same_as_crate(&Drawing { entities: vec![e.clone()], ..d.clone() });
        }
    }

    /// FreeCAD reads no R12 LAYER record without a handle (issue 13): every table record has
    /// one (DIMSTYLE in group 105), unique, below $HANDSEED.
    #[test]
    fn r12_table_records_have_handles() {
        let mut d = drawing();
        d.layer("LINKS", Aci::BLUE, LineType::Continuous);
        d.layer("PATH", Aci::RED, LineType::Dashed);
        let p = write(&d);
        let mut seen = std::collections::HashSet::new();
        for kind in ["LAYER", "LTYPE", "STYLE", "VPORT", "APPID", "DIMSTYLE"] {
            let code = if kind == "DIMSTYLE" { 105 } else { 5 };
            for r in records(&p, kind).into_iter().filter(|r| r.len() > 2) {
                let h = get(&r, code);
                assert_eq!(h.len(), 1, "{kind} {:?}", get(&r, 2));
                assert!(seen.insert(u64::from_str_radix(h[0], 16).unwrap()), "{kind}: handle {} used twice", h[0]);
            }
        }
        let layer_records = records(&p, "LAYER");
        let layers: Vec<&str> = layer_records.iter().filter_map(|r| get(r, 2).first().copied()).collect();
        assert_eq!(layers, ["0", "LINKS", "PATH"]);
        let i = p.iter().position(|(c, v)| *c == 9 && v == "$HANDSEED").unwrap();
        let seed = u64::from_str_radix(&p[i + 1].1, 16).unwrap();
        assert!(seen.iter().all(|h| *h < seed));
    }

    #[test]
    fn the_scale_must_be_positive_and_finite() {
        let d = drawing();
        for k in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let opts = DxfOptions { mm_per_unit: k, ..DxfOptions::default() };
            assert!(matches!(to_bytes(&d, &opts), Err(DxfError::BadScale { .. })), "{k}");
        }
        let mut d = drawing();
        d.add(0, Shape::Circle { center: Point::new(1e306, 0.0), radius: 1.0 });
        let opts = DxfOptions { mm_per_unit: 1000.0, ..DxfOptions::default() };
        assert!(matches!(to_bytes(&d, &opts), Err(DxfError::NonFinite { .. })), "overflow to infinity");
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let mut d = drawing();
        d.add(0, Shape::Circle { center: Point::new(f64::NAN, 0.0), radius: 1.0 });
        assert!(matches!(to_bytes(&d, &DxfOptions::default()), Err(DxfError::NonFinite { entity: 0, .. })));
        let mut d = drawing();
        d.add(3, Shape::Line { from: Point::new(0.0, 0.0), to: Point::new(1.0, 0.0) });
        assert!(matches!(to_bytes(&d, &DxfOptions::default()), Err(DxfError::NoSuchLayer { layer: 3, .. })));
        let mut d = drawing();
        d.add(0, Shape::Filled { points: vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)] });
        assert!(matches!(to_bytes(&d, &DxfOptions::default()), Err(DxfError::BadShape { .. })));
        let mut d = drawing();
        d.layer("A/B", Aci::RED, LineType::Continuous);
        assert!(matches!(to_bytes(&d, &DxfOptions::default()), Err(DxfError::BadLayerName { .. })));
    }
}
