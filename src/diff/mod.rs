//! `mechdraw diff OLD_DIR NEW_DIR`: two runs' output directories compared as an engineer
//! reads them, for a course's or a team's golden files in CI (docs/ci.md).
//!
//! Files only in one directory are added or removed. A file in both is the same when its
//! bytes are; otherwise it is compared by what it holds, one module per format:
//!
//! | files | compared | module |
//! |---|---|---|
//! | `.csv` | cell by cell; numbers within a relative tolerance of their column's scale | `table` |
//! | `.json` | leaf by leaf; numbers as for a CSV, a key path (indices dropped) as the column | `json` |
//! | `.svg`, `.png` | rasterised (resvg, the bundled font, as the golden tests) and compared pixel by pixel with a channel tolerance; a red/white diff PNG for each changed picture | `picture` |
//! | `.dxf` | entity by entity: counts per type and layer, the largest coordinate difference, texts | `dxf` |
//! | `.pdf` | the page count and each page's text | `pdf` |
//! | anything else (`.html`) | bytes | |
//!
//! The verdict: [`Report::passed`] when nothing was added or removed and every changed file
//! is within the tolerances; the command line exits 0 then, 1 otherwise, and 2 on bad input
//! ([`DiffError`]).

mod dxf;
mod json;
mod pdf;
mod picture;
mod summary;
mod table;

use std::path::{Path, PathBuf};

use rayon::prelude::*;

/// Default relative tolerance of numbers (`--tol-rel`): a number differs when it moved by
/// more than this fraction of its column's scale (the largest magnitude in that CSV column,
/// JSON key path or DXF drawing). 1e-9 passes a last-digit difference and flags any change a
/// person could see in a table.
pub const DEFAULT_TOL_REL: f64 = 1e-9;

/// Default channel tolerance of pictures (`--tol-px`): a pixel differs when a channel (red,
/// green, blue, alpha; 0–255) moved by more than this. 1 is the golden tests' tolerance.
pub const DEFAULT_TOL_PX: u8 = 1;

/// Width at which SVG pictures are rasterised for the comparison, pixels (the golden tests').
pub const RASTER_WIDTH_PX: u32 = 800;

/// What `mechdraw diff` is asked.
#[derive(Debug, Clone)]
pub struct DiffOptions {
    /// Relative tolerance of numbers ([`DEFAULT_TOL_REL`]).
    pub tol_rel: f64,
    /// Channel tolerance of pixels ([`DEFAULT_TOL_PX`]).
    pub tol_px: u8,
    /// Where the diff PNGs of changed pictures go (`DIR/<path of the picture>.diff.png`);
    /// nothing is written when no picture changed.
    pub out: PathBuf,
}

/// Why two directories could not be compared: bad input (exit code 2).
#[derive(Debug, thiserror::Error)]
pub enum DiffError {
    /// A directory to compare does not exist or is not a directory. Example: a misspelt
    /// `out-golden/`.
    #[error("{path}: no such directory (mechdraw diff compares two output directories: OLD_DIR NEW_DIR)")]
    NoDir {
        /// The path as given.
        path: String,
    },
    /// A file or directory could not be read. Example: a file without read permission.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file or directory.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file could not be understood as its extension says. Example: a `.json` cut short.
    #[error("{path}: cannot read it as {format}: {message}")]
    Format {
        /// The file.
        path: String,
        /// What it should be (`CSV`, `JSON`, `SVG`, ...).
        format: &'static str,
        /// What is wrong.
        message: String,
    },
    /// A diff picture could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file or directory.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// How a file present in both directories compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    /// Byte for byte.
    Same,
    /// Its bytes differ, but every number and pixel is within the tolerances.
    Within,
    /// It differs beyond the tolerances.
    Changed,
}

/// One file present in both directories.
#[derive(Debug, Clone)]
pub struct FileDiff {
    /// Path relative to the directories, `/`-separated.
    pub path: String,
    /// How it compares.
    pub verdict: Verdict,
    /// What differs, one line each, for the summary (empty when the bytes are the same).
    pub details: Vec<String>,
    /// For pictures: how many pixels differ beyond the tolerance (the summary's measure of
    /// how much a picture moved).
    pub pixels: usize,
    /// The diff PNG written for a changed picture.
    pub diff_png: Option<PathBuf>,
}

