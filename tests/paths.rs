//! Traced paths at paper resolution (issue 16 §3): the coupler curve of the four-bar (at
//! 3600 positions) and the path of M of the four-bar written as a linkage, as the frames,
//! the viewer and the DXF draw them, deviate from the polyline through every computed
//! position by at most `PATH_TOLERANCE_MM` on paper. The positions are read from the run's
//! own CSV table (the solver's numbers), the drawn path from the motion's shared base.

mod common;

use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::shared::vocab::{PATH_TOLERANCE_MM, distance_to_segment};
use mechdraw::geom::Point;
use mechdraw::run::products::{Picture, Products};
use mechdraw::scene::{self, Override};

fn products(template: &str, sets: &[&str]) -> Products {
    let path = common::root().join("templates").join(template);
    let overrides: Vec<Override> = sets.iter().map(|s| s.parse::<Override>().unwrap()).collect();
    let loaded = scene::load(&path, &overrides).unwrap();
    mechdraw::run::products(&loaded, &Default::default()).unwrap()
}

/// The points of columns `x` and `y` of the run's main CSV table.
fn positions(p: &Products, x: &str, y: &str) -> Vec<Point> {
    let table = p.tables.iter().find(|t| t.suffix.is_empty()).expect("main table");
    let text = String::from_utf8(table.csv.to_bytes()).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (ix, iy) = (col(x), col(y));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            Point::new(f[ix].parse().unwrap(), f[iy].parse().unwrap())
        })
        .collect()
}

/// The open polylines on layer `layer` of the drawing.
fn polylines(d: &Drawing, layer: &str) -> Vec<Vec<Point>> {
    let l = d.layers.iter().position(|l| l.name == layer).unwrap_or_else(|| panic!("no layer {layer}"));
    d.entities
        .iter()
        .filter(|e| e.layer == l)
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: false, .. } => Some(points.clone()),
            _ => None,
        })
        .collect()
}

fn to_polyline(p: Point, line: &[Point]) -> f64 {
    line.windows(2).map(|w| distance_to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
}

/// Checks that the path drawn on `layer` through the first and the last of `all` keeps
/// every one of them within the tolerance on paper; returns (drawn vertices, positions).
fn check_path(p: &Products, layer: &str, all: &[Point]) -> (usize, usize) {
    let Picture::Motion(a) = &p.picture else { panic!("a motion") };
    let k = a.base.paper_mm_per_unit.expect("drawn on paper");
    let tol = PATH_TOLERANCE_MM / k;
    let drawn = polylines(&a.base, layer)
        .into_iter()
        .find(|l| l.first() == all.first())
        .unwrap_or_else(|| panic!("no path on {layer} from {:?}", all.first()));
    // A full turn closes the curve: its last vertex is the first position again.
    let mut all = all.to_vec();
    if drawn.last() == all.first() && all.len() > 1 {
        all.push(all[0]);
    }
    assert_eq!(drawn.last(), all.last(), "{layer}: the path ends at the last position");
    // Vertices are computed positions, in order.
    let mut rest = all.iter();
    assert!(drawn.iter().all(|v| rest.any(|q| q == v)), "a vertex of the drawn path is not a position");
    let (worst, at) =
        all.iter().map(|q| (to_polyline(*q, &drawn), *q)).fold((0.0, all[0]), |a, b| if b.0 > a.0 { b } else { a });
    assert!(
        worst <= tol,
        "{layer}: position {at:?} is {:.4} mm of paper from the drawn path (tolerance {PATH_TOLERANCE_MM} mm)",
        worst * k
    );
    (drawn.len(), all.len())
}

#[test]
fn the_coupler_curve_at_3600_positions_is_drawn_within_the_tolerance_on_paper() {
    let p = products("fourbar-chebyshev.toml", &["phi1_deg.step=0.1", "outputs=[\"position\"]"]);
    let all = positions(&p, "M_x", "M_y");
    assert_eq!(all.len(), 3591);
    let (drawn, n) = check_path(&p, "COUPLER_CURVE", &all);
    // The curve's shape on paper sets the vertices, not the number of positions.
    assert!(drawn * 20 < n, "{drawn} vertices for {n} positions");
    // The same curve at 1° needs about as many vertices: the frames grow linearly.
    let coarse = products("fourbar-chebyshev.toml", &["outputs=[\"position\"]"]);
    let (drawn_coarse, _) = check_path(&coarse, "COUPLER_CURVE", &positions(&coarse, "M_x", "M_y"));
    assert!(drawn <= drawn_coarse + drawn_coarse / 4, "{drawn} vertices at 0.1° against {drawn_coarse} at 1°");
}

#[test]
fn the_path_of_m_of_the_four_bar_as_a_linkage_is_drawn_within_the_tolerance_on_paper() {
    let p = products("fourbar-linkage.toml", &[]);
    for point in ["B", "M"] {
        let all = positions(&p, &format!("{point}.x"), &format!("{point}.y"));
        let (drawn, n) = check_path(&p, "TRAJECTORY", &all);
        assert!(drawn < n, "{point}: {drawn} vertices for {n} positions");
    }
}
