//! The `dxf` crate's writer (feature `dxf-r2000`, which the command line has): the R2000 and
//! R2007 files, and for R12 the reference path ([`super::to_bytes_via_crate`]) that the
//! hand-written R12 writer (`r12.rs`, `r12_head.rs`) is compared with byte for byte. Every
//! entity is built as a crate struct, the crate serialises the drawing, and [`fix_up`] mends
//! its text where the crate's API cannot say what is wanted (see the parent module).
//! The live page's module has no such feature: it writes R12 only.

use std::borrow::Cow;

use dxf::entities::{
    AngularThreePointDimension, Arc, Circle, DimensionBase, Entity as DxfEntity, EntityType, Line, Polyline,
    RotatedDimension, Solid, Text, Vertex,
};
use dxf::enums::{AcadVersion, DimensionType, HorizontalTextJustification, VerticalTextJustification};
use dxf::tables::{Layer as DxfLayer, LineType as DxfLineType};
use dxf::{Block, Color, Point as DxfPoint};

use super::*;

/// Transparency "opaque" (group 440, R2004+): the flag 0x02000000 with alpha 255.
const OPAQUE: i32 = 0x0200_00FF;

/// The crate path of a validated drawing.
pub(super) fn crate_bytes(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    let mut doc = build_head(drawing, opts);
    add_entities(&mut doc, drawing, opts);
    let mut raw = Vec::new();
    doc.save(&mut raw).map_err(|e| DxfError::Crate(e.to_string()))?;
    let limits_min = doc.header.paperspace_minimum_drawing_limits.clone();
    Ok(fix_up(&raw, opts.version, (-limits_min.x, -limits_min.y)))
}

fn pt(p: Point) -> DxfPoint {
    DxfPoint::new(snap(p.x), snap(p.y), 0.0)
}

fn aci(c: Aci) -> Color {
    Color::from_index(c.0)
}

/// The layer-table colour: 1–255 (0 would mean BYBLOCK, which a layer cannot have).
fn layer_color(c: Aci) -> Color {
    Color::from_index(layer_aci(c))
}

/// The DXF-epoch date (1 Jan 1900 local time = 2415021.0 whatever the time zone) used for
/// every date in the header.
fn epoch_local() -> chrono::DateTime<chrono::Local> {
    use chrono::TimeZone;
    chrono::Local.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).earliest().unwrap_or_default()
}

fn epoch_utc() -> chrono::DateTime<chrono::Utc> {
    use chrono::TimeZone;
    chrono::Utc.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).earliest().unwrap_or_default()
}

