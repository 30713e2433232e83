//! SVG to PNG with resvg, using the font bundled in the repository (assets/fonts), so that
//! a picture renders the same on every machine (system fonts differ; resvg silently drops
//! text when it finds none). Used for `--png` diagram copies and for golden images.

use std::sync::{Arc, OnceLock};

use resvg::{tiny_skia, usvg};

pub use super::FONT;

/// Errors of the rasteriser.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    /// The SVG could not be parsed (a bug in the SVG writer: it writes only valid SVG).
    #[error("SVG could not be parsed for rasterising: {0}")]
    Parse(String),
    /// The requested size is empty or too large.
    #[error("cannot rasterise at {width}×{height} pixels")]
    Size {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// PNG encoding failed.
    #[error("PNG encoding failed: {0}")]
    Encode(String),
}

fn options() -> &'static usvg::Options<'static> {
    static OPTS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTS.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        usvg::Options { font_family: "DejaVu Sans".to_string(), fontdb: Arc::new(db), ..usvg::Options::default() }
    })
}

/// Renders `svg` to an RGBA pixmap `width_px` wide (height from the SVG's aspect ratio),
/// on white.
pub fn render(svg: &str, width_px: u32) -> Result<tiny_skia::Pixmap, RasterError> {
    let tree = usvg::Tree::from_str(svg, options()).map_err(|e| RasterError::Parse(e.to_string()))?;
    let size = tree.size();
    let scale = width_px as f32 / size.width();
    let height = (size.height() * scale).round().max(1.0) as u32;
    let mut pixmap = tiny_skia::Pixmap::new(width_px, height).ok_or(RasterError::Size { width: width_px, height })?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(&tree, tiny_skia::Transform::from_scale(scale, scale), &mut pixmap.as_mut());
    Ok(pixmap)
}

/// Renders `svg` to PNG bytes `width_px` wide.
pub fn to_png(svg: &str, width_px: u32) -> Result<Vec<u8>, RasterError> {
    render(svg, width_px)?.encode_png().map_err(|e| RasterError::Encode(e.to_string()))
}
