//! The R12 writer, by hand: HEADER and TABLES (`head.rs`, small: mostly fixed text), then
//! BLOCKS and ENTITIES straight into the output buffer, in exactly the form the `dxf` crate
//! and the fix-up give them (the crate path, `to_bytes_via_crate` with the feature
//! `dxf-r2000`, is the reference the tests compare with byte for byte).
//!
//! The form, as the crate writes R12 and the fix-up leaves it: group codes right-aligned in
//! three characters, CRLF line ends, 16-bit integers right-aligned in six, floats with at most
//! 12 decimals (trailing zeros trimmed, at least one decimal, the sign of `-0` kept where the
//! value is not snapped), strings with control characters and `^` as caret escapes and every
//! non-ASCII character as `\U+XXXX`. Handles continue the crate's numbering after the tables:
//! a dimension's BLOCK takes one, its (R12-unwritten) BLOCK_RECORD the next, its entities the
//! following ones, the DIMENSION the next; a polyline's vertices come before the POLYLINE,
//! its SEQEND after. `$HANDSEED` is the next free handle.
//! With [`super::Dimensions::Exploded`] a dimension's parts are written as entities in
//! drawing order instead (no BLOCK, no DIMENSION), as the crate path adds them.

use std::io::Write;

use super::{
    CONTINUOUS, DimPiece, DimPrim, Dimensions, DxfError, DxfOptions, DxfVersion, Prim, TEXT_STYLE, dimension_pieces,
    entity_linetype, prims, snap,
};

mod head;

/// About the size of the HEADER and TABLES sections with a few layers.
const HEAD_BYTES: usize = 8 * 1024;
use crate::draw::parts::explode_dimension;
use crate::draw::{Drawing, Entity, HAlign, Shape, VAlign};
use crate::geom::Point;