/// The crate's drawing with the HEADER and the TABLES only (no blocks, no entities).
/// `drawing` has been validated.
fn build_head(drawing: &Drawing, opts: &DxfOptions) -> dxf::Drawing {
    let mut doc = dxf::Drawing::new();
    let bounds = drawing.bounds().unwrap_or(Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
    let extent = bounds.width().max(bounds.height());
    let extent = if extent > 0.0 { extent } else { 1.0 };
    setup_header(&mut doc, drawing, opts, &bounds, extent);
    setup_tables(&mut doc, drawing, &bounds, extent);
    doc
}

/// Adds the blocks and entities of `drawing` to the crate's drawing (the reference path).
fn add_entities(doc: &mut dxf::Drawing, drawing: &Drawing, opts: &DxfOptions) {
    let style = drawing.dim_style;
    let mut dim_count = 0usize;
    for e in &drawing.entities {
        let common = Common {
            layer: drawing.layers[e.layer].name.clone(),
            color: e.color.map(aci).unwrap_or_else(Color::by_layer),
            linetype: entity_linetype(drawing, e).unwrap_or("BYLAYER"),
        };
        match &e.shape {
            Shape::AngularDimension { .. } | Shape::LinearDimension { .. } => {
                if opts.dimensions == Dimensions::Exploded {
                    let part_common = Common { linetype: CONTINUOUS, ..common };
                    for part in explode_dimension(&e.shape, &style) {
                        add_simple(doc, &part, true, &part_common);
                    }
                    continue;
                }
                for piece in dimension_pieces(&e.shape, &style) {
                    dim_count += 1;
                    let block_name = format!("*D{dim_count}");
                    add_dimension_block(doc, &block_name, &piece.geometry, &common);
                    doc.add_entity(common.entity(dimension_entity(&piece, &block_name)));
                }
            }
            shape => add_simple(doc, shape, opts.dimensions == Dimensions::Exploded, &common),
        }
    }
}

/// Adds the DXF entities of a shape other than a dimension to model space (crate path),
/// each built and added in turn, so that handles run as the hand-written R12 path gives
/// them (a POLYLINE's vertices, the POLYLINE, then the next entity); `outlined` as
/// [`prims`].
fn add_simple(doc: &mut dxf::Drawing, shape: &Shape, outlined: bool, common: &Common) {
    let mut all = Vec::new();
    prims(shape, outlined, |p| all.push(p));
    for p in all {
        let specific = crate_entity(doc, p);
        doc.add_entity(common.entity(specific));
    }
}

fn setup_header(doc: &mut dxf::Drawing, drawing: &Drawing, opts: &DxfOptions, bounds: &Bounds, extent: f64) {
    let h = &mut doc.header;
    h.version = match opts.version {
        DxfVersion::R12 => AcadVersion::R12,
        DxfVersion::R2000 => AcadVersion::R2000,
        DxfVersion::R2007 => AcadVersion::R2007,
    };
    h.handles_enabled = true;
    // R2007 text is UTF-8: the code page says so (ANSI_65001, Windows' UTF-8), so that GDAL
    // reads it as UTF-8 (it recodes from the stated code page: from ANSI_1252 it garbled φ1
    // into "Ï 1"); LibreCAD, FreeCAD, ezdxf and dxf-parser read it either way (reader
    // matrix, issue 29). R2000 text is ASCII (escapes) and R12 has no such variable.
    if opts.version == DxfVersion::R2007 {
        h.drawing_code_page = R2007_CODE_PAGE.to_string();
    }
    // The file is in millimetres (stated from R2000 on; R12 has no such variables).
    h.default_drawing_units = dxf::enums::Units::Millimeters;
    h.drawing_units = dxf::enums::DrawingUnits::Metric;
    h.text_style = TEXT_STYLE.to_string();
    // R13+ here; R12 gets it in fix_up (LibreCAD draws dimension text in this style).
    h.dimension_text_style = TEXT_STYLE.to_string();
    h.creation_date = epoch_local();
    h.update_date = epoch_local();
    h.creation_date_universal = epoch_utc();
    h.update_date_universal = epoch_utc();
    h.time_in_drawing = Default::default();
    h.user_elapsed_timer = Default::default();
    h.user_timer_on = false;
    h.fingerprint_guid = Default::default();
    h.version_guid = Default::default();
    h.minimum_drawing_extents = pt(bounds.min);
    h.maximum_drawing_extents = pt(bounds.max);
    let (lim_min, lim_max) = sheet(drawing, bounds, extent);
    let (lim_min, lim_max) = (pt(lim_min), pt(lim_max));
    h.minimum_drawing_limits = lim_min.clone();
    h.maximum_drawing_limits = lim_max.clone();
    h.paperspace_minimum_drawing_limits = lim_min;
    h.paperspace_maximum_drawing_limits = lim_max;
    // The drawing's origin on the sheet $PLIMMIN–$PLIMMAX (R14+ here; R12 gets it in fix_up).
    h.paperspace_insertion_base =
        DxfPoint::new(-h.paperspace_minimum_drawing_limits.x, -h.paperspace_minimum_drawing_limits.y, 0.0);
    h.line_type_scale = 1.0;
    // R2000+: the sheet's scale; LibreCAD draws a 0 (the crate's default) as a dot.
    h.viewport_view_scale_factor = 1.0;
    let s = drawing.dim_style;
    h.default_text_height = s.text_height;
    h.dimensioning_text_height = s.text_height;
    h.dimensioning_arrow_size = s.arrow_size;
    h.dimension_extension_line_offset = parts::EXT_LINE_GAP * s.arrow_size;
    h.dimension_extension_line_extension = parts::EXT_LINE_OVERSHOOT * s.arrow_size;
    h.dimension_line_gap = parts::LINEAR_TEXT_LIFT * s.text_height;
    h.text_above_dimension_line = true;
    h.dimension_text_inside_horizontal = false;
    h.dimension_text_outside_horizontal = false;
}

fn setup_tables(doc: &mut dxf::Drawing, drawing: &Drawing, bounds: &Bounds, extent: f64) {
    // R12 knows none of the annotative items the crate adds; keep only what R12 has.
    let remove_named = |names: Vec<String>, keep: &dyn Fn(&str) -> bool| -> Vec<usize> {
        let mut idx: Vec<usize> = names.iter().enumerate().filter(|(_, n)| !keep(n)).map(|(i, _)| i).collect();
        idx.reverse();
        idx
    };
    for i in remove_named(doc.app_ids().map(|a| a.name.clone()).collect(), &|n| n == "ACAD") {
        doc.remove_app_id(i);
    }
    for i in remove_named(doc.dim_styles().map(|a| a.name.clone()).collect(), &|n| n == "STANDARD") {
        doc.remove_dim_style(i);
    }
    for i in remove_named(doc.styles().map(|a| a.name.clone()).collect(), &|n| n == "STANDARD") {
        doc.remove_style(i);
    }
    doc.add_style(dxf::tables::Style {
        name: TEXT_STYLE.to_string(),
        primary_font_file_name: TEXT_FONT_FILE.to_string(),
        ..Default::default()
    });

    let (dash, gap) = parts::dash_pattern(extent);
    doc.add_line_type(DxfLineType {
        name: DASHED.to_string(),
        description: "Dashed __ __ __".to_string(),
        element_count: 2,
        total_pattern_length: dash + gap,
        dash_dot_space_lengths: vec![dash, -gap],
        ..Default::default()
    });
    for lt in doc.line_types_mut() {
        if lt.name == CONTINUOUS {
            lt.description = "Solid line".to_string();
        }
    }

    for (i, layer) in drawing.layers.iter().enumerate() {
        if i == 0 {
            for l in doc.layers_mut().filter(|l| l.name == "0") {
                l.color = layer_color(layer.color);
                l.line_type_name = linetype_name(layer.linetype).to_string();
                l.is_layer_on = layer.on;
            }
        } else {
            doc.add_layer(DxfLayer {
                name: layer.name.clone(),
                color: layer_color(layer.color),
                line_type_name: linetype_name(layer.linetype).to_string(),
                // Off: the crate writes the colour negative; fix_up freezes it too.
                is_layer_on: layer.on,
                ..Default::default()
            });
        }
    }

    let s = drawing.dim_style;
    for ds in doc.dim_styles_mut() {
        ds.dimensioning_text_height = s.text_height;
        ds.dimensioning_arrow_size = s.arrow_size;
        ds.dimension_extension_line_offset = parts::EXT_LINE_GAP * s.arrow_size;
        ds.dimension_extension_line_extension = parts::EXT_LINE_OVERSHOOT * s.arrow_size;
        ds.dimension_line_gap = parts::LINEAR_TEXT_LIFT * s.text_height;
        ds.text_above_dimension_line = true;
        ds.dimension_text_inside_horizontal = false;
        ds.dimension_text_outside_horizontal = false;
    }

    // Open on the whole drawing.
    let center = Point::from((bounds.min.coords + bounds.max.coords) / 2.0);
    let (w, h) = (bounds.width().max(1e-9 * extent), bounds.height().max(1e-9 * extent));
    for vp in doc.view_ports_mut() {
        vp.view_center = pt(center);
        vp.view_height = (1.0 + 2.0 * LIMITS_MARGIN) * h;
        vp.view_port_aspect_ratio = w / h;
    }
}

/// Layer, colour and line type shared by the DXF entities made from one [`Entity`].
struct Common {
    layer: String,
    color: Color,
    linetype: &'static str,
}

impl Common {
    fn entity(&self, specific: EntityType) -> DxfEntity {
        let mut e = DxfEntity::new(specific);
        // R2000+: BYLAYER lineweight (the crate's default 0 means 0 mm) and opaque (the
        // crate's 0 is an invalid transparency); neither is written to R12.
        e.common.lineweight_enum_value = -1;
        e.common.transparency = OPAQUE;
        e.common.layer = self.layer.clone();
        e.common.color = self.color.clone();
        e.common.line_type_name = self.linetype.to_string();
        e
    }
}

/// The crate's entity for a [`Prim`] (polyline vertices take their handles from `doc` here,
/// as the crate numbers them).
fn crate_entity(doc: &mut dxf::Drawing, prim: Prim) -> EntityType {
    match prim {
        Prim::Circle { center, radius } => EntityType::Circle(Circle::new(pt(center), radius)),
        Prim::Arc { center, radius, start_deg, end_deg } => {
            EntityType::Arc(Arc::new(pt(center), radius, start_deg, end_deg))
        }
        Prim::Line { from, to } => EntityType::Line(Line::new(pt(from), pt(to))),
        Prim::Polyline { points, closed, width } => crate_polyline(doc, points, closed, width),
        Prim::Outline(tri) => crate_polyline(doc, &tri, true, 0.0),
        Prim::Solid([a, b, c, d]) => EntityType::Solid(Solid::new(pt(a), pt(b), pt(c), pt(d))),
        Prim::Text { at, insert, height, value, halign, valign, rotation_deg, width } => {
            let mut t = Text {
                location: pt(insert),
                text_height: height,
                value: value.to_string(),
                rotation: rotation_deg,
                relative_x_scale_factor: width,
                text_style_name: TEXT_STYLE.to_string(),
                horizontal_text_justification: match halign {
                    HAlign::Left => HorizontalTextJustification::Left,
                    HAlign::Center => HorizontalTextJustification::Center,
                    HAlign::Right => HorizontalTextJustification::Right,
                },
                vertical_text_justification: match valign {
                    VAlign::Baseline => VerticalTextJustification::Baseline,
                    VAlign::Middle => VerticalTextJustification::Middle,
                    VAlign::Top => VerticalTextJustification::Top,
                },
                ..Default::default()
            };
            if halign != HAlign::Left || valign != VAlign::Baseline {
                // Readers place justified text by the alignment point (11/21); the insertion
                // point (10/20) is where the text starts, for readers that ignore alignment.
                t.second_alignment_point = pt(at);
            }
            EntityType::Text(t)
        }
    }
}

/// A POLYLINE with its vertices (their handles taken from `doc`, as the crate numbers them).
fn crate_polyline(doc: &mut dxf::Drawing, points: &[Point], closed: bool, width: f64) -> EntityType {
    let mut poly = Polyline { default_starting_width: width, default_ending_width: width, ..Default::default() };
    poly.set_is_closed(closed);
    for p in points {
        let v = Vertex { starting_width: width, ending_width: width, ..Vertex::new(pt(*p)) };
        poly.add_vertex(doc, v);
    }
    EntityType::Polyline(poly)
}

/// DXF entities for a shape other than a dimension (crate path); `outlined` as [`prims`].
fn simple_entities(doc: &mut dxf::Drawing, shape: &Shape, outlined: bool) -> Vec<EntityType> {
    let mut all = Vec::new();
    prims(shape, outlined, |p| all.push(p));
    all.into_iter().map(|p| crate_entity(doc, p)).collect()
}

/// The anonymous block `name` with a dimension's exploded geometry (`geometry`, a
/// [`DimPiece`]'s), on the dimension's layer in its colour (explicit rather than BYBLOCK:
/// ezdxf's renderer draws BYBLOCK dimension geometry black) and line type CONTINUOUS
/// (dimensions are never dashed, as in the SVG).
fn add_dimension_block(doc: &mut dxf::Drawing, name: &str, geometry: &[Shape], dim: &Common) {
    let common = Common { layer: dim.layer.clone(), color: dim.color.clone(), linetype: CONTINUOUS };
    let mut entities = Vec::new();
    for part in geometry {
        for specific in simple_entities(doc, part, false) {
            entities.push(common.entity(specific));
        }
    }
    let mut block = Block { name: name.to_string(), layer: "0".to_string(), entities, ..Default::default() };
    block.set_is_anonymous(true);
    doc.add_block(block);
}

/// The DIMENSION entity of a piece, pointing at `block_name` (crate path).
fn dimension_entity(piece: &DimPiece, block_name: &str) -> EntityType {
    let base = |def1: Point, text_mid: Point, kind: DimensionType| DimensionBase {
        block_name: block_name.to_string(),
        definition_point_1: pt(def1),
        text_mid_point: pt(text_mid),
        dimension_type: kind,
        text: piece.text.to_string(),
        is_block_reference_referenced_by_this_block_only: true,
        is_at_user_defined_location: true,
        ..Default::default()
    };
    match piece.prim {
        DimPrim::Angular { two_line, def1, text_at, defs: [p13, p14, p15, p16] } => {
            // The crate has no 2-line angular type; the 3-point one has the same groups (its
            // R2000 subclass marker is renamed in fix_up).
            let kind = if two_line { DimensionType::Angular } else { DimensionType::AngularThreePoint };
            EntityType::AngularThreePointDimension(AngularThreePointDimension {
                dimension_base: base(def1, text_at, kind),
                definition_point_2: pt(p13),
                definition_point_3: pt(p14),
                definition_point_4: pt(p15),
                definition_point_5: pt(p16),
            })
        }
        DimPrim::Rotated { on_line, text_mid, p1, p2, angle_deg } => EntityType::RotatedDimension(RotatedDimension {
            dimension_base: base(on_line, text_mid, DimensionType::RotatedHorizontalOrVertical),
            definition_point_2: pt(p1),
            definition_point_3: pt(p2),
            rotation_angle: angle_deg,
            ..Default::default()
        }),
    }
}

/// One group-code/value pair of the crate's output: its code as written (with the padding),
/// the code's number, and the value. Pairs are borrowed from the crate's text unless the
/// fix-up replaces them.
struct Pair<'a> {
    /// The code line as written (e.g. `"  8"`).
    code_text: Cow<'a, str>,
    /// The code's number (−1 if the line is not a number).
    code: i32,
    /// The value line.
    value: Cow<'a, str>,
}

