//! [`Products`] to named byte buffers: the one place that calls the DXF, SVG, PDF and PNG
//! writers and names the files. It needs no file system and no terminal: the files go
//! to a [`Sink`] (the output directory's staging, or memory for a download), and progress
//! is reported through a callback.
//!
//! File names, relative to the output directory (`<name>` is the scene's name):
//!
//! | file | from |
//! |---|---|
//! | `<name>.dxf` | the picture; a motion with one layer per position |
//! | `<name>.svg` (and `<name>.png` with `--png`) | the picture; a motion's first position |
//! | `<name>-<suffix>.dxf`, `.svg` (and `.png`) | each extra sheet, written like a still picture |
//! | `<name><suffix>.csv` | each table |
//! | `<name>.json` | the summary, pretty, with a final newline |
//! | `diagrams/<name>/<stem>.svg` (and `.png`) | each diagram |
//! | `frames/<name>/<position>.svg` (and `.png`) | a motion's frames (unless `--no-frames`) |
//! | `<name>-sheets.pdf`, `sheets/<name>/<position>.svg` (and `.png`) | the printed pages, one per position (`--sheets`) |
//!
//! A report (`mechdraw report`, [`report_files`]) is `<name>-report.pdf`,
//! `report/<name>/<NN>-<part>.svg` (and `.png`), `<name>-report.csv` and `<name>-report.json`.
//!
//! The files are built as independent jobs on every core and handed to the sink as each is
//! made: a motion's DXF, its frames in batches, the sheets with the tables and the JSON, the
//! diagrams and the printed pages; so writing (the kernel's copy) overlaps building.
//! The live page `<name>.html` is the command line's (`run::page`): it carries the module
//! this code runs in.

use std::sync::Mutex;

use crate::par::prelude::*;

use super::finite::{check_csv, check_drawing};
use super::paths::RelPath;
use super::products::{Diagram, Page, Picture, Products, Sheet};
use crate::Error;
use crate::draw::Drawing;
use crate::draw::dxf::{self, DxfOptions};
use crate::draw::svg::{self, SvgOptions};
use crate::figure::shared::animation::Animation;

/// Width of the SVG frames and pictures, pixels (their viewBox is in model units).
pub const FRAME_WIDTH_PX: u32 = 1000;

/// How the products become bytes.
#[derive(Debug, Clone, Default)]
pub struct WriteOptions {
    /// PNG copies of every SVG written: the picture, the sheets, the diagrams, the printed
    /// pages and the frames ([`super::PNG_WIDTH_PX`] wide).
    pub png: bool,
    /// Skip a motion's per-position frames.
    pub no_frames: bool,
    /// The DXF writer's options (its scale is the products' [`Products::mm_per_unit`]).
    pub dxf: DxfOptions,
}

/// One file: its path relative to the output directory (checked: [`RelPath`]) and its bytes
/// in pieces, the one after the other (a frame: the part every frame shares, then its own; a
/// motion's DXF: its head, then what each job wrote; one piece for a file made whole), so
/// that no file is copied together.
pub type File<'a> = (RelPath, Vec<&'a [u8]>);

/// A file made whole: its path and its bytes.
type Owned = (RelPath, Vec<u8>);

/// The path `dir/…/stem.ext`, every part checked ([`RelPath::join`]).
fn path(dir: &[&str], stem: &str, ext: &str) -> Result<RelPath, Error> {
    let last = format!("{stem}.{ext}");
    let mut parts = dir.to_vec();
    parts.push(&last);
    RelPath::join(&parts)
}

