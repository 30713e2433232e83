//! The synthesised mechanism as a scene file, `<name>-design.toml`: a `fourbar` scene for
//! the four-bars (crank-rocker, motion and function generation), a `linkage` scene for the
//! slider-crank and the shaper, laid out as the templates are (`fourbar-chebyshev.toml`,
//! `slider-crank.toml`, `shaper.toml`), so that `mechdraw run` analyses it like any scene.
//!
//! Numbers are written with the shortest digits that read back to the same f64 (`{:?}`), so
//! the scene analysed is the design to the last bit.

use std::f64::consts::TAU;
use std::fmt::Write;

use crate::geom::{Point, Side, angle_of};
use crate::scene::Units;
use crate::solve::fourbar::Geometry;
use crate::solve::synthesis::{quick_return, slider_crank};

/// A number as TOML reads it back exactly (`-0` written as `0.0`).
pub fn num(v: f64) -> String {
    if v == 0.0 { "0.0".into() } else { format!("{v:?}") }
}

/// A point `[x, y]`.
pub fn pt(p: Point) -> String {
    format!("[{}, {}]", num(p.x), num(p.y))
}

fn units_text(u: Units) -> &'static str {
    match u {
        Units::Mm => "mm",
        Units::Si => "SI",
    }
}

fn side_text(s: Side) -> &'static str {
    match s {
        Side::Left => "left",
        Side::Right => "right",
    }
}

/// A four-bar as the `fourbar` kind writes it: its geometry (the solver's type: pivots,
/// links, coupler point, assembly mode), the crank's speed and the crank angles swept.
#[derive(Debug, Clone)]
pub struct FourbarDesign {
    /// Pivots, links, the coupler point M (l_bm, alpha) and the assembly mode.
    pub geometry: Geometry,
    /// Crank speed, rad/s.
    pub omega1: f64,
    /// Crank angles swept: from, to, step (degrees).
    pub sweep_deg: (f64, f64, f64),
}

/// The `fourbar` scene of `f`, named `name`, with `header` comment lines first.
pub fn fourbar(name: &str, units: Units, header: &[String], f: &FourbarDesign) -> String {
    let mut s = String::new();
    for h in header {
        let _ = writeln!(s, "# {h}");
    }
    let _ = writeln!(s, "kind = \"fourbar\"");
    let _ = writeln!(s, "name = \"{name}\"");
    let _ = writeln!(s, "units = \"{}\"", units_text(units));
    let g = &f.geometry;
    let _ = writeln!(s, "o1 = {}", pt(g.o1));
    let _ = writeln!(s, "c = {}", pt(g.c));
    let _ = writeln!(s, "l1 = {}          # O1A", num(g.l1));
    let _ = writeln!(s, "l_ab = {}", num(g.l_ab));
    let _ = writeln!(s, "l_bm = {}", num(g.l_bm));
    let _ = writeln!(s, "alpha_deg = {}   # angle from ray B→A to ray B→M", num(g.alpha.to_degrees()));
    let _ = writeln!(s, "l_bc = {}", num(g.l_bc));
    let _ = writeln!(s, "omega1 = {}      # rad/s, counter-clockwise positive", num(f.omega1));
    let (from, to, step) = f.sweep_deg;
    let _ = writeln!(s, "phi1_deg = {{ from = {}, to = {}, step = {} }}", num(from), num(to), num(step));
    let _ = writeln!(s, "branch = \"{}\"    # B's side of the directed line A→C", side_text(g.branch));
    let _ = writeln!(s, "outputs = [\"position\", \"velocity\", \"acceleration\"]");
    s
}

/// The time range of one turn of a crank at `omega` (rad/s): [0, T] with T the smallest
/// f64 for which |ω|·T reaches 2π (the stroke's period is found on the law).
fn one_turn(omega: f64) -> f64 {
    let w = omega.abs();
    let mut t = TAU / w;
    while w * t < TAU {
        t = f64::from_bits(t.to_bits() + 1);
    }
    t
}

/// The crank's law `ω·t` (`2*pi*t` for one turn a second).
fn law(omega: f64) -> String {
    if omega == TAU { "2*pi*t".into() } else { format!("{}*t", num(omega)) }
}

/// The `[[driver]]` and the time range of one crank turn.
fn time_and_driver(omega: f64) -> (String, String) {
    (
        format!("time = {{ from = 0.0, to = {}, steps = 360 }}", num(one_turn(omega))),
        format!("[[driver]]\njoint = \"O1\"\nlaw = \"{}\"          # rad: the crank turns at omega1\n", law(omega)),
    )
}

/// A `[[body]]`: name, points (body coordinates), placement.
fn body(s: &mut String, name: &str, points: &[(&str, Point)], at: Point, angle: f64) {
    let pts: Vec<String> = points.iter().map(|(n, p)| format!("{n} = {}", pt(*p))).collect();
    let _ = writeln!(s, "[[body]]\nname = \"{name}\"\npoints = {{ {} }}", pts.join(", "));
    let _ = writeln!(s, "at = {}\nangle_deg = {}\n", pt(at), num(angle.to_degrees()));
}

/// A revolute `[[joint]]`.
fn revolute(s: &mut String, name: &str, a: &str, b: &str) {
    let _ = writeln!(s, "[[joint]]\nname = \"{name}\"\nrevolute = [\"{a}\", \"{b}\"]\n");
}