impl<'a> Pair<'a> {
    fn borrowed(code_text: &'a str, value: &'a str) -> Pair<'a> {
        Pair {
            code_text: Cow::Borrowed(code_text),
            code: code_text.trim_ascii().parse().unwrap_or(-1),
            value: value.into(),
        }
    }

    fn owned(code_text: &'static str, value: String) -> Pair<'a> {
        Pair { code_text: Cow::Borrowed(code_text), code: code_text.trim().parse().unwrap_or(-1), value: value.into() }
    }
}

/// The lines of `text` split at CRLF, as `text.split("\r\n")` gives them, but found with a
/// fast search for the line feed (the general substring search is a good part of the
/// fix-up's time on a large drawing).
fn crlf_lines(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let s = rest?;
        let mut from = 0;
        // Lines are short: a plain scan beats a vectorised search here.
        while let Some(k) = s.as_bytes()[from..].iter().position(|&b| b == b'\n') {
            let at = from + k;
            if at > 0 && s.as_bytes()[at - 1] == b'\r' {
                rest = Some(&s[at + 1..]);
                return Some(&s[..at - 1]);
            }
            from = at + 1;
        }
        rest = None;
        Some(s)
    })
}

/// Fixes the crate's text output where its API cannot: see the module documentation.
/// Works record by record (a record runs from one group-0 pair to the next), in one pass
/// that borrows every pair it leaves unchanged.
fn fix_up(raw: &[u8], version: DxfVersion, paper_insertion_base: (f64, f64)) -> Vec<u8> {
    let text = String::from_utf8_lossy(raw);
    // The pairs, read from the text as they are needed (a whole drawing's pairs would take
    // several times the text's memory).
    let pairs = || {
        let mut lines = crlf_lines(&text);
        std::iter::from_fn(move || Some(Pair::borrowed(lines.next()?, lines.next()?)))
    };
    let r12 = version == DxfVersion::R12;
    // R2000: handles for the TABLE heads and the ENDBLKs (the crate writes none, resp. the
    // BLOCK's), numbered after the highest handle the crate assigned. (R12 needs neither.)
    let mut handles = if r12 { Handles { next: 0, seed: 0 } } else { Handles::after(pairs()) };

    let mut out = String::with_capacity(raw.len() + 1024);
    let mut section = "";
    let mut poly_layer: Option<String> = None;
    let mut pairs = pairs().peekable();
    let mut record: Vec<Pair> = Vec::new();
    while let Some(first) = pairs.next() {
        record.clear();
        record.push(first);
        while let Some(p) = pairs.next_if(|p| p.code != 0) {
            record.push(p);
        }
        let kind = record[0].value.clone();
        if let Some(p) = record.get(1).filter(|p| kind == "SECTION" && p.code == 2) {
            section = match p.value.as_ref() {
                "TABLES" => "TABLES",
                "BLOCKS" => "BLOCKS",
                "ENTITIES" => "ENTITIES",
                _ => "",
            };
        }
        let is_header = kind == "SECTION" && record.get(1).is_some_and(|p| p.value == "HEADER");
        if r12 && is_header {
            r12_header(&mut record, paper_insertion_base);
        }
        if section == "TABLES" {
            table_record(&mut record, &kind);
        }
        if r12 {
            // R12 has no subclass markers. Its table records keep their handles (group 5,
            // 105 in DIMSTYLE), as R12 allows with $HANDLING = 1: FreeCAD cannot read a
            // LAYER record without one ("no layer name").
            record.retain(|p| p.code != 100);
        } else {
            handles.r2000_record(&mut record, &kind, is_header);
        }
        poly_layer = vertices_and_text(&mut record, &kind, poly_layer);
        for p in &record {
            push_pair(&mut out, &p.code_text, &p.value);
        }
    }
    out.into_bytes()
}