/// Where files go as they are made. `put` may be called from any thread, in any order;
/// [`write`](fn@write) returns the files' canonical order.
pub trait Sink: Sync {
    /// Takes a batch of files.
    fn put(&self, files: &[File<'_>]) -> Result<(), Error>;
}

/// Files kept in memory (e.g. for a download), owned.
#[derive(Debug, Default)]
pub struct Memory(Mutex<Vec<(String, Vec<u8>)>>);

impl Sink for Memory {
    fn put(&self, files: &[File<'_>]) -> Result<(), Error> {
        let mut v = self.0.lock().map_err(|_| poisoned())?;
        v.extend(files.iter().map(|(n, pieces)| (n.to_string(), pieces.concat())));
        Ok(())
    }
}

/// A writer thread panicked while holding the in-memory files.
fn poisoned() -> Error {
    Error::Export { what: "files in memory".into(), message: "a writer thread panicked".into() }
}

/// The products as named byte buffers, in the canonical order of [`write`](fn@write).
pub fn to_files(p: &Products, opts: &WriteOptions) -> Result<Vec<(String, Vec<u8>)>, Error> {
    let memory = Memory::default();
    let order = write(p, opts, &|| {}, &memory)?;
    let mut files = memory.0.into_inner().map_err(|_| poisoned())?;
    let rank: std::collections::HashMap<&str, usize> = order.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
    files.sort_by_key(|(n, _)| rank.get(n.as_str()).copied().unwrap_or(usize::MAX));
    Ok(files)
}

/// Writes every file of `p` into `sink`; `tick` is called once per frame made (for a
/// progress bar). Returns the names of the files in their canonical order: the picture
/// (DXF, SVG, PNG), the sheets (each DXF, SVG, PNG), the tables, the text files, the JSON,
/// the diagrams, the printed pages' PDF and SVGs, the frames; then each derived run's, in
/// the same order.
///
/// The files are made and handed to the sink as independent jobs (a motion's DXF, its frames
/// in batches, the sheets with the tables and the JSON, the diagrams, the printed pages), so
/// that each core builds one while the other writes another; the order they reach the sink
/// in is not the canonical one.
pub fn write(
    p: &Products,
    opts: &WriteOptions,
    tick: &(dyn Fn() + Sync),
    sink: &dyn Sink,
) -> Result<Vec<RelPath>, Error> {
    let name = &p.name;
    let wopts = &WriteOptions { dxf: DxfOptions { mm_per_unit: p.mm_per_unit, ..opts.dxf }, ..opts.clone() };
    let mut order = match &p.picture {
        Picture::Still(d) => {
            let mut files: Vec<Owned> = Vec::new();
            still_files(&mut files, name, d, wopts)?;
            let (extras, diagrams) =
                crate::par::join(|| extra_files(p, wopts), || diagram_files(&p.diagrams, name, wopts.png));
            files.extend(extras?);
            files.extend(diagrams?);
            files.extend(page_files(name, &p.pages, wopts.png)?);
            put_owned(sink, files)?
        }
        Picture::Motion(a) => motion(a, p, wopts, tick, sink)?,
    };
    // The scenes this one made, each written as its own run (its own scale to millimetres).
    for d in &p.derived {
        order.extend(write(d, opts, tick, sink)?);
    }
    Ok(order)
}

/// The sheets (each DXF, SVG, PNG), the tables, the text files and the JSON summary, in
/// this order.
fn extra_files(p: &Products, opts: &WriteOptions) -> Result<Vec<Owned>, Error> {
    let name = &p.name;
    let mut files = Vec::new();
    sheet_files(&mut files, name, &p.sheets, opts)?;
    for t in &p.tables {
        let csv = path(&[], &format!("{name}{}", t.suffix), "csv")?;
        check_csv(&t.csv, csv.as_str())?;
        files.push((csv, t.csv.to_bytes()));
    }
    for t in &p.texts {
        files.push((RelPath::join(&[&format!("{name}{}", t.suffix)])?, t.text.clone().into_bytes()));
    }
    let json_path = path(&[], name, "json")?;
    let json = serde_json::to_string_pretty(&p.summary)
        .map_err(|e| Error::Export { what: json_path.to_string(), message: e.to_string() })?;
    files.push((json_path, (json + "\n").into_bytes()));
    Ok(files)
}

/// Hands `files` to `sink` and returns their names, in order.
fn put_owned(sink: &dyn Sink, files: Vec<Owned>) -> Result<Vec<RelPath>, Error> {
    sink.put(&view(&files))?;
    Ok(files.into_iter().map(|(n, _)| n).collect())
}

/// Borrowed views of owned files, for [`Sink::put`].
fn view(v: &[Owned]) -> Vec<File<'_>> {
    v.iter().map(|(n, b)| (n.clone(), vec![b.as_slice()])).collect()
}

/// A still drawing as `<stem>.dxf`, `<stem>.svg` and (when asked for) `<stem>.png`.
fn still_files(files: &mut Vec<Owned>, stem: &str, d: &Drawing, opts: &WriteOptions) -> Result<(), Error> {
    let dxf = path(&[], stem, "dxf")?;
    check_drawing(d, dxf.as_str())?;
    files.push((dxf.clone(), dxf_bytes(d, &opts.dxf, &dxf)?));
    picture_files(files, &[], stem, picture_svg(d), opts.png)
}

/// A still drawing's SVG (`<stem>.svg`).
pub fn picture_svg(d: &Drawing) -> String {
    svg::to_string(d, &SvgOptions { width_px: FRAME_WIDTH_PX, ..SvgOptions::default() })
}

/// The SVG options of a motion's frames: one window for all (the animation's fixed window,
/// else fitted to the base and `poses`), on the base's paper.
pub fn frame_options(a: &Animation, poses: &[Drawing]) -> SvgOptions {
    SvgOptions {
        width_px: FRAME_WIDTH_PX,
        window: Some(a.window(poses)),
        // Every frame on the base's paper, so that frames share the base's header.
        paper_mm_per_unit: a.base.paper_mm_per_unit,
        ..SvgOptions::default()
    }
}

/// Each sheet as a still drawing named `<name>-<suffix>`, built in parallel.
fn sheet_files(files: &mut Vec<Owned>, name: &str, sheets: &[Sheet], opts: &WriteOptions) -> Result<(), Error> {
    let per: Vec<Vec<Owned>> = sheets
        .par_iter()
        .map(|s| {
            let mut v = Vec::with_capacity(3);
            still_files(&mut v, &format!("{name}-{}", s.suffix), &s.drawing, opts)?;
            Ok(v)
        })
        .collect::<Result<_, Error>>()?;
    files.extend(per.into_iter().flatten());
    Ok(())
}

/// The picture's SVG `dir/…/stem.svg`, and its PNG when asked for.
fn picture_files(files: &mut Vec<Owned>, dir: &[&str], stem: &str, svg: String, png: bool) -> Result<(), Error> {
    let svg_path = path(dir, stem, "svg")?;
    let png = if png {
        let png_path = path(dir, stem, "png")?;
        let bytes = png_bytes(&svg, &png_path)?;
        Some((png_path, bytes))
    } else {
        None
    };
    files.push((svg_path, svg.into_bytes()));
    files.extend(png);
    Ok(())
}

/// Each diagram's SVG (and PNG), built in parallel.
fn diagram_files(diagrams: &[Diagram], name: &str, png: bool) -> Result<Vec<Owned>, Error> {
    let per: Vec<Vec<Owned>> = diagrams
        .par_iter()
        .map(|d| {
            check_drawing(&d.drawing, path(&["diagrams", name], &d.stem, "svg")?.as_str())?;
            let s = svg::to_string(&d.drawing, &SvgOptions::default());
            let mut v = Vec::with_capacity(2);
            picture_files(&mut v, &["diagrams", name], &d.stem, s, png)?;
            Ok(v)
        })
        .collect::<Result<_, Error>>()?;
    Ok(per.into_iter().flatten().collect())
}

/// The printed pages: `<name>-sheets.pdf` with every page, then each page's SVG
/// `sheets/<name>/<stem>.svg` (true size: `width="297mm"`, viewBox in paper mm) and, when
/// asked for, its PNG `sheets/<name>/<stem>.png`; nothing without pages. The SVGs (and PNGs)
/// are built in parallel with the PDF.
fn page_files(name: &str, pages: &[Page], png: bool) -> Result<Vec<Owned>, Error> {
    let pdf_name = path(&[], &format!("{name}-sheets"), "pdf")?;
    paper_files(Some(&pdf_name), &["sheets", name], pages, png)
}

/// Pages of paper: `pdf_name` (when given) with every page, then each page's SVG
/// `<dir>/<stem>.svg` (true size, viewBox in paper mm) and, when asked for, its PNG; nothing
/// without pages. Every page is checked for numbers that are not finite first.
fn paper_files(pdf_name: Option<&RelPath>, dir: &[&str], pages: &[Page], png: bool) -> Result<Vec<Owned>, Error> {
    if pages.is_empty() {
        return Ok(Vec::new());
    }
    let doc_name = pdf_name.map_or_else(|| RelPath::join(dir).map(String::from), |n| Ok(n.to_string()))?;
    for p in pages {
        check_drawing(&p.drawing, &format!("{doc_name}, page {}", p.stem))?;
    }
    let (doc, svgs) = crate::par::join(
        || pdf_name.map(|n| pdf_bytes(pages, n.as_str()).map(|b| (n.clone(), b))).transpose(),
        || {
            pages
                .par_iter()
                .map(|p| {
                    let mut v = Vec::with_capacity(2);
                    picture_files(&mut v, dir, &p.stem, page_svg(p), png)?;
                    Ok(v)
                })
                .collect::<Result<Vec<_>, Error>>()
        },
    );
    let mut files: Vec<Owned> = doc?.into_iter().collect();
    files.extend(svgs?.into_iter().flatten());
    Ok(files)
}

/// A printed page's SVG: sized in paper mm (`width="297mm"`), its viewBox the paper.
pub fn page_svg(p: &Page) -> String {
    let extent = p.window.width().max(p.window.height()).max(f64::MIN_POSITIVE);
    let opts = SvgOptions {
        margin: 0.0,
        hairline: p.hairline_mm / extent,
        window: Some(p.window),
        paper_mm_per_unit: Some(1.0),
        ..SvgOptions::default()
    };
    svg::to_string(&p.drawing, &opts)
}

/// A report's files (`mechdraw report`), in order: `<name>-report.pdf` (every page; in a
/// build with the PDF writer, feature `pdf`: the command line's, not the live page's
/// module), each page's SVG `report/<name>/<NN>-<part>.svg` (and its PNG with `png`), the
/// chosen positions' table `<name>-report.csv` (motion kinds) and `<name>-report.json` (the
/// parts and their pages, the structure, the positions).
pub fn report_files(r: &super::report::Report, png: bool) -> Result<Vec<(String, Vec<u8>)>, Error> {
    let name = &r.name;
    let pdf = path(&[], &format!("{name}-report"), "pdf")?;
    let pdf = cfg!(feature = "pdf").then_some(&pdf);
    let mut files = paper_files(pdf, &["report", name], &r.pages, png)?;
    if let Some(t) = &r.table {
        let csv = path(&[], &format!("{name}-report"), "csv")?;
        check_csv(t, csv.as_str())?;
        files.push((csv, t.to_bytes()));
    }
    let json_path = path(&[], &format!("{name}-report"), "json")?;
    let json = serde_json::to_string_pretty(&r.summary)
        .map_err(|e| Error::Export { what: json_path.to_string(), message: e.to_string() })?;
    files.push((json_path, (json + "\n").into_bytes()));
    Ok(files.into_iter().map(|(n, b)| (n.into(), b)).collect())
}

#[cfg(feature = "png")]
fn png_bytes(svg: &str, what: &RelPath) -> Result<Vec<u8>, Error> {
    crate::draw::raster::to_png(svg, super::PNG_WIDTH_PX)
        .map_err(|e| Error::Export { what: what.to_string(), message: e.to_string() })
}

/// Without the PNG writer (the live page's module), a PNG asked for is refused by name.
#[cfg(not(feature = "png"))]
fn png_bytes(_svg: &str, what: &RelPath) -> Result<Vec<u8>, Error> {
    Err(Error::Export { what: what.to_string(), message: NOT_IN_THIS_BUILD.replace("{}", "PNG").replace("{f}", "png") })
}

/// The PDF of the printed pages.
#[cfg(feature = "pdf")]
fn pdf_bytes(pages: &[Page], what: &str) -> Result<Vec<u8>, Error> {
    let v: Vec<crate::draw::pdf::Page<'_>> = pages
        .iter()
        .map(|p| crate::draw::pdf::Page { drawing: &p.drawing, window: p.window, hairline_mm: p.hairline_mm })
        .collect();
    crate::draw::pdf::to_bytes(&v).map_err(|e| Error::Export { what: what.to_string(), message: e.to_string() })
}

/// Without the PDF writer (the live page's module), the printed pages' PDF is refused by name.
#[cfg(not(feature = "pdf"))]
fn pdf_bytes(_pages: &[Page], what: &str) -> Result<Vec<u8>, Error> {
    Err(Error::Export { what: what.to_string(), message: NOT_IN_THIS_BUILD.replace("{}", "PDF").replace("{f}", "pdf") })
}

/// What a build without a writer says when its output is asked for.
#[cfg(not(all(feature = "png", feature = "pdf")))]
const NOT_IN_THIS_BUILD: &str = "this build has no {} writer (the live page leaves it to the command line: `mechdraw run` has it; a library build needs the Cargo feature `{f}`)";

fn dxf_bytes(d: &Drawing, opts: &DxfOptions, what: &RelPath) -> Result<Vec<u8>, Error> {
    dxf::to_bytes(d, opts).map_err(|e| Error::Export { what: what.to_string(), message: e.to_string() })
}

/// One SVG frame of a motion: `head` (the part every frame shares, written once; empty for a
/// frame written whole) followed by `svg[from..]`.
struct Frame<'a> {
    head: &'a str,
    svg: String,
    from: usize,
}

impl Frame<'_> {
    /// The frame's two pieces, as a [`File`] holds them.
    fn pieces(&self) -> Vec<&[u8]> {
        vec![self.head.as_bytes(), &self.svg.as_bytes()[self.from..]]
    }