/// Writes a validated drawing (in mm) as R12.
pub(super) fn to_bytes(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<u8>, DxfError> {
    Ok(to_pieces(drawing, opts)?.concat())
}

/// Entities written by one job (a motion's few hundred thousand lines of entities are split
/// among the cores; a small drawing is one job).
const ENTITIES_PER_JOB: usize = 1024;

/// [`to_bytes`] in pieces, the file being the one after the other: the file up to the
/// BLOCKS section's first block (or the ENTITIES section's first entity), each job's blocks,
/// the ENTITIES section's start, each job's entities, the end of the file. Jobs of
/// [`ENTITIES_PER_JOB`] entities are written in parallel, so that the pieces (most of a
/// motion's file) are neither written on one core nor copied to join them.
pub(super) fn to_pieces(drawing: &Drawing, opts: &DxfOptions) -> Result<Vec<Vec<u8>>, DxfError> {
    to_pieces_in(drawing, opts, ENTITIES_PER_JOB)
}

/// [`to_pieces`] with `per_job` entities per job (the tests try every job boundary).
pub(super) fn to_pieces_in(drawing: &Drawing, opts: &DxfOptions, per_job: usize) -> Result<Vec<Vec<u8>>, DxfError> {
    let opts = DxfOptions { version: DxfVersion::R12, ..*opts };
    let first_handle = head::first_handle(drawing);
    let Some((written, next)) = jobs(drawing, &opts, per_job, first_handle) else {
        debug_assert!(false, "a job's handle count differs from what it wrote");
        return to_pieces_in(drawing, &opts, drawing.entities.len());
    };
    let mut out = Vec::with_capacity(HEAD_BYTES);
    head::write(&mut out, drawing, next);
    let mut pieces = Vec::with_capacity(2 * written.len() + 3);
    let (blocks, entities): (Vec<Vec<u8>>, Vec<Vec<u8>>) = written.into_iter().unzip();
    let entities_start = b"  0\r\nSECTION\r\n  2\r\nENTITIES\r\n";
    if blocks.iter().any(|b| !b.is_empty()) {
        out.extend_from_slice(b"  0\r\nSECTION\r\n  2\r\nBLOCKS\r\n");
        pieces.push(out);
        pieces.extend(blocks.into_iter().filter(|b| !b.is_empty()));
        pieces.push([&b"  0\r\nENDSEC\r\n"[..], entities_start].concat());
    } else {
        out.extend_from_slice(entities_start);
        pieces.push(out);
    }
    pieces.extend(entities.into_iter().filter(|e| !e.is_empty()));
    pieces.push(b"  0\r\nENDSEC\r\n  0\r\nEOF\r\n".to_vec());
    Ok(pieces)
}

/// What one job wrote: its part of the BLOCKS section, then of the ENTITIES section.
type JobBytes = (Vec<u8>, Vec<u8>);

/// The BLOCKS and ENTITIES contents in jobs of `per_job` entities, written in parallel with
/// handles from `first_handle` on: each job's blocks and entities, and the next free handle.
/// Each job's handles and dimensions are counted first ([`count`]), which says where the
/// next job's numbering starts; `None` if a job did not end where the count said (a bug:
/// the caller then writes one job).
fn jobs(drawing: &Drawing, opts: &DxfOptions, per_job: usize, first_handle: u64) -> Option<(Vec<JobBytes>, u64)> {
    use crate::par::prelude::*;
    // Layer names escaped once, for every job.
    let layers: Vec<String> = drawing
        .layers
        .iter()
        .map(|l| {
            let mut v = Vec::new();
            escaped(&mut v, &l.name);
            String::from_utf8(v).unwrap_or_default()
        })
        .collect();
    let jobs: Vec<&[Entity]> = drawing.entities.chunks(per_job.max(1)).collect();
    let counts: Vec<(u64, usize)> = jobs.par_iter().map(|es| count(drawing, es, opts.dimensions)).collect();
    let mut starts = Vec::with_capacity(jobs.len());
    let (mut next, mut dims) = (first_handle, 0usize);
    for &(handles, dimensions) in &counts {
        starts.push((next, dims));
        next += handles;
        dims += dimensions;
    }
    let written: Vec<(Vec<u8>, Vec<u8>, u64)> = jobs
        .par_iter()
        .zip(&starts)
        .map(|(es, &(first, dims))| {
            let mut body = Body::new(drawing, &layers, first, dims, opts.dimensions, es.len());
            body.write(es);
            (body.blocks, body.entities, body.next)
        })
        .collect();
    // A job ends where the next begins (one job is right by construction).
    if !written.iter().zip(starts.iter().skip(1)).all(|((_, _, end), &(begin, _))| *end == begin) {
        return None;
    }
    let next = written.last().map_or(first_handle, |w| w.2);
    Some((written.into_iter().map(|(b, e, _)| (b, e)).collect(), next))
}

/// The handles and the dimensions (anonymous blocks) that [`Body::write`] takes for
/// `entities`, without writing them.
fn count(drawing: &Drawing, entities: &[Entity], dimensions: Dimensions) -> (u64, usize) {
    // A polyline takes its vertices, the POLYLINE and its SEQEND; every other entity one.
    let of = |p: Prim| match p {
        Prim::Polyline { points, .. } => points.len() as u64 + 2,
        Prim::Outline(tri) => tri.len() as u64 + 2,
        _ => 1,
    };
    let mut handles = 0u64;
    let mut dims = 0usize;
    for e in entities {
        match &e.shape {
            shape @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                if dimensions == Dimensions::Exploded {
                    for part in explode_dimension(shape, &drawing.dim_style) {
                        prims(&part, true, |p| handles += of(p));
                    }
                    continue;
                }
                for piece in dimension_pieces(shape, &drawing.dim_style) {
                    dims += 1;
                    // The block's entities, the BLOCK and its BLOCK_RECORD, the DIMENSION.
                    for part in &piece.geometry {
                        prims(part, false, |p| handles += of(p));
                    }
                    handles += 3;
                }
            }
            shape => prims(shape, dimensions == Dimensions::Exploded, |p| handles += of(p)),
        }
    }
    (handles, dims)
}

/// Layer (escaped), line type and colour of the entities written for one drawing entity.
#[derive(Clone, Copy)]
struct Style<'a> {
    layer: &'a str,
    linetype: Option<&'static str>,
    color: Option<u8>,
}

/// One job's BLOCKS and ENTITIES contents being written, and the next handle.
struct Body<'a> {
    drawing: &'a Drawing,
    /// How dimensions are written.
    dimensions: Dimensions,
    /// Layer names as written (escaped once per layer).
    layers: &'a [String],
    /// Dimensions (anonymous blocks `*D1`, `*D2`, …) written before this one.
    dim_count: usize,
    blocks: Vec<u8>,
    entities: Vec<u8>,
    next: u64,
}