/// The offset slider-crank as a `linkage` scene: crank O1A, rod AB, slider B on the guide
/// y = −e, driven at `omega`.
pub fn slider_crank(name: &str, units: Units, header: &[String], d: &slider_crank::Design, omega: f64) -> String {
    let mut s = String::new();
    for h in header {
        let _ = writeln!(s, "# {h}");
    }
    let (time, driver) = time_and_driver(omega);
    let _ = writeln!(s, "kind = \"linkage\"\nname = \"{name}\"\nunits = \"{}\"\n{time}\n", units_text(units));
    let (g0, _) = d.guide();
    let reach = d.a + d.b;
    let _ = writeln!(
        s,
        "[ground]\npoints = {{ O1 = [0.0, 0.0], G1 = {}, G2 = {} }}   # the guide, along +x\n",
        pt(Point::new(g0.x - d.a, g0.y)),
        pt(Point::new(g0.x + 1.25 * reach, g0.y))
    );
    // Placed at φ1 = 0: A = (a, 0), B on the guide to the right.
    let a0 = Point::new(d.a, 0.0);
    let b0 = Point::new(d.a + (d.b * d.b - d.e * d.e).sqrt(), -d.e);
    body(&mut s, "crank", &[("O1", Point::origin()), ("A", Point::new(d.a, 0.0))], Point::origin(), 0.0);
    body(&mut s, "rod", &[("A", Point::origin()), ("B", Point::new(d.b, 0.0))], a0, angle_of(b0 - a0));
    body(&mut s, "slider", &[("B", Point::origin())], b0, 0.0);
    revolute(&mut s, "O1", "ground.O1", "crank.O1");
    revolute(&mut s, "A", "crank.A", "rod.A");
    revolute(&mut s, "B", "rod.B", "slider.B");
    let _ = writeln!(
        s,
        "[[joint]]\nname = \"guide\"\nprismatic = {{ point = \"slider.B\", line = [\"ground.G1\", \"ground.G2\"] }}\n"
    );
    let _ = writeln!(s, "{driver}");
    let _ = writeln!(s, "[[measure]]\npoint = \"slider.B\"\nquantities = [\"x\", \"vx\", \"ax\"]");
    s
}

/// The shaper as a `linkage` scene laid out as `templates/shaper.toml`.
pub fn shaper(name: &str, units: Units, header: &[String], d: &quick_return::Design, omega: f64) -> String {
    let mut s = String::new();
    for h in header {
        let _ = writeln!(s, "# {h}");
    }
    let (time, driver) = time_and_driver(omega);
    let _ = writeln!(s, "kind = \"linkage\"\nname = \"{name}\"\nunits = \"{}\"\n{time}\n", units_text(units));
    let h = d.ram_height;
    let _ = writeln!(
        s,
        "[ground]\npoints = {{ O3 = [0.0, 0.0], O1 = {}, G1 = {}, G2 = {} }}\n",
        pt(d.o1),
        pt(Point::new(-0.25 * d.rocker, h)),
        pt(Point::new(0.75 * d.rocker, h))
    );
    // Placed at φ1 = 0: A = O1 + (r, 0), the rocker through A, E right of B on the guide.
    let a0 = d.o1 + crate::geom::Vector::new(d.crank, 0.0);
    let rocker_angle = angle_of(a0 - d.o3);
    let b0 = d.o3 + crate::geom::Vector::new(libm::cos(rocker_angle), libm::sin(rocker_angle)) * d.rocker;
    let e0 = Point::new(b0.x + (d.link * d.link - (h - b0.y) * (h - b0.y)).sqrt(), h);
    body(&mut s, "crank", &[("O1", Point::origin()), ("A", Point::new(d.crank, 0.0))], d.o1, 0.0);
    body(&mut s, "block", &[("A", Point::origin())], a0, rocker_angle);
    body(&mut s, "rocker", &[("O3", Point::origin()), ("B", Point::new(d.rocker, 0.0))], d.o3, rocker_angle);
    body(&mut s, "link", &[("B", Point::origin()), ("E", Point::new(d.link, 0.0))], b0, angle_of(e0 - b0));
    body(&mut s, "ram", &[("E", Point::origin())], e0, 0.0);
    revolute(&mut s, "O1", "ground.O1", "crank.O1");
    revolute(&mut s, "A", "crank.A", "block.A");
    let _ = writeln!(
        s,
        "[[joint]]\nname = \"slide\"\nprismatic = {{ point = \"block.A\", line = [\"rocker.O3\", \"rocker.B\"] }}\n"
    );
    revolute(&mut s, "O3", "ground.O3", "rocker.O3");
    revolute(&mut s, "B", "rocker.B", "link.B");
    revolute(&mut s, "E", "link.E", "ram.E");
    let _ = writeln!(
        s,
        "[[joint]]\nname = \"ram-guide\"\nprismatic = {{ point = \"ram.E\", line = [\"ground.G1\", \"ground.G2\"] }}\n"
    );
    let _ = writeln!(s, "{driver}");
    let _ = writeln!(s, "[[measure]]\npoint = \"ram.E\"\nquantities = [\"x\", \"vx\", \"ax\"]\n");
    let _ = writeln!(s, "[[measure]]\nbody = \"rocker\"\nquantities = [\"angle\", \"omega\", \"eps\"]");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_to_the_same_bits() {
        for v in [0.1, 1.0 / 3.0, 1e-7, 123456.789, -2.5e-300, TAU, 300.00000000000006] {
            let back: f64 = toml::from_str::<toml::Table>(&format!("v = {}", num(v))).unwrap()["v"].as_float().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v}");
        }
        assert_eq!(num(-0.0), "0.0");
    }

    #[test]
    fn one_turn_reaches_two_pi_on_the_law() {
        for w in [1.0, 3.0, 7.7, -2.1, TAU, 100.0 / 3.0] {
            let t = one_turn(w);
            assert!(w.abs() * t >= TAU && w.abs() * t < TAU * (1.0 + 1e-15), "{w}");
        }
        assert_eq!(one_turn(TAU), 1.0);
    }
}