    /// The whole frame in one string (for the picture and a PNG).
    fn whole(&self) -> String {
        let tail = &self.svg[self.from..];
        let mut s = String::with_capacity(self.head.len() + tail.len());
        s.push_str(self.head);
        s.push_str(tail);
        s
    }
}

/// Frames made and handed to the sink together (each batch is one job: its frames built,
/// then written while other jobs are built).
const FRAMES_PER_BATCH: usize = 12;

/// A motion's files: each position drawn once (in parallel), for the window, the DXF layer
/// and the frame; then the DXF, the frames (in batches), the sheets with the tables and the
/// JSON, the diagrams and the printed pages built and handed to the sink as separate jobs.
fn motion(
    a: &Animation,
    p: &Products,
    opts: &WriteOptions,
    tick: &(dyn Fn() + Sync),
    sink: &dyn Sink,
) -> Result<Vec<RelPath>, Error> {
    let name = &p.name;
    let poses = a.poses();
    let dxf_name = path(&[], name, "dxf")?;
    check_drawing(&a.base, dxf_name.as_str())?;
    poses.par_iter().enumerate().try_for_each(|(k, pose)| {
        let position = a.names.get(k).map_or_else(|| k.to_string(), |n| n.to_lowercase());
        check_drawing(pose, &format!("{dxf_name} and frames/{name}/{position}.svg"))
    })?;
    let svg_opts = frame_options(a, &poses);
    // The DXF's pieces first, on every core (its jobs are the largest part of the run; the
    // sheets, the tables and the JSON meanwhile), then the file written on one core while
    // the frames, the diagrams and the printed pages are made on the other.
    let (pieces, extras) = crate::par::join(
        || {
            dxf::to_pieces(&a.all_positions(&poses), &opts.dxf)
                .map_err(|e| Error::Export { what: dxf_name.to_string(), message: e.to_string() })
        },
        || extra_files(p, opts).and_then(|f| put_owned(sink, f)),
    );
    let dxf_file = (dxf_name.clone(), pieces?);
    let (dxf, (frames, (diagrams, pages))) = crate::par::join(
        || {
            // The entities, most of the file, are not copied to join them (and are freed here).
            let (name, pieces) = dxf_file;
            sink.put(&[(name, pieces.iter().map(Vec::as_slice).collect())])
        },
        || {
            crate::par::join(
                || frame_files(a, &poses, &svg_opts, opts, tick, sink, name),
                || {
                    crate::par::join(
                        || diagram_files(&p.diagrams, name, opts.png).and_then(|f| put_owned(sink, f)),
                        || page_files(name, &p.pages, opts.png).and_then(|f| put_owned(sink, f)),
                    )
                },
            )
        },
    );
    dxf?;
    let (picture, frame_names) = frames?;
    let mut files = Vec::with_capacity(2);
    picture_files(&mut files, &[], name, picture, opts.png)?;
    let mut order = vec![dxf_name];
    order.extend(put_owned(sink, files)?);
    order.extend(extras?);
    order.extend(diagrams?);
    order.extend(pages?);
    order.extend(frame_names);
    // The positions' drawings (many small allocations) freed on every core.
    poses.into_par_iter().for_each(drop);
    Ok(order)
}