/// The handles `fix_up` gives out in an R2000 file: the next free one and the seed the
/// header states ($HANDSEED), past all of them.
struct Handles {
    next: u64,
    seed: u64,
}

impl Handles {
    /// After the highest handle the crate assigned in `pairs`, room for a handle per TABLE
    /// head and per ENDBLK.
    fn after<'a>(pairs: impl Iterator<Item = Pair<'a>>) -> Handles {
        let (mut highest, mut extra) = (0u64, 0u64);
        for p in pairs {
            match p.code {
                5 | 105 => highest = highest.max(u64::from_str_radix(p.value.trim(), 16).unwrap_or(0)),
                0 if p.value == "TABLE" || p.value == "ENDBLK" => extra += 1,
                _ => {}
            }
        }
        Handles { next: highest + 1, seed: highest + 1 + extra }
    }

    /// Takes the next free handle, in hexadecimal.
    fn take(&mut self) -> String {
        self.next += 1;
        format!("{:X}", self.next - 1)
    }

    /// R2000 and later: the header's $HANDSEED, a handle for each TABLE head and ENDBLK,
    /// the 2-line angular dimension's subclass, the vertices' lineweight and transparency.
    fn r2000_record(&mut self, record: &mut Vec<Pair>, kind: &str, is_header: bool) {
        if is_header
            && let Some(at) = record.iter().position(|p| p.code == 9 && p.value == "$HANDSEED")
            && let Some(pair) = record.get_mut(at + 1)
        {
            pair.value = format!("{:X}", self.seed).into();
        }
        match kind {
            "TABLE" => {
                let at = if record.get(1).is_some_and(|p| p.code == 2) { 2 } else { 1 };
                record.insert(at, Pair::owned("  5", self.take()));
                record.insert(at + 1, Pair::owned("330", "0".to_string()));
            }
            "ENDBLK" => {
                let handle = self.take();
                match record.iter_mut().find(|p| p.code == 5) {
                    Some(pair) => pair.value = handle.into(),
                    None => record.insert(1, Pair::owned("  5", handle)),
                }
            }
            // The 2-line angular dimension, written as the crate's 3-point one.
            "DIMENSION" => {
                let two_line =
                    record.iter().any(|p| p.code == 70 && p.value.trim().parse::<i32>().is_ok_and(|v| v & 7 == 2));
                if two_line {
                    for pair in record.iter_mut().filter(|p| p.code == 100 && p.value == "AcDb3PointAngularDimension") {
                        pair.value = Cow::Borrowed("AcDb2LineAngularDimension");
                    }
                }
            }
            // Lineweight BYLAYER on the vertices the crate builds itself (it writes 0 mm).
            // ... and opaque (R2007: the crate's 0 is an invalid transparency).
            "VERTEX" => {
                for pair in record.iter_mut() {
                    match pair.code {
                        370 => pair.value = format!("{:>6}", -1).into(),
                        440 => pair.value = format!("{:>9}", OPAQUE).into(),
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }
}

/// R12's header: $DIMTXSTY (the crate writes it from R13 on; LibreCAD draws the dimension
/// text it regenerates in this style) and $PINSBASE at `paper_insertion_base` (the crate
/// writes it from R14 on: where the drawing's origin lies on the sheet $PLIMMIN–$PLIMMAX;
/// LibreCAD prints that sheet with the drawing on it).
fn r12_header(record: &mut Vec<Pair>, paper_insertion_base: (f64, f64)) {
    if let Some(at) = record.iter().position(|p| p.code == 9 && p.value == "$TEXTSTYLE") {
        let var = [("  9", "$DIMTXSTY".to_string()), ("  7", TEXT_STYLE.to_string())];
        for (k, (c, v)) in var.into_iter().enumerate() {
            record.insert(at + 2 + k, Pair::owned(c, v));
        }
    }
    if let Some(at) = record.iter().position(|p| p.code == 9 && p.value == "$PLIMMAX") {
        let next = record[at + 1..].iter().position(|p| p.code == 9).map_or(record.len(), |k| at + 1 + k);
        let (x, y) = paper_insertion_base;
        let var = [("  9", "$PINSBASE".to_string()), (" 10", fmt_f64(x)), (" 20", fmt_f64(y)), (" 30", fmt_f64(0.0))];
        for (k, (c, v)) in var.into_iter().enumerate() {
            record.insert(next + k, Pair::owned(c, v));
        }
    }
}

/// A record of the TABLES section: a layer that is off (negative colour) frozen too (flag
/// 1: LibreCAD, QCAD and others read a layer's visibility from the flag alone and show an
/// off layer); a DIMSTYLE's handle in group 105 (5 is $DIMBLK there).
fn table_record(record: &mut [Pair], kind: &str) {
    if kind == "LAYER" && record.iter().any(|p| p.code == 62 && p.value.trim().starts_with('-')) {
        for pair in record.iter_mut().filter(|p| p.code == 70) {
            pair.value = Cow::Borrowed("     1");
        }
    }
    if kind == "DIMSTYLE" {
        for pair in record.iter_mut().filter(|p| p.code == 5) {
            pair.code_text = Cow::Borrowed("105");
            pair.code = 105;
        }
    }
}

/// Every version: a polyline's VERTEX and SEQEND records on the POLYLINE's layer
/// (`poly_layer`, the layer of the polyline being written), a justified TEXT's alignment
/// point (the crate omits it when it is (0, 0)); returns the polyline's layer for the next
/// record.
fn vertices_and_text(record: &mut Vec<Pair>, kind: &str, poly_layer: Option<String>) -> Option<String> {
    match kind {
        "POLYLINE" => record.iter().find(|p| p.code == 8).map(|p| p.value.to_string()),
        "VERTEX" | "SEQEND" => {
            if let Some(layer) = &poly_layer {
                match record.iter_mut().find(|p| p.code == 8) {
                    Some(pair) => pair.value = layer.clone().into(),
                    None => {
                        // After the type and the handle.
                        let at = if record.get(1).is_some_and(|p| p.code == 5) { 2 } else { 1 };
                        record.insert(at.min(record.len()), Pair::owned("  8", layer.clone()));
                    }
                }
            }
            poly_layer
        }
        "TEXT" => {
            let justified = record.iter().any(|p| (p.code == 72 || p.code == 73) && p.value.trim() != "0");
            if justified && !record.iter().any(|p| p.code == 11) {
                let at = record.iter().position(|p| p.code == 72 || p.code == 73).unwrap_or(record.len());
                let at = if record.get(at).is_some_and(|p| p.code == 72) { at + 1 } else { at };
                for (i, c) in [" 11", " 21", " 31"].into_iter().enumerate() {
                    record.insert(at + i, Pair::owned(c, "0.0".to_string()));
                }
            }
            None
        }
        _ => None,
    }
}

/// A float as the crate writes it: at most 12 decimals, trailing zeros trimmed, at least one
/// decimal.
fn fmt_f64(v: f64) -> String {
    let s = format!("{:.12}", snap(v));
    let s = s.trim_end_matches('0');
    if s.ends_with('.') { format!("{s}0") } else { s.to_string() }
}

fn push_pair(out: &mut String, code: &str, value: &str) {
    out.push_str(code);
    out.push_str("\r\n");
    out.push_str(value);
    out.push_str("\r\n");
}

#[cfg(test)]
mod tests {
    use super::crlf_lines;

    #[test]
    fn crlf_lines_split_as_the_substring_split_does() {
        for text in ["", "a", "a\r\n", "a\r\nb", "\r\n\r\n", "a\nb\r\nc\r", "\n\r\n", "x\r\r\ny\n"] {
            let expected: Vec<&str> = text.split("\r\n").collect();
            assert_eq!(crlf_lines(text).collect::<Vec<_>>(), expected, "{text:?}");
        }
    }
}
