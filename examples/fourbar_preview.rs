//! Preview frames of the four-bar figure to look at while developing the drawing
//! vocabulary: the Chebyshev template (templates/fourbar-chebyshev.toml) solved through the
//! public API, drawn at φ1 = 0°, 90° and 180° with its velocity and acceleration polygons,
//! and rendered to PNG: `target/fourbar-preview-<deg>.png`; with `--forces`, the force
//! polygons and the reactions on the mechanism too: `target/forces-preview-<deg>.png`.
//!
//! Run with `cargo run --release --example fourbar_preview [-- --forces] [--deg 0,90,132]`
//! (`--deg`: the crank angles to draw, whole degrees; 0°, 90° and 180° by default).

use mechdraw::draw::{raster, svg};
use mechdraw::figure::fourbar::{Layout, ModelUnits, Show};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::solve_motion;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let forces = args.iter().any(|a| a == "--forces");
    // Crank angles in degrees (`--deg 0,90,132`); 0°, 90° and 180° by default.
    let degs: Vec<usize> = match args.iter().position(|a| a == "--deg").and_then(|i| args.get(i + 1)) {
        Some(list) => list.split(',').map(|d| d.trim().parse()).collect::<Result<_, _>>()?,
        None => vec![0, 90, 180],
    };
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let Scene::Fourbar(s) = scene::load(&root.join("templates/fourbar-chebyshev.toml"), &[])?.scene else {
        return Err("not a four-bar scene".into());
    };
    let motion = solve_motion(&s.spec)?;
    let geom = &s.spec.geometry;
    let show =
        Show { velocity: true, acceleration: true, forces: forces && !motion.forces.is_empty(), ..Show::default() };
    let force_of = |i: usize| motion.forces.get(i).filter(|_| show.forces);
    let external = s.spec.dynamics.as_ref().map_or(&[][..], |d| d.forces.as_slice());
    let layout =
        Layout::new(geom, &motion.positions, show.forces.then_some(motion.forces.as_slice()), show, ModelUnits::SI)
            .with_drive(s.spec.omega1, external);
    let base = layout.base(geom, &[motion.positions.iter().map(|p| p.m).collect()]);
    let opts = svg::SvgOptions { window: Some(layout.frame.window), ..Default::default() };
    let (stem, width) = if show.forces { ("forces-preview", 1400) } else { ("fourbar-preview", 1200) };
    let dir = root.join("target");
    std::fs::create_dir_all(&dir)?;
    for deg in degs {
        // The template turns the crank in 1° steps from 0°: position i is at i degrees.
        let Some(pos) = motion.positions.get(deg) else { continue };
        let frame = layout.frame(&base, &layout.moving(deg, geom, pos, force_of(deg)));
        let png = raster::to_png(&svg::to_string(&frame, &opts), width)?;
        let file = dir.join(format!("{stem}-{deg}.png"));
        std::fs::write(&file, png)?;
        println!("{}", file.display());
    }
    Ok(())
}