/// The frames (unless `--no-frames`; with `--png` each frame's PNG follows its SVG), handed to
/// the sink in batches built in parallel: the base written once (by [`svg::to_string`] with
/// `svg_opts`), each position's part after it (see [`svg::splice_parts`]). Returns the picture
/// (the first frame whole; without frames the first position, or the base alone) and the
/// frames' file names in order.
fn frame_files(
    a: &Animation,
    poses: &[Drawing],
    svg_opts: &SvgOptions,
    opts: &WriteOptions,
    tick: &(dyn Fn() + Sync),
    sink: &dyn Sink,
    name: &str,
) -> Result<(String, Vec<RelPath>), Error> {
    if opts.no_frames || poses.is_empty() {
        let picture = match poses.first() {
            Some(first) => svg::to_string(&a.frame_of(first), svg_opts),
            None => svg::to_string(&a.base, svg_opts),
        };
        return Ok((picture, Vec::new()));
    }
    // Each frame's SVG path, and its PNG's with --png.
    let stems: Vec<(RelPath, Option<RelPath>)> = a
        .names
        .iter()
        .take(poses.len())
        .map(|n| {
            let stem = n.to_lowercase();
            let png = if opts.png { Some(path(&["frames", name], &stem, "png")?) } else { None };
            Ok((path(&["frames", name], &stem, "svg")?, png))
        })
        .collect::<Result<_, Error>>()?;
    let base_svg = svg::to_string(&a.base, svg_opts);
    let firsts: Vec<Option<String>> = poses
        .par_chunks(FRAMES_PER_BATCH)
        .zip(stems.par_chunks(FRAMES_PER_BATCH))
        .enumerate()
        .map(|(batch, (poses, stems))| -> Result<Option<String>, Error> {
            let frames: Vec<Frame<'_>> = poses
                .iter()
                .map(|pose| {
                    let f = frame(a, pose, &base_svg, svg_opts);
                    tick();
                    f
                })
                .collect();
            let pngs: Vec<(&RelPath, Vec<u8>)> = stems
                .iter()
                .zip(&frames)
                .filter_map(|((_, png), f)| png.as_ref().map(|png| Ok((png, png_bytes(&f.whole(), png)?))))
                .collect::<Result<_, Error>>()?;
            let mut files: Vec<File<'_>> = Vec::with_capacity(frames.len() + pngs.len());
            for (i, ((svg, _), f)) in stems.iter().zip(&frames).enumerate() {
                files.push((svg.clone(), f.pieces()));
                if let Some((png, bytes)) = pngs.get(i) {
                    files.push(((*png).clone(), vec![bytes.as_slice()]));
                }
            }
            sink.put(&files)?;
            Ok(if batch == 0 { frames.first().map(Frame::whole) } else { None })
        })
        .collect::<Result<_, Error>>()?;
    let picture = firsts.into_iter().flatten().next().unwrap_or_else(|| svg::to_string(&a.base, svg_opts));
    let names = stems.into_iter().flat_map(|(svg, png)| std::iter::once(svg).chain(png)).collect();
    Ok((picture, names))
}

/// One SVG frame: `pose` on the base (`base_svg`, written with `svg_opts`).
fn frame<'a>(a: &Animation, pose: &Drawing, base_svg: &'a str, svg_opts: &SvgOptions) -> Frame<'a> {
    let moving = svg::to_string(pose, svg_opts);
    match svg::splice_parts(base_svg, &moving) {
        Some((head, tail)) => Frame { head, from: moving.len() - tail.len(), svg: moving },
        None => Frame { head: "", svg: svg::to_string(&a.frame_of(pose), svg_opts), from: 0 },
    }
}
