//! Pictures compared as a person sees them: an SVG rasterised with resvg and the bundled
//! font at [`RASTER_WIDTH_PX`](super::RASTER_WIDTH_PX) (as the golden tests do), a PNG
//! decoded; a pixel differs when a channel moved by more than the tolerance. A changed
//! picture gets a diff PNG: red where the pixels differ, white elsewhere, with the new
//! picture's ink in light grey so that the red can be placed.

use std::path::PathBuf;

use resvg::tiny_skia::{Pixmap, PremultipliedColorU8};

use super::{DiffError, DiffOptions, FileDiff, Pair, Verdict};
use crate::draw::raster;

pub(super) fn compare_svg(pair: &Pair<'_>, old: &str, new: &str, opts: &DiffOptions) -> Result<FileDiff, DiffError> {
    let render = |which: &std::path::Path, svg: &str| {
        raster::render(svg, super::RASTER_WIDTH_PX).map_err(|e| pair.format_error(which, "SVG", e.to_string()))
    };
    compare(pair, &render(pair.old, old)?, &render(pair.new, new)?, opts)
}

pub(super) fn compare_png(pair: &Pair<'_>, old: &[u8], new: &[u8], opts: &DiffOptions) -> Result<FileDiff, DiffError> {
    let decode = |which: &std::path::Path, png: &[u8]| {
        Pixmap::decode_png(png).map_err(|e| pair.format_error(which, "PNG", e.to_string()))
    };
    compare(pair, &decode(pair.old, old)?, &decode(pair.new, new)?, opts)
}

fn compare(pair: &Pair<'_>, a: &Pixmap, b: &Pixmap, opts: &DiffOptions) -> Result<FileDiff, DiffError> {
    if (a.width(), a.height()) != (b.width(), b.height()) {
        let detail = format!("size {}×{} → {}×{} px", a.width(), a.height(), b.width(), b.height());
        return Ok(FileDiff::new(pair.rel, Verdict::Changed, vec![detail]));
    }
    let (differing, diff) = differ(a, b, opts.tol_px);
    let total = a.pixels().len();
    if differing == 0 {
        let detail = format!("every pixel within {} per channel (bytes differ)", opts.tol_px);
        return Ok(FileDiff::new(pair.rel, Verdict::Within, vec![detail]));
    }
    let png = write_diff(&opts.out, pair.rel, &diff)?;
    let detail = format!(
        "{differing} of {total} pixels ({:.3} %) differ by more than {} in a channel; diff: {}",
        100.0 * differing as f64 / total as f64,
        opts.tol_px,
        png.display()
    );
    let mut d = FileDiff::new(pair.rel, Verdict::Changed, vec![detail]);
    d.pixels = differing;
    d.diff_png = Some(png);
    Ok(d)
}

/// How many pixels differ beyond `tol`, and the diff picture.
fn differ(a: &Pixmap, b: &Pixmap, tol: u8) -> (usize, Pixmap) {
    let mut diff = Pixmap::new(a.width(), a.height()).unwrap_or_else(|| a.clone());
    let red = PremultipliedColorU8::from_rgba(255, 0, 0, 255).unwrap_or(PremultipliedColorU8::TRANSPARENT);
    let mut differing = 0;
    for ((pa, pb), d) in a.pixels().iter().zip(b.pixels()).zip(diff.pixels_mut()) {
        let (ca, cb) = (pa.demultiply(), pb.demultiply());
        let moved = ca.red().abs_diff(cb.red()) > tol
            || ca.green().abs_diff(cb.green()) > tol
            || ca.blue().abs_diff(cb.blue()) > tol
            || ca.alpha().abs_diff(cb.alpha()) > tol;
        *d = if moved {
            differing += 1;
            red
        } else {
            // The new picture's ink, light: 255 on white, 215 where it is black.
            let ink = 255 - (255 - u16::from(cb.red().min(cb.green()).min(cb.blue()))) * 40 / 255;
            let g = ink as u8;
            PremultipliedColorU8::from_rgba(g, g, g, 255).unwrap_or(red)
        };
    }
    (differing, diff)
}

/// Writes `diff` as `out/<rel>.diff.png`.
fn write_diff(out: &std::path::Path, rel: &str, diff: &Pixmap) -> Result<PathBuf, DiffError> {
    let path = out.join(format!("{rel}.diff.png"));
    let err = |p: &std::path::Path, source| DiffError::Write { path: p.display().to_string(), source };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| err(dir, e))?;
    }
    let bytes = diff.encode_png().map_err(|e| err(&path, std::io::Error::other(e.to_string())))?;
    std::fs::write(&path, bytes).map_err(|e| err(&path, e))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn svg(x: f64) -> String {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 100 50"><line x1="10" y1="25" x2="{x}" y2="25" stroke="black" stroke-width="1"/></svg>"#
        )
    }

    #[test]
    fn a_moved_line_is_red_in_the_diff_and_the_same_line_is_within() {
        let tmp = tempfile::tempdir().unwrap();
        let opts = DiffOptions { tol_rel: 1e-9, tol_px: 1, out: tmp.path().to_path_buf() };
        let p = std::path::Path::new("a/x.svg");
        let pair = Pair { rel: "a/x.svg", old: p, new: p, tol_rel: 1e-9 };
        // The same picture written differently (bytes differ, pixels do not).
        let same = compare_svg(&pair, &svg(90.0), &svg(90.0).replace("/>", " />"), &opts).unwrap();
        assert_eq!(same.verdict, Verdict::Within);
        let d = compare_svg(&pair, &svg(90.0), &svg(60.0), &opts).unwrap();
        assert_eq!(d.verdict, Verdict::Changed);
        // 30 of 100 mm of a 1 mm line at 8 px/mm: about 240 × 8 pixels.
        assert!((1500..2500).contains(&d.pixels), "{} pixels", d.pixels);
        let png = d.diff_png.unwrap();
        assert_eq!(png, tmp.path().join("a/x.svg.diff.png"));
        let img = Pixmap::load_png(&png).unwrap();
        let at = |x: u32, y: u32| img.pixel(x, y).unwrap();
        assert_eq!((at(600, 200).red(), at(600, 200).green()), (255, 0), "red where only the old line was");
        assert_eq!(at(5, 5).red(), 255, "white away from the lines");
        assert!(at(300, 200).red() < 255 && at(300, 200).green() == at(300, 200).red(), "grey where both lines are");
    }
}