impl<'a> Body<'a> {
    fn new(
        drawing: &'a Drawing,
        layers: &'a [String],
        first_handle: u64,
        dim_count: usize,
        dimensions: Dimensions,
        entities: usize,
    ) -> Body<'a> {
        Body {
            drawing,
            dimensions,
            layers,
            dim_count,
            blocks: Vec::new(),
            entities: Vec::with_capacity(entities * 160),
            next: first_handle,
        }
    }

    /// Writes `entities` (and every dimension's block), in drawing order.
    fn write(&mut self, entities: &[Entity]) {
        let drawing = self.drawing;
        let layers = self.layers;
        let mut name = String::new();
        for e in entities {
            let style = Style {
                layer: layers.get(e.layer).map_or("0", String::as_str),
                linetype: entity_linetype(drawing, e),
                color: e.color.map(|c| c.0),
            };
            match &e.shape {
                shape @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. })
                    if self.dimensions == Dimensions::Exploded =>
                {
                    let part_style = Style { linetype: Some(CONTINUOUS), ..style };
                    let next = &mut self.next;
                    let out = &mut self.entities;
                    for part in explode_dimension(shape, &drawing.dim_style) {
                        prims(&part, true, |p| prim(out, next, p, part_style));
                    }
                }
                shape @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                    for piece in dimension_pieces(shape, &drawing.dim_style) {
                        self.dim_count += 1;
                        name.clear();
                        name.push_str("*D");
                        name.push_str(&self.dim_count.to_string());
                        self.dimension(&piece, &name, style);
                    }
                }
                shape => {
                    let next = &mut self.next;
                    let out = &mut self.entities;
                    prims(shape, self.dimensions == Dimensions::Exploded, |p| prim(out, next, p, style));
                }
            }
        }
    }

    /// A dimension piece's anonymous block (its exploded geometry on the dimension's layer in
    /// its colour, line type CONTINUOUS) and its DIMENSION entity.
    fn dimension(&mut self, piece: &DimPiece, name: &str, style: Style) {
        let block_handle = self.next;
        // The BLOCK, then its BLOCK_RECORD (not written to R12).
        self.next += 2;
        let b = &mut self.blocks;
        b.extend_from_slice(b"  0\r\nBLOCK\r\n  8\r\n0\r\n");
        string(b, b"  2", name);
        b.extend_from_slice(b" 70\r\n     1\r\n 10\r\n0.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n");
        string(b, b"  3", name);
        b.extend_from_slice(b"  1\r\n\r\n");
        let part_style = Style { linetype: Some(CONTINUOUS), ..style };
        for part in &piece.geometry {
            prims(part, false, |p| prim(b, &mut self.next, p, part_style));
        }
        b.extend_from_slice(b"  0\r\nENDBLK\r\n");
        handle(b, block_handle);
        b.extend_from_slice(b"  8\r\n0\r\n");

        let o = &mut self.entities;
        common(o, b"DIMENSION", self.next, style);
        self.next += 1;
        string(o, b"  2", name);
        let (def1, text_mid, flags) = match piece.prim {
            DimPrim::Angular { two_line, def1, text_at, .. } => {
                (def1, text_at, if two_line { 2 } else { 5 } | 32 | 128)
            }
            DimPrim::Rotated { on_line, text_mid, .. } => (on_line, text_mid, 32 | 128),
        };
        point(o, b" 10", b" 20", b" 30", def1);
        point(o, b" 11", b" 21", b" 31", text_mid);
        short(o, b" 70", flags);
        string(o, b"  1", piece.text);
        o.extend_from_slice(b"  3\r\nSTANDARD\r\n");
        match piece.prim {
            DimPrim::Angular { defs: [p13, p14, p15, p16], .. } => {
                point(o, b" 13", b" 23", b" 33", p13);
                point(o, b" 14", b" 24", b" 34", p14);
                point(o, b" 15", b" 25", b" 35", p15);
                point(o, b" 16", b" 26", b" 36", p16);
            }
            DimPrim::Rotated { p1, p2, angle_deg, .. } => {
                point(o, b" 13", b" 23", b" 33", p1);
                point(o, b" 14", b" 24", b" 34", p2);
                float(o, b" 50", angle_deg);
            }
        }
    }
}