impl FileDiff {
    fn new(path: &str, verdict: Verdict, details: Vec<String>) -> FileDiff {
        FileDiff { path: path.to_string(), verdict, details, pixels: 0, diff_png: None }
    }
}

/// The comparison of two directories.
#[derive(Debug, Clone)]
pub struct Report {
    /// The directories as given.
    pub old: PathBuf,
    /// The directories as given.
    pub new: PathBuf,
    /// The tolerances used.
    pub tol_rel: f64,
    /// The tolerances used.
    pub tol_px: u8,
    /// Files only in the new directory.
    pub added: Vec<String>,
    /// Files only in the old directory.
    pub removed: Vec<String>,
    /// Files in both, sorted by path.
    pub files: Vec<FileDiff>,
}

impl Report {
    /// Whether the new run is the old one within the tolerances: nothing added or removed,
    /// no file changed beyond them.
    pub fn passed(&self) -> bool {
        self.added.is_empty() && self.removed.is_empty() && self.files.iter().all(|f| f.verdict != Verdict::Changed)
    }

    /// The report as a CI log shows it: counts, then what changed grouped by folder, then
    /// the verdict.
    pub fn summary(&self) -> String {
        summary::text(self)
    }
}

/// Compares the output directories `old` and `new`.
pub fn compare(old: &Path, new: &Path, opts: &DiffOptions) -> Result<Report, DiffError> {
    let old_files = list(old)?;
    let new_files = list(new)?;
    let added: Vec<String> = new_files.iter().filter(|f| old_files.binary_search(f).is_err()).cloned().collect();
    let removed: Vec<String> = old_files.iter().filter(|f| new_files.binary_search(f).is_err()).cloned().collect();
    let common: Vec<&String> = old_files.iter().filter(|f| new_files.binary_search(f).is_ok()).collect();
    let files =
        common.par_iter().map(|rel| compare_file(old, new, rel, opts)).collect::<Result<Vec<FileDiff>, DiffError>>()?;
    Ok(Report {
        old: old.to_path_buf(),
        new: new.to_path_buf(),
        tol_rel: opts.tol_rel,
        tol_px: opts.tol_px,
        added,
        removed,
        files,
    })
}

/// Every file under `dir`, `/`-separated paths relative to it, sorted.
fn list(dir: &Path) -> Result<Vec<String>, DiffError> {
    if !dir.is_dir() {
        return Err(DiffError::NoDir { path: dir.display().to_string() });
    }
    let mut out = Vec::new();
    walk(dir, "", &mut out)?;
    out.sort();
    Ok(out)
}

fn walk(dir: &Path, prefix: &str, out: &mut Vec<String>) -> Result<(), DiffError> {
    let read = |source| DiffError::Read { path: dir.display().to_string(), source };
    for entry in std::fs::read_dir(dir).map_err(read)? {
        let entry = entry.map_err(read)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let rel = if prefix.is_empty() { name } else { format!("{prefix}/{name}") };
        let path = entry.path();
        if path.is_dir() {
            walk(&path, &rel, out)?;
        } else {
            out.push(rel);
        }
    }
    Ok(())
}

fn read(path: &Path) -> Result<Vec<u8>, DiffError> {
    std::fs::read(path).map_err(|source| DiffError::Read { path: path.display().to_string(), source })
}

/// The text of a file whose format is text (CSV, JSON, SVG, DXF).
fn text<'a>(path: &Path, bytes: &'a [u8], format: &'static str) -> Result<&'a str, DiffError> {
    std::str::from_utf8(bytes).map_err(|e| DiffError::Format {
        path: path.display().to_string(),
        format,
        message: format!("not UTF-8 text ({e})"),
    })
}

/// Compares `rel` in both directories.
fn compare_file(old: &Path, new: &Path, rel: &str, opts: &DiffOptions) -> Result<FileDiff, DiffError> {
    let (po, pn) = (old.join(rel), new.join(rel));
    let (a, b) = (read(&po)?, read(&pn)?);
    if a == b {
        return Ok(FileDiff::new(rel, Verdict::Same, Vec::new()));
    }
    let ext = rel.rsplit_once('.').map_or("", |(_, e)| e).to_ascii_lowercase();
    let pair = Pair { rel, old: &po, new: &pn, tol_rel: opts.tol_rel };
    match ext.as_str() {
        "csv" => table::compare(&pair, text(&po, &a, "CSV")?, text(&pn, &b, "CSV")?),
        "json" => json::compare(&pair, text(&po, &a, "JSON")?, text(&pn, &b, "JSON")?),
        "dxf" => dxf::compare(&pair, &a, &b),
        "pdf" => pdf::compare(&pair, &a, &b),
        "svg" => picture::compare_svg(&pair, text(&po, &a, "SVG")?, text(&pn, &b, "SVG")?, opts),
        "png" => picture::compare_png(&pair, &a, &b, opts),
        _ => Ok(FileDiff::new(rel, Verdict::Changed, vec![format!("bytes differ ({} → {} bytes)", a.len(), b.len())])),
    }
}

