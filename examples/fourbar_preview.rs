//! Preview frames of the four-bar figure to look at while developing the drawing
//! vocabulary: the Chebyshev template (templates/fourbar-chebyshev.toml) solved through the
//! public API, drawn at φ1 = 0°, 90° and 180° with its velocity and acceleration polygons,
//! and rendered to PNG: `target/fourbar-preview-{0,90,180}.png`; with `--forces`, the force
//! polygons and the reactions on the mechanism too: `target/forces-preview-{0,90,180}.png`.
//!
//! Run with `cargo run --release --example fourbar_preview [-- --forces]`.

use mechdraw::draw::{raster, svg};
use mechdraw::figure::fourbar::{Layout, ModelUnits, Show};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::solve_motion;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let forces = std::env::args().skip(1).any(|a| a == "--forces");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let Scene::Fourbar(s) = scene::load(&root.join("templates/fourbar-chebyshev.toml"), &[])?.scene else {
        return Err("not a four-bar scene".into());
    };
    let motion = solve_motion(&s.spec)?;
    let geom = &s.spec.geometry;
    let show = Show { velocity: true, acceleration: true, forces: forces && !motion.forces.is_empty() };
    let force_of = |i: usize| motion.forces.get(i).filter(|_| show.forces);
    let layout =
        Layout::new(geom, &motion.positions, show.forces.then_some(motion.forces.as_slice()), show, ModelUnits::SI);
    let base = layout.base(geom, &[motion.positions.iter().map(|p| p.m).collect()]);
    let opts = svg::SvgOptions { window: Some(layout.window), ..Default::default() };
    let (stem, width) = if show.forces { ("forces-preview", 1400) } else { ("fourbar-preview", 1200) };
    let dir = root.join("target");
    std::fs::create_dir_all(&dir)?;
    for deg in [0usize, 90, 180] {
        // The template turns the crank in 1° steps from 0°: position i is at i degrees.
        let Some(pos) = motion.positions.get(deg) else { continue };
        let frame = layout.frame(&base, &layout.moving(geom, pos, force_of(deg)));
        let png = raster::to_png(&svg::to_string(&frame, &opts), width)?;
        let file = dir.join(format!("{stem}-{deg}.png"));
        std::fs::write(&file, png)?;
        println!("{}", file.display());
    }
    Ok(())
}