/// Writes one entity (a polyline with its vertices and SEQEND), taking handles from `next`.
fn prim(o: &mut Vec<u8>, next: &mut u64, p: Prim, style: Style) {
    match p {
        Prim::Circle { center, radius } => {
            common(o, b"CIRCLE", take(next), style);
            point(o, b" 10", b" 20", b" 30", center);
            float(o, b" 40", radius);
        }
        Prim::Arc { center, radius, start_deg, end_deg } => {
            common(o, b"ARC", take(next), style);
            point(o, b" 10", b" 20", b" 30", center);
            float(o, b" 40", radius);
            float(o, b" 50", start_deg);
            float(o, b" 51", end_deg);
        }
        Prim::Line { from, to } => {
            common(o, b"LINE", take(next), style);
            point(o, b" 10", b" 20", b" 30", from);
            point(o, b" 11", b" 21", b" 31", to);
        }
        Prim::Solid([a, b, c, d]) => {
            common(o, b"SOLID", take(next), style);
            point(o, b" 10", b" 20", b" 30", a);
            point(o, b" 11", b" 21", b" 31", b);
            point(o, b" 12", b" 22", b" 32", c);
            point(o, b" 13", b" 23", b" 33", d);
        }
        Prim::Polyline { points, closed, width } => polyline(o, next, points, closed, width, style),
        Prim::Outline(tri) => polyline(o, next, &tri, true, 0.0, style),
        Prim::Text { at, insert, height, value, halign, valign, rotation_deg, width } => {
            common(o, b"TEXT", take(next), style);
            point(o, b" 10", b" 20", b" 30", insert);
            float(o, b" 40", height);
            string(o, b"  1", value);
            if rotation_deg != 0.0 {
                float(o, b" 50", rotation_deg);
            }
            if width != 1.0 {
                float(o, b" 41", width);
            }
            string(o, b"  7", TEXT_STYLE);
            match halign {
                HAlign::Left => {}
                HAlign::Center => short(o, b" 72", 1),
                HAlign::Right => short(o, b" 72", 2),
            }
            if halign != HAlign::Left || valign != VAlign::Baseline {
                point(o, b" 11", b" 21", b" 31", at);
            }
            match valign {
                VAlign::Baseline => {}
                VAlign::Middle => short(o, b" 73", 2),
                VAlign::Top => short(o, b" 73", 3),
            }
        }
    }
}

/// A POLYLINE with its VERTEXes and SEQEND, taking handles from `next`: the crate numbers
/// the vertices as they are added, before the POLYLINE.
fn polyline(o: &mut Vec<u8>, next: &mut u64, points: &[Point], closed: bool, width: f64, style: Style) {
    let first_vertex = *next;
    *next += points.len() as u64;
    common(o, b"POLYLINE", take(next), style);
    o.extend_from_slice(b" 66\r\n     1\r\n 10\r\n0.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n");
    if closed {
        short(o, b" 70", 1);
    }
    if width != 0.0 {
        float(o, b" 40", width);
        float(o, b" 41", width);
    }
    for (k, p) in points.iter().enumerate() {
        // Vertices and SEQEND: the polyline's layer, no colour or line type of their own.
        o.extend_from_slice(b"  0\r\nVERTEX\r\n");
        handle(o, first_vertex + k as u64);
        layer(o, style.layer);
        point(o, b" 10", b" 20", b" 30", *p);
        if width != 0.0 {
            float(o, b" 40", width);
            float(o, b" 41", width);
        }
        o.extend_from_slice(b" 70\r\n     0\r\n 50\r\n0.0\r\n");
    }
    o.extend_from_slice(b"  0\r\nSEQEND\r\n");
    handle(o, take(next));
    layer(o, style.layer);
}

/// The current handle, advancing `next`.
fn take(next: &mut u64) -> u64 {
    let h = *next;
    *next += 1;
    h
}

/// Type, handle, layer, line type (unless BYLAYER) and colour (unless BYLAYER).
fn common(o: &mut Vec<u8>, kind: &[u8], h: u64, style: Style) {
    o.extend_from_slice(b"  0\r\n");
    o.extend_from_slice(kind);
    o.extend_from_slice(b"\r\n");
    handle(o, h);
    layer(o, style.layer);
    if let Some(lt) = style.linetype {
        o.extend_from_slice(b"  6\r\n");
        o.extend_from_slice(lt.as_bytes());
        o.extend_from_slice(b"\r\n");
    }
    if let Some(c) = style.color {
        short(o, b" 62", i16::from(c));
    }
}

/// Group 8 with the layer name as written (already escaped).
fn layer(o: &mut Vec<u8>, name: &str) {
    o.extend_from_slice(b"  8\r\n");
    o.extend_from_slice(name.as_bytes());
    o.extend_from_slice(b"\r\n");
}