/// The file being compared, for the per-format modules.
struct Pair<'a> {
    rel: &'a str,
    old: &'a Path,
    new: &'a Path,
    tol_rel: f64,
}

impl Pair<'_> {
    fn format_error(&self, which: &Path, format: &'static str, message: impl Into<String>) -> DiffError {
        DiffError::Format { path: which.display().to_string(), format, message: message.into() }
    }
}

/// The largest difference among numbers that belong together (a CSV column, a JSON key
/// path, a DXF's coordinates), and where it is.
#[derive(Debug, Clone, Default)]
struct Spread {
    /// The scale differences are measured against: the largest magnitude seen.
    scale: f64,
    /// The largest |new − old|, and where.
    largest: f64,
    at: String,
    /// `(|new − old|, where)` of every pair, to count those beyond the tolerance once the
    /// scale is known.
    deltas: Vec<(f64, String)>,
}

impl Spread {
    fn add(&mut self, a: f64, b: f64, at: impl FnOnce() -> String) {
        self.scale = self.scale.max(a.abs()).max(b.abs());
        let d = (b - a).abs();
        if d > 0.0 || a.is_nan() != b.is_nan() {
            let at = at();
            let d = if d.is_nan() { f64::INFINITY } else { d };
            if d > self.largest {
                self.largest = d;
                self.at = at.clone();
            }
            self.deltas.push((d, at));
        }
    }

    /// The tolerance: `tol_rel` of the scale.
    fn tolerance(&self, tol_rel: f64) -> f64 {
        tol_rel * self.scale
    }

    /// How many pairs moved beyond the tolerance, and where the first one is.
    fn beyond(&self, tol_rel: f64) -> (usize, Option<&str>) {
        let tol = self.tolerance(tol_rel);
        let mut over = self.deltas.iter().filter(|(d, _)| *d > tol);
        let first = over.next().map(|(_, at)| at.as_str());
        (first.map_or(0, |_| 1 + over.count()), first)
    }

    /// `|Δ| 2.1e-4 (1.9e-3 of its scale 0.11) at …`.
    fn describe(&self) -> String {
        let rel = if self.scale > 0.0 { self.largest / self.scale } else { f64::INFINITY };
        format!(
            "largest |Δ| {} ({} of its scale {}) at {}",
            short(self.largest),
            short(rel),
            short(self.scale),
            self.at
        )
    }
}

/// A number in 3 significant digits for the summary.
fn short(x: f64) -> String {
    if x == 0.0 || (1e-3..1e5).contains(&x.abs()) {
        let s = format!("{x:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-" { "0".to_string() } else { s.to_string() }
    } else {
        format!("{x:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spread_counts_what_moved_beyond_its_scale() {
        let mut s = Spread::default();
        s.add(100.0, 100.0, || "row 1".into());
        s.add(10.0, 10.5, || "row 2".into());
        s.add(1.0, 1.0 + 1e-12, || "row 3".into());
        assert_eq!(s.scale, 100.0);
        assert_eq!(s.largest, 0.5);
        assert_eq!(s.at, "row 2");
        // 1e-12 is within 1e-9 of the column's scale (100), 0.5 is not.
        assert_eq!(s.beyond(1e-9), (1, Some("row 2")));
        assert_eq!(s.beyond(1e-15), (2, Some("row 2")));
        assert_eq!(s.beyond(1e-2), (0, None), "0.5 is 0.5 % of 100");
        assert_eq!(s.beyond(1e-3).0, 1);
    }

    #[test]
    fn numbers_are_short_in_the_summary() {
        assert_eq!(short(0.0), "0");
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(2.0), "2");
        assert_eq!(short(123.456789), "123.4568");
        assert_eq!(short(2.1e-4), "2.10e-4");
        assert_eq!(short(f64::INFINITY), "inf");
    }
}