/// Group 5 with the handle in upper-case hex.
fn handle(o: &mut Vec<u8>, h: u64) {
    o.extend_from_slice(b"  5\r\n");
    hex(o, h);
    o.extend_from_slice(b"\r\n");
}

fn hex(o: &mut Vec<u8>, h: u64) {
    let mut buf = [0u8; 16];
    let mut i = buf.len();
    let mut v = h;
    loop {
        i -= 1;
        buf[i] = b"0123456789ABCDEF"[(v & 15) as usize];
        v >>= 4;
        if v == 0 {
            break;
        }
    }
    o.extend_from_slice(&buf[i..]);
}

/// A point's x and y (snapped) and z = 0.
fn point(o: &mut Vec<u8>, cx: &[u8], cy: &[u8], cz: &[u8], p: Point) {
    float(o, cx, snap(p.x));
    float(o, cy, snap(p.y));
    o.extend_from_slice(cz);
    o.extend_from_slice(b"\r\n0.0\r\n");
}

/// A float pair, the value as the crate formats it (not snapped here).
fn float(o: &mut Vec<u8>, code: &[u8], v: f64) {
    o.extend_from_slice(code);
    o.extend_from_slice(b"\r\n");
    write_f64(o, v);
    o.extend_from_slice(b"\r\n");
}

/// A 16-bit integer pair, right-aligned in six characters.
fn short(o: &mut Vec<u8>, code: &[u8], v: i16) {
    o.extend_from_slice(code);
    o.extend_from_slice(b"\r\n");
    let mut buf = [b' '; 6];
    let mut i = digits(&mut buf, u64::from(v.unsigned_abs()));
    if v < 0 {
        i -= 1;
        buf[i] = b'-';
    }
    o.extend_from_slice(&buf);
    o.extend_from_slice(b"\r\n");
}

/// Writes the decimal digits of `m` right-aligned at the end of `buf` (which must be long
/// enough); returns the index of the first digit.
fn digits(buf: &mut [u8], mut m: u64) -> usize {
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (m % 10) as u8;
        m /= 10;
        if m == 0 {
            return i;
        }
    }
}

/// A string pair, escaped as the crate escapes R12 text.
fn string(o: &mut Vec<u8>, code: &[u8], s: &str) {
    o.extend_from_slice(code);
    o.extend_from_slice(b"\r\n");
    escaped(o, s);
    o.extend_from_slice(b"\r\n");
}

/// `s` as the crate writes a string to R12: control characters (U+0000–U+001F) as `^@`…`^_`,
/// `^` as `^ `, then every non-ASCII character as `\U+XXXX` (at least four hex digits).
fn escaped(o: &mut Vec<u8>, s: &str) {
    if s.bytes().all(|b| (0x20..0x80).contains(&b) && b != b'^') {
        o.extend_from_slice(s.as_bytes());
        return;
    }
    for c in s.chars() {
        let u = c as u32;
        if u <= 0x1F {
            o.push(b'^');
            o.push(u as u8 + 0x40);
        } else if c == '^' {
            o.extend_from_slice(b"^ ");
        } else if u >= 0x80 {
            // Cannot fail: writing to a Vec.
            let _ = write!(o, "\\U+{u:04X}");
        } else {
            o.push(u as u8);
        }
    }
}

/// `v` as the crate formats a float (`format!("{v:.12}")` with trailing zeros trimmed and at
/// least one decimal), without allocating: the exact binary value rounded half-to-even to 12
/// decimals in 128-bit integers, as the standard library rounds. Magnitudes of 2⁶³ and more
/// (and non-finite values, which validation excludes) go through the standard formatter.
pub(super) fn write_f64(o: &mut Vec<u8>, v: f64) {
    const SCALE: u128 = 1_000_000_000_000;
    let bits = v.to_bits();
    let negative = bits >> 63 == 1;
    let exp_bits = ((bits >> 52) & 0x7FF) as i32;
    let frac_bits = bits & ((1u64 << 52) - 1);
    let (mant, exp) = if exp_bits == 0 { (frac_bits, -1074) } else { (frac_bits | (1u64 << 52), exp_bits - 1075) };
    // v = mant · 2^exp; q = v · 10¹² rounded half to even.
    let q: u128 = if exp_bits == 0x7FF || exp > 10 {
        let s = format!("{v:.12}");
        let s = s.trim_end_matches('0');
        o.extend_from_slice(s.as_bytes());
        if s.ends_with('.') {
            o.push(b'0');
        }
        return;
    } else if mant == 0 {
        0
    } else if exp >= 0 {
        (u128::from(mant) << exp) * SCALE
    } else if exp <= -127 {
        // Below 2⁻⁷³: rounds to zero.
        0
    } else {
        let shift = (-exp) as u32;
        let n = u128::from(mant) * SCALE;
        let q = n >> shift;
        let r = n - (q << shift);
        let half = 1u128 << (shift - 1);
        if r > half || (r == half && q & 1 == 1) { q + 1 } else { q }
    };
    // In 64 bits when q fits (|v| below 1.8·10⁷): a 128-bit division is a library call.
    let (int, frac) = match u64::try_from(q) {
        Ok(q) => (q / SCALE as u64, q % SCALE as u64),
        Err(_) => ((q / SCALE) as u64, (q % SCALE) as u64),
    };
    // Sign, integer digits, point and up to 12 decimals made on the stack, appended at once.
    let mut buf = [0u8; 40];
    let mut n = 0;
    if negative {
        buf[0] = b'-';
        n = 1;
    }
    let mut int_digits = [0u8; 20];
    let i = digits(&mut int_digits, int);
    buf[n..n + 20 - i].copy_from_slice(&int_digits[i..]);
    n += 20 - i;
    buf[n] = b'.';
    n += 1;
    if frac == 0 {
        buf[n] = b'0';
        n += 1;
    } else {
        // Two decimals at a time, from a table.
        const PAIRS: [u8; 200] = {
            let mut t = [0u8; 200];
            let mut k = 0;
            while k < 100 {
                t[2 * k] = b'0' + (k / 10) as u8;
                t[2 * k + 1] = b'0' + (k % 10) as u8;
                k += 1;
            }
            t
        };
        let (hi, lo) = (frac / 1_000_000, frac % 1_000_000);
        for (j, pair) in
            [hi / 10_000, hi / 100 % 100, hi % 100, lo / 10_000, lo / 100 % 100, lo % 100].into_iter().enumerate()
        {
            let p = 2 * pair as usize;
            buf[n + 2 * j..n + 2 * j + 2].copy_from_slice(&PAIRS[p..p + 2]);
        }
        n += 12;
        // Trailing zeros trimmed (frac ≠ 0: a non-zero decimal stays).
        while buf[n - 1] == b'0' {
            n -= 1;
        }
    }
    o.extend_from_slice(&buf[..n]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crate_format(v: f64) -> String {
        let s = format!("{v:.12}");
        let s = s.trim_end_matches('0');
        if s.ends_with('.') { format!("{s}0") } else { s.to_string() }
    }

    fn ours(v: f64) -> String {
        let mut o = Vec::new();
        write_f64(&mut o, v);
        String::from_utf8(o).unwrap()
    }

    #[test]
    fn floats_are_formatted_as_the_standard_library_formats_them() {
        let mut special = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            2.5,
            1.0 / 8192.0,
            3.0 / 8192.0,
            -5.0 / 8192.0,
            5e-13,
            4.99e-13,
            5.000001e-13,
            1e-12,
            -1e-12,
            1.5e-12,
            2.5e-12,
            1e-300,
            -1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            123456.789,
            1e15,
            9.2e18,
            9.3e18,
            1e19,
            -1e300,
            f64::MAX,
            0.1,
            0.2,
            0.3,
            std::f64::consts::PI,
            59.036243467926,
        ];
        // Pseudo-random bit patterns over a wide range of exponents.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let exp = 1023 - 60 + (x >> 56) % 100;
            let v = f64::from_bits((x & ((1 << 52) - 1)) | (exp << 52) | (x & (1 << 63)));
            special.push(v);
            // Short decimals (many ties and near-ties at the 13th decimal).
            special.push((x % 10_000_000_000_000) as f64 / 1e13);
            special.push((x % 100_000) as f64 / 8192.0);
        }
        for v in special {
            assert_eq!(ours(v), crate_format(v), "{v:e}");
        }
    }

    #[test]
    fn escapes_as_the_crate() {
        let mut o = Vec::new();
        escaped(&mut o, "a\u{7}^\u{1E} b φ° 𝄞\u{7f}");
        assert_eq!(String::from_utf8(o).unwrap(), "a^G^ ^^ b \\U+03C6\\U+00B0 \\U+1D11E\u{7f}");
    }
}
